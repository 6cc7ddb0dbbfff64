"""rclpy.destroyable (diffctl: diffctl.client.destroyable)."""

from diffctl.client.destroyable import DestroyableType  # noqa: F401
