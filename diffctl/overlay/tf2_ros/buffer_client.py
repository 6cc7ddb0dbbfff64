"""tf2_ros.buffer_client (diffctl: diffctl.tf2.buffer_client)."""

from diffctl.tf2.buffer_client import BufferClient  # noqa: F401
