"""SetROSLogDir (`set_ros_log_dir`): ROS_LOG_DIR for the processes started after it."""

from __future__ import annotations

import os
from typing import Any

from diffctl.launch.action import Action
from diffctl.launch.frontend import Entity, Parser, expose_action
from diffctl.launch.launch_context import LaunchContext
from diffctl.launch.some_substitutions_type import SomeSubstitutionsType
from diffctl.launch.substitution import Substitution
from diffctl.launch.utilities import normalize_to_list_of_substitutions, perform_substitutions


@expose_action("set_ros_log_dir")
class SetROSLogDir(Action):
    """Set ROS_LOG_DIR in the launch's environment: an absolute directory as given, a relative one under the
    current log directory (ROS_LOG_DIR, else where the client library logs). A scoped GroupAction (or
    Push/PopEnvironment) limits it; nodes already running in a container keep theirs."""

    def __init__(self, new_log_dir: SomeSubstitutionsType, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.__log_dir = normalize_to_list_of_substitutions(new_log_dir)

    @classmethod
    def parse(cls, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
        _, kwargs = super().parse(entity, parser)
        kwargs["new_log_dir"] = parser.parse_substitution(entity.get_attr("new_log_dir"))
        return cls, kwargs

    @property
    def log_dir(self) -> list[Substitution]:
        return self.__log_dir

    def execute(self, context: LaunchContext) -> None:
        from diffctl.client.ros_logging import get_logging_directory

        environment = context.environment
        current = environment.get("ROS_LOG_DIR") or str(get_logging_directory())
        log_dir = os.path.join(current, perform_substitutions(context, self.log_dir))
        assert os.path.isabs(log_dir), log_dir
        environment["ROS_LOG_DIR"] = log_dir
