"""tf2_py (ROS's Python binding of tf2): exceptions and BufferCore, from diffctl.tf2."""

from diffctl.tf2.exceptions import (
    ConnectivityException,
    ExtrapolationException,
    InvalidArgumentException,
    LookupException,
    TimeoutException,
    TransformException,
)
from diffctl.tf2.ros_io import BufferCore

__all__ = [
    "BufferCore",
    "ConnectivityException",
    "ExtrapolationException",
    "InvalidArgumentException",
    "LookupException",
    "TimeoutException",
    "TransformException",
]
