"""IncludeLaunchDescription and the launch description sources (Python, YAML, XML or any, chosen by file name).

Jazzy's include does not scope what the included file sets; diffctl keeps an include's configurations inside
it (as a `<group>` around it would), which is what files written for ROS expect of their own arguments.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

from diffctl.errors import LaunchError
from diffctl.launch.actions import Action, describe
from diffctl.launch.registry import register
from diffctl.launch.substitutions import SomeSubstitutions, normalize, perform

if TYPE_CHECKING:
    from diffctl.launch.context import Scope
    from diffctl.launch.plan import Step
    from diffctl.launch.resolver import Resolver
    from diffctl.launch.yaml_frontend import Entity


class LaunchDescriptionSource:
    """Where an included description comes from (Python, YAML or XML, chosen by the file's name)."""

    def __init__(self, launch_file_path: SomeSubstitutions) -> None:
        self.location = normalize(launch_file_path)


PythonLaunchDescriptionSource = LaunchDescriptionSource
AnyLaunchDescriptionSource = LaunchDescriptionSource
FrontendLaunchDescriptionSource = LaunchDescriptionSource
YAMLLaunchDescriptionSource = LaunchDescriptionSource
XMLLaunchDescriptionSource = LaunchDescriptionSource


@register
class IncludeLaunchDescription(Action):
    """Include another launch file with arguments; what it sets stays inside it."""

    frontend_tags = ("include",)
    frontend_attrs = ("file", "arg")

    def __init__(
        self,
        launch_description_source: LaunchDescriptionSource | SomeSubstitutions,
        *,
        launch_arguments: Iterable[tuple[SomeSubstitutions, SomeSubstitutions]]
        | Mapping[str, SomeSubstitutions]
        | None = None,
        **kw: Any,
    ) -> None:
        super().__init__(**kw)
        if isinstance(launch_description_source, LaunchDescriptionSource):
            self.location = launch_description_source.location
        else:
            self.location = normalize(launch_description_source)
        pairs = launch_arguments.items() if isinstance(launch_arguments, Mapping) else (launch_arguments or [])
        self.launch_arguments = [(normalize(k), normalize(v)) for k, v in pairs]

    def label(self) -> str:
        return f"include {describe(self.location)}"

    def visit(self, r: Resolver, scope: Scope) -> list[Step]:
        path = Path(perform(self.location, scope))
        if not path.is_absolute() and scope.launch_file:
            beside = Path(scope.launch_file).parent / path
            path = beside if beside.exists() else path
        path = path.resolve()
        if str(path) in scope.includes:
            chain = " → ".join(Path(p).name for p in (*scope.includes, str(path)))
            raise LaunchError(f"include cycle: {chain}")
        if not path.is_file():
            raise LaunchError(f"included launch file {path} does not exist")
        inner = scope.child()
        inner.launch_file = str(path)
        inner.includes = (*scope.includes, str(path))
        for key, value in self.launch_arguments:
            inner.configurations[perform(key, scope)] = perform(value, scope)
        return r.include(path, inner)

    @classmethod
    def from_entity(cls, e: Entity) -> Action:
        args = [
            (a.text("name", required=True), a.text("value", required=True)) for a in e.items("arg", ("name", "value"))
        ]
        return cls(e.text("file", required=True), launch_arguments=args)
