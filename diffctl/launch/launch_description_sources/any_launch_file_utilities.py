"""Loading a launch file of any kind."""

from __future__ import annotations

import os
from typing import TYPE_CHECKING

from ..frontend.parser import Parser
from ..invalid_launch_file_error import InvalidLaunchFileError
from .frontend_launch_file_utilities import get_launch_description_from_frontend_launch_file
from .python_launch_file_utilities import get_launch_description_from_python_launch_file

if TYPE_CHECKING:
    from ..launch_description import LaunchDescription


def get_launch_description_from_any_launch_file(
    launch_file_path: str, *, parser: type[Parser] = Parser
) -> LaunchDescription:
    """The launch description of a file: Python for `.py`, otherwise the markup frontends then Python.

    When no loader succeeds, InvalidLaunchFileError carries what each raised.
    """
    name = os.path.basename(launch_file_path)
    extension = os.path.splitext(name)[1][1:]
    if extension == 'py':
        loaders = [get_launch_description_from_python_launch_file, get_launch_description_from_frontend_launch_file]
    else:
        loaders = [get_launch_description_from_frontend_launch_file, get_launch_description_from_python_launch_file]
        if not Parser.is_filename_valid(name):
            extension = ''
    errors = []
    for loader in loaders:
        try:
            return loader(launch_file_path)
        except Exception as exc:
            errors.append(exc)
    raise InvalidLaunchFileError(extension, likely_errors=errors)
