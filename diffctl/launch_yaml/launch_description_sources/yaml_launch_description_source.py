"""`YAMLLaunchDescriptionSource`: a YAML launch file."""

from __future__ import annotations

from diffctl.launch.launch_description_sources.frontend_launch_description_source import (
    FrontendLaunchDescriptionSource,
)
from diffctl.launch.some_substitutions_type import SomeSubstitutionsType

from ..parser import Parser


class YAMLLaunchDescriptionSource(FrontendLaunchDescriptionSource):
    """The launch description of a `.launch.yaml` file (path may hold substitutions; relative to the cwd)."""

    def __init__(self, launch_file_path: SomeSubstitutionsType) -> None:
        super().__init__(launch_file_path, method='interpreted YAML launch file', parser=Parser)
