"""`FrontendLaunchDescriptionSource`: a markup launch file."""

from __future__ import annotations

from typing import TYPE_CHECKING

from ..frontend.parser import Parser
from ..launch_description_source import LaunchDescriptionSource
from .frontend_launch_file_utilities import get_launch_description_from_frontend_launch_file

if TYPE_CHECKING:
    from ..some_substitutions_type import SomeSubstitutionsType


class FrontendLaunchDescriptionSource(LaunchDescriptionSource):
    """The launch description of a markup file (XML, YAML, …), loaded when first needed."""

    def __init__(
        self,
        launch_file_path: SomeSubstitutionsType,
        *,
        method: str = 'interpreted frontend launch file',
        parser: type[Parser] = Parser,
    ) -> None:
        super().__init__(None, launch_file_path, method)
        self._parser = parser

    def _get_launch_description(self, location):
        return get_launch_description_from_frontend_launch_file(location, parser=self._parser)
