"""rclpy.action.server, from diffctl.client.action.server."""

from diffctl.client.action.server import (  # noqa: F401
    ActionServer,
    CancelResponse,
    GoalEvent,
    GoalResponse,
    ServerGoalHandle,
    default_cancel_callback,
    default_goal_callback,
    default_handle_accepted_callback,
)
from diffctl.client.exceptions import RCLError  # noqa: F401
