"""tf2_ros.buffer_client (diffctl: diffctl.tf2.buffer_client)."""

# ROS's buffer_client imports rclpy.action.client at load: `rclpy.action` is reachable after `import tf2_ros`.
import rclpy.action.client  # noqa: F401

from diffctl.tf2.buffer_client import BufferClient  # noqa: F401
