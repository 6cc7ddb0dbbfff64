"""Joint limits enforced on the commands controllers write (ros2_control's joint_limits package, Jazzy).

With the controller manager's `enforce_command_limits` (false by default, read-only), the resource manager gives
every `<ros2_control>` joint a limiter built from the robot description (joint_limits_urdf.py): a
JointSaturationLimiter, or a JointSoftLimiter when the URDF joint has a `<safety_controller>`. A command is
limited when the controller writes it (with the manager's period) and again, over each joint's claimed commands,
after all controllers ran and before the hardware writes (with the cycle's period). joint_limits_helpers.py holds
the bounds; the limiters only clamp to them and remember the previous command.
"""

from diffctl.control.joint_limits.joint_limits import JointControlInterfacesData, JointLimits, SoftJointLimits
from diffctl.control.joint_limits.joint_saturation_limiter import JointSaturationLimiter
from diffctl.control.joint_limits.joint_soft_limiter import JointSoftLimiter

__all__ = [
    "JointControlInterfacesData",
    "JointLimits",
    "JointSaturationLimiter",
    "JointSoftLimiter",
    "SoftJointLimits",
]
