"""rclpy.topic_endpoint_info (diffctl: diffctl.client.topic_endpoint_info)."""

from diffctl.client.topic_endpoint_info import *  # noqa: F403
