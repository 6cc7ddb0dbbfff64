"""tf2_ros (Python): Buffer, TransformListener, the broadcasters and tf2's exceptions, from diffctl.tf2."""

from diffctl.tf2.exceptions import (
    ConnectivityException,
    ExtrapolationException,
    InvalidArgumentException,
    LookupException,
    TimeoutException,
    TransformException,
)
from diffctl.tf2.ros_io import (
    Buffer,
    BufferCore,
    BufferInterface,
    ConvertRegistration,
    NotImplementedException,
    StaticTransformBroadcaster,
    TransformBroadcaster,
    TransformListener,
    TransformRegistration,
    TypeException,
    convert,
)

__all__ = [
    "Buffer",
    "BufferCore",
    "BufferInterface",
    "ConnectivityException",
    "ConvertRegistration",
    "ExtrapolationException",
    "InvalidArgumentException",
    "LookupException",
    "NotImplementedException",
    "StaticTransformBroadcaster",
    "TimeoutException",
    "TransformBroadcaster",
    "TransformException",
    "TransformListener",
    "TransformRegistration",
    "TypeException",
    "convert",
]
