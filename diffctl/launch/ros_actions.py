"""ROS scope actions of launch_ros: SetParameter, SetParametersFromFile, SetRemap, SetUseSimTime (`set_parameter`,
`set_parameters_from_file`, `set_remap`, `set_use_sim_time`).

They change the scope, so every node started after them in the same scope gets the parameter or remapping
(before its own), and a scoped group keeps them inside, as launch_ros does.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

from diffctl.errors import LaunchError
from diffctl.launch.actions import Action, describe
from diffctl.launch.parameters import ParameterValue, _param_value
from diffctl.launch.registry import register
from diffctl.launch.substitutions import SomeSubstitutions, normalize, perform

if TYPE_CHECKING:
    from diffctl.launch.context import Scope
    from diffctl.launch.plan import Step
    from diffctl.launch.resolver import Resolver
    from diffctl.launch.yaml_frontend import Entity


@register
class SetParameter(Action):
    """A parameter for every node after it in this scope (ROS passes it as `-p name:=value`)."""

    frontend_tags = ("set_parameter",)
    frontend_attrs = ("name", "value")

    def __init__(self, name: SomeSubstitutions, value: Any, **kw: Any) -> None:
        super().__init__(**kw)
        self.name = normalize(name)
        self.value = value if isinstance(value, ParameterValue) or not isinstance(value, str) else normalize(value)

    def label(self) -> str:
        return f"set_parameter {describe(self.name)}"

    def visit(self, r: Resolver, scope: Scope) -> list[Step]:
        scope.global_params[perform(self.name, scope)] = _param_value(self.value, scope)
        return []

    @classmethod
    def from_entity(cls, e: Entity) -> Action:
        if not e.has("value"):
            raise e.error("`set_parameter` needs `value`")
        return cls(e.text("name", required=True), e.value("value"))


@register
class SetUseSimTime(Action):
    """`set_use_sim_time`: SetParameter('use_sim_time', value) for every node after it."""

    frontend_tags = ("set_use_sim_time",)
    frontend_attrs = ("value",)

    def __init__(self, value: bool | SomeSubstitutions, **kw: Any) -> None:
        super().__init__(**kw)
        self.value = value

    def visit(self, r: Resolver, scope: Scope) -> list[Step]:
        from diffctl.launch.conditions import truth

        value = self.value if isinstance(self.value, bool) else truth(perform(self.value, scope), "use_sim_time")
        scope.global_params["use_sim_time"] = value
        return []

    @classmethod
    def from_entity(cls, e: Entity) -> Action:
        return cls(e.text("value", required=True))


@register
class SetParametersFromFile(Action):
    """A parameter file for every node after it in this scope (before each node's own parameters)."""

    frontend_tags = ("set_parameters_from_file",)
    frontend_attrs = ("filename",)

    def __init__(self, filename: SomeSubstitutions, **kw: Any) -> None:
        super().__init__(**kw)
        self.filename = normalize(filename)

    def label(self) -> str:
        return f"set_parameters_from_file {describe(self.filename)}"

    def visit(self, r: Resolver, scope: Scope) -> list[Step]:
        path = Path(perform(self.filename, scope))
        if not path.is_absolute() and scope.launch_file:
            path = Path(scope.launch_file).parent / path
        if not path.is_file():
            raise LaunchError(f"parameter file {path} does not exist")
        scope.param_files.append(str(path.resolve()))
        return []

    @classmethod
    def from_entity(cls, e: Entity) -> Action:
        return cls(e.text("filename", required=True))


@register
class SetRemap(Action):
    """A remapping for every node after it in this scope (before each node's own remappings)."""

    frontend_tags = ("set_remap",)
    frontend_attrs = ("from", "to")

    def __init__(self, src: SomeSubstitutions, dst: SomeSubstitutions, **kw: Any) -> None:
        super().__init__(**kw)
        self.src, self.dst = normalize(src), normalize(dst)

    def label(self) -> str:
        return f"set_remap {describe(self.src)}:={describe(self.dst)}"

    def visit(self, r: Resolver, scope: Scope) -> list[Step]:
        scope.remaps.append((perform(self.src, scope), perform(self.dst, scope)))
        return []

    @classmethod
    def from_entity(cls, e: Entity) -> Action:
        return cls(e.text("from", required=True), e.text("to", required=True))
