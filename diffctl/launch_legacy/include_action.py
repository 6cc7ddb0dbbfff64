"""IncludeLaunchDescription and the launch description sources (Python, YAML, XML or any, chosen by file name).

As Jazzy's, an include is not scoped: its arguments become launch configurations of the including file, and
what the included file declares, sets and changes in the environment stays visible after it (wrap it in a
GroupAction to scope it). The included file becomes the current launch file for what follows in the same
visit, as ROS's locals do.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

from diffctl.errors import LaunchError
from diffctl.launch_legacy.actions import Action, describe
from diffctl.launch_legacy.registry import register
from diffctl.launch_legacy.substitutions import SomeSubstitutions, normalize, perform

if TYPE_CHECKING:
    from diffctl.launch_legacy.context import Scope
    from diffctl.launch_legacy.yaml_frontend import Entity


class LaunchDescriptionSource:
    """Where an included description comes from (Python, YAML or XML, chosen by the file's name)."""

    def __init__(self, launch_file_path: Any) -> None:
        from diffctl.launch_legacy.actions import LaunchDescription

        self.description = launch_file_path if isinstance(launch_file_path, LaunchDescription) else None
        self.location = normalize("<script>" if self.description is not None else launch_file_path)


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
        from diffctl.launch_legacy.actions import LaunchDescription

        self.description: LaunchDescription | None = None
        if isinstance(launch_description_source, LaunchDescription):
            launch_description_source = LaunchDescriptionSource(launch_description_source)
        if isinstance(launch_description_source, LaunchDescriptionSource):
            self.location = launch_description_source.location
            self.description = launch_description_source.description
        else:
            self.location = normalize(launch_description_source)
        pairs = launch_arguments.items() if isinstance(launch_arguments, Mapping) else (launch_arguments or [])
        self.launch_arguments = [(normalize(k), normalize(v)) for k, v in pairs]

    def label(self) -> str:
        return f"include {describe(self.location)}"

    def execute(self, context: Scope) -> list[Action] | None:
        from diffctl.launch_legacy.actions import SetLaunchConfiguration

        scope = context
        if self.description is not None:
            entities: list[Action] = list(self.description.entities)
        else:
            path = Path(perform(self.location, scope))
            if not path.is_absolute() and scope.launch_file:
                beside = Path(scope.launch_file).parent / path
                path = beside if beside.exists() else path
            path = path.resolve()
            stack = scope.engine.include_stack
            if str(path) in stack:
                chain = " → ".join(Path(p).name for p in (*stack, str(path)))
                raise LaunchError(f"include cycle: {chain}")
            if not path.is_file():
                raise LaunchError(f"included launch file {path} does not exist")
            entities = scope.engine.include(path)
            scope.extend_locals({"current_launch_file_path": str(path)})
        given = [perform(k, scope) for k, _ in self.launch_arguments]
        _check_required(entities, given)
        sets: list[Action] = []
        for key, value in self.launch_arguments:
            action = SetLaunchConfiguration(key, value)
            action.where = self.where
            sets.append(action)
        return [*sets, *entities]

    @classmethod
    def from_entity(cls, e: Entity) -> Action:
        args = [
            (a.text("name", required=True), a.text("value", required=True)) for a in e.items("arg", ("name", "value"))
        ]
        return cls(e.text("file", required=True), launch_arguments=args)


def _check_required(entities: list[Any], given: list[str]) -> None:
    """As Jazzy: every unconditional argument without a default must be passed by this include (or by an
    include inside it), whatever the including file's own configurations hold."""
    from diffctl.launch_legacy.actions import DeclareLaunchArgument, GroupAction, LaunchDescription

    passed = set(given)
    declared: list[DeclareLaunchArgument] = []

    def walk(items: list[Any]) -> None:
        for item in items:
            if getattr(item, "condition", None) is not None:
                continue
            if isinstance(item, DeclareLaunchArgument):
                declared.append(item)
            elif isinstance(item, IncludeLaunchDescription):
                passed.update(str(describe(k)) for k, _ in item.launch_arguments)
            elif isinstance(item, (GroupAction, LaunchDescription)):
                walk(item.describe_sub_entities())

    walk(entities)
    for arg in declared:
        if arg.default_value is None and arg.name not in passed:
            raise LaunchError(
                f"Included launch description missing required argument {arg.name!r} "
                f"(description: {arg.description!r}), given: [{', '.join(repr(g) for g in given)}]",
                hint=f"pass it in the include: {arg.name}:=VALUE",
            )
