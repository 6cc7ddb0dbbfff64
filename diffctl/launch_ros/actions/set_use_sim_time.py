"""SetUseSimTime (`set_use_sim_time`): the launch process's own ROS node follows /clock (RosTimer then counts
simulated time). The nodes launch starts are not affected: give them `use_sim_time` as a parameter."""

from __future__ import annotations

from typing import Any

from diffctl.launch.action import Action
from diffctl.launch.frontend import Entity, Parser, expose_action
from diffctl.launch.launch_context import LaunchContext
from diffctl.launch.utilities.type_utils import normalize_typed_substitution, perform_typed_substitution

from ..ros_adapters import get_ros_node


@expose_action("set_use_sim_time")
class SetUseSimTime(Action):
    """Set `use_sim_time` on the launch's ROS node (made now if the launch had none)."""

    def __init__(self, value: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.__value = value

    @classmethod
    def parse(cls, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
        _, kwargs = super().parse(entity, parser)
        kwargs["value"] = parser.parse_substitution(entity.get_attr("value"))
        return cls, kwargs

    @property
    def value(self) -> Any:
        return self.__value

    def execute(self, context: LaunchContext) -> None:
        from diffctl.client.parameter import Parameter

        value = perform_typed_substitution(context, normalize_typed_substitution(self.value, bool), bool)
        node = get_ros_node(context)
        node.set_parameters([Parameter("use_sim_time", Parameter.Type.BOOL, value)])
        if node.get_parameter("use_sim_time").get_parameter_value().bool_value != value:
            raise RuntimeError("Failed to set use_sim_time parameter")
