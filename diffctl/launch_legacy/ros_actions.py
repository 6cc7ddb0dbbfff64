"""ROS scope actions of launch_ros: SetParameter, SetParametersFromFile, SetRemap, SetUseSimTime (`set_parameter`,
`set_parameters_from_file`, `set_remap`, `set_use_sim_time`).

They append to the launch configurations `global_params` / `ros_remaps` as launch_ros does, so every node
started after them gets the parameter or remapping (before its own); a scoped group keeps them inside unless
the list existed before the group (Jazzy's shallow copy lets additions leak out then, and so does diffctl).
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

from diffctl.errors import LaunchError
from diffctl.launch_legacy.actions import Action, TimerAction, describe
from diffctl.launch_legacy.parameters import ParameterValue, _param_value
from diffctl.launch_legacy.registry import register
from diffctl.launch_legacy.substitutions import SomeSubstitutions, normalize, perform

if TYPE_CHECKING:
    from diffctl.launch_legacy.context import Scope
    from diffctl.launch_legacy.yaml_frontend import Entity


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

    def execute(self, context: Scope) -> list[Action] | None:
        value = _param_value(self.value, context)
        context.global_params.append((perform(self.name, context), value if isinstance(value, str) else str(value)))
        return None

    @classmethod
    def from_entity(cls, e: Entity) -> Action:
        if not e.has("value"):
            raise e.error("`set_parameter` needs `value`")
        return cls(e.text("name", required=True), e.value("value"))


@register
class SetUseSimTime(Action):
    """`set_use_sim_time`: as launch_ros's, it sets `use_sim_time` of launch's own ROS node (what RosTimer
    would count on), not of the nodes it starts: use `set_parameter` for those."""

    frontend_tags = ("set_use_sim_time",)
    frontend_attrs = ("value",)

    def __init__(self, value: bool | SomeSubstitutions, **kw: Any) -> None:
        super().__init__(**kw)
        self.value = value

    def execute(self, context: Scope) -> list[Action] | None:
        from diffctl.launch_legacy.conditions import truth

        value = self.value if isinstance(self.value, bool) else truth(perform(self.value, context), "use_sim_time")
        context.extend_globals({"use_sim_time": value})
        return None

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

    def execute(self, context: Scope) -> list[Action] | None:
        scope = context
        path = Path(perform(self.filename, scope))
        if not path.is_absolute() and scope.launch_file:
            path = Path(scope.launch_file).parent / path
        if not path.is_file():
            raise LaunchError(f"parameter file {path} does not exist")
        scope.global_params.append(str(path.resolve()))
        return None

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

    def execute(self, context: Scope) -> list[Action] | None:
        context.remaps.append((perform(self.src, context), perform(self.dst, context)))
        return None

    @classmethod
    def from_entity(cls, e: Entity) -> Action:
        return cls(e.text("from", required=True), e.text("to", required=True))


@register
class SetROSLogDir(Action):
    """`set_ros_log_dir`: ROS_LOG_DIR for what starts after it; a relative directory is joined to the current one."""

    frontend_tags = ("set_ros_log_dir",)
    frontend_attrs = ("new_log_dir",)

    def __init__(self, new_log_dir: SomeSubstitutions, **kw: Any) -> None:
        super().__init__(**kw)
        self.new_log_dir = normalize(new_log_dir)

    def label(self) -> str:
        return f"set_ros_log_dir {describe(self.new_log_dir)}"

    def execute(self, context: Scope) -> list[Action] | None:
        import os

        env = context.env
        ros_home = env.get("ROS_HOME") or os.path.join(os.path.expanduser("~"), ".ros")
        current = env.get("ROS_LOG_DIR") or os.path.join(ros_home, "log")
        context.set_env("ROS_LOG_DIR", os.path.join(current, perform(self.new_log_dir, context)))
        return None

    @classmethod
    def from_entity(cls, e: Entity) -> Action:
        return cls(e.text("new_log_dir", required=True))


@register
class RosTimer(TimerAction):
    """`ros_timer`: a TimerAction (launch_ros counts it on its node's ROS clock; here on the wall clock)."""

    frontend_tags = ("ros_timer",)
