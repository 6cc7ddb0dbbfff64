"""rclpy.action.client, from diffctl.client.action.client."""

from diffctl.client.action.client import ActionClient, ClientGoalHandle  # noqa: F401
