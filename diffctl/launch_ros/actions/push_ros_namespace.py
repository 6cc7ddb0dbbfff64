"""PushROSNamespace (`push_ros_namespace`, `push-ros-namespace`): nodes after it in the scope go under it."""

from __future__ import annotations

from typing import Any

from diffctl.client.names import validate_namespace
from diffctl.launch.action import Action
from diffctl.launch.frontend import Entity, Parser, expose_action
from diffctl.launch.launch_context import LaunchContext
from diffctl.launch.some_substitutions_type import SomeSubstitutionsType
from diffctl.launch.substitution import Substitution
from diffctl.launch.substitutions import SubstitutionFailure
from diffctl.launch.utilities import normalize_to_list_of_substitutions, perform_substitutions

from ..utilities import make_namespace_absolute, prefix_namespace


@expose_action("push_ros_namespace")
@expose_action("push-ros-namespace")
class PushROSNamespace(Action):
    """Push a ROS namespace (relative ones join the one already pushed) onto the `ros_namespace` launch
    configuration; a scoped GroupAction pops it, nothing else does."""

    def __init__(self, namespace: SomeSubstitutionsType, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.__namespace = normalize_to_list_of_substitutions(namespace)

    @classmethod
    def parse(cls, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
        _, kwargs = super().parse(entity, parser)
        kwargs["namespace"] = parser.parse_substitution(entity.get_attr("namespace"))
        return cls, kwargs

    @property
    def namespace(self) -> list[Substitution]:
        return self.__namespace

    def execute(self, context: LaunchContext) -> None:
        pushed = perform_substitutions(context, self.namespace)
        previous = context.launch_configurations.get("ros_namespace", None)
        namespace = make_namespace_absolute(prefix_namespace(previous, pushed))
        try:
            validate_namespace(namespace)
        except Exception:
            raise SubstitutionFailure(
                f"The resulting namespace is invalid: [previous_namespace='{previous}', pushed_namespace='{pushed}']"
            ) from None
        context.launch_configurations["ros_namespace"] = namespace
