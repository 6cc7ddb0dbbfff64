"""`PythonLaunchDescriptionSource`: a Python launch file."""

from __future__ import annotations

from typing import TYPE_CHECKING

from ..launch_description_source import LaunchDescriptionSource
from .python_launch_file_utilities import get_launch_description_from_python_launch_file

if TYPE_CHECKING:
    from ..some_substitutions_type import SomeSubstitutionsType


class PythonLaunchDescriptionSource(LaunchDescriptionSource):
    """The launch description of a `.launch.py` file, loaded when first needed (path may hold substitutions)."""

    def __init__(self, launch_file_path: SomeSubstitutionsType) -> None:
        super().__init__(None, launch_file_path, 'interpreted python launch file')

    def _get_launch_description(self, location):
        return get_launch_description_from_python_launch_file(location)
