"""`AnyLaunchDescriptionSource`: a launch file of any kind."""

from __future__ import annotations

from typing import TYPE_CHECKING

from ..launch_description_source import LaunchDescriptionSource
from .any_launch_file_utilities import get_launch_description_from_any_launch_file

if TYPE_CHECKING:
    from ..some_substitutions_type import SomeSubstitutionsType


class AnyLaunchDescriptionSource(LaunchDescriptionSource):
    """The launch description of a file, by its extension first, then as Python, then as markup.

    A relative path is relative to the working directory of the launch.
    """

    def __init__(self, launch_file_path: SomeSubstitutionsType) -> None:
        super().__init__(None, launch_file_path, 'interpreted launch file')

    def _get_launch_description(self, location):
        return get_launch_description_from_any_launch_file(location)
