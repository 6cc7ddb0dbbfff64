"""Launch files of any kind: Python, or one of the markup frontends'."""

from __future__ import annotations

import functools
import os
from typing import TYPE_CHECKING

from .._private.attempts import NoneWorked, first_success
from ..frontend.parser import Parser
from ..invalid_launch_file_error import InvalidLaunchFileError
from .frontend_launch_file_utilities import get_launch_description_from_frontend_launch_file
from .python_launch_file_utilities import get_launch_description_from_python_launch_file

if TYPE_CHECKING:
    from ..launch_description import LaunchDescription


def get_launch_description_from_any_launch_file(
    launch_file_path: str, *, parser: type[Parser] = Parser
) -> LaunchDescription:
    """The launch description of a file: read as Python first for `.py`, by the frontends first otherwise.

    When neither way works, InvalidLaunchFileError carries what each raised.
    """
    base = os.path.basename(launch_file_path)
    extension = os.path.splitext(base)[1][1:]
    as_python = (get_launch_description_from_python_launch_file,)
    as_markup = (get_launch_description_from_frontend_launch_file,)
    attempts = as_python + as_markup if extension == 'py' else as_markup + as_python
    if extension != 'py' and not Parser.is_filename_valid(base):
        extension = ''  # no frontend claims the name: the error says the format is unknown
    try:
        return first_success(functools.partial(attempt, launch_file_path) for attempt in attempts)
    except NoneWorked as tried:
        failures = tried.failures
    raise InvalidLaunchFileError(extension, likely_errors=failures)
