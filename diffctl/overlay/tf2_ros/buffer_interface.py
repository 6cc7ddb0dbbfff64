"""tf2_ros.buffer_interface, from diffctl.tf2."""

from diffctl.tf2.ros_io import (  # noqa: F401
    BufferInterface,
    ConvertRegistration,
    NotImplementedException,
    TransformRegistration,
    TypeException,
    convert,
)
