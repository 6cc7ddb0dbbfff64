"""tf2_ros.buffer_client (diffctl: diffctl.tf2.buffer_client)."""

from diffctl.tf2.buffer_client import BufferClient  # noqa: F401

# ROS's buffer_client imports rclpy.action.client at load: `rclpy.action` is reachable after `import tf2_ros`.
import rclpy.action.client  # noqa: E402, F401
