"""The one table of type pairs the bridge can move, from ros_gz_bridge's Jazzy mapping table (mappings.py).

A pair is looked up by (ROS type, gz type); `ignition.msgs.*` is read as `gz.msgs.*` and `pkg/Type` as
`pkg/msg/Type`, as ros_gz_bridge accepts both spellings.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from diffctl.bridge import conversions as c
from diffctl.bridge import covariance_conversions as cv
from diffctl.bridge import geometry_conversions as g
from diffctl.bridge import gps_actuator_conversions as ga
from diffctl.bridge import gz_interfaces_conversions as gi
from diffctl.bridge import gz_scene_conversions as gs
from diffctl.bridge import sensor_conversions as sc
from diffctl.bridge import std_conversions as st
from diffctl.bridge import vision_conversions as vc
from diffctl.errors import MessageError


@dataclass(frozen=True)
class TypePair:
    ros_type: str
    gz_type: str
    to_ros: Callable[[dict[str, Any]], Any]
    to_gz: Callable[[Any], dict[str, Any]]

    def convert_to_ros(self, gz_msg: dict[str, Any]) -> Any:
        try:
            return self.to_ros(gz_msg)
        except MessageError:
            raise
        except (TypeError, ValueError, KeyError, AttributeError, OverflowError) as e:
            raise MessageError(f"malformed {self.gz_type}: {e}") from None

    def convert_to_gz(self, ros_msg: Any) -> dict[str, Any]:
        try:
            return self.to_gz(ros_msg)
        except MessageError:
            raise
        except (TypeError, ValueError, KeyError, AttributeError, OverflowError) as e:
            raise MessageError(f"malformed {self.ros_type}: {e}") from None


TYPE_PAIRS: tuple[TypePair, ...] = (
    TypePair("rosgraph_msgs/msg/Clock", "gz.msgs.Clock", c.clock_to_ros, c.clock_to_gz),
    TypePair("geometry_msgs/msg/Twist", "gz.msgs.Twist", c.twist_to_ros, c.twist_to_gz),
    TypePair("geometry_msgs/msg/TwistStamped", "gz.msgs.Twist", c.twist_stamped_to_ros, c.twist_stamped_to_gz),
    TypePair("nav_msgs/msg/Odometry", "gz.msgs.Odometry", c.odometry_to_ros, c.odometry_to_gz),
    TypePair("sensor_msgs/msg/JointState", "gz.msgs.Model", c.model_to_joint_state, c.joint_state_to_model),
    TypePair("tf2_msgs/msg/TFMessage", "gz.msgs.Pose_V", c.pose_v_to_tf, c.tf_to_pose_v),
    TypePair("sensor_msgs/msg/LaserScan", "gz.msgs.LaserScan", sc.laser_scan_to_ros, sc.laser_scan_to_gz),
    TypePair("sensor_msgs/msg/Imu", "gz.msgs.IMU", sc.imu_to_ros, sc.imu_to_gz),
    TypePair("sensor_msgs/msg/Image", "gz.msgs.Image", sc.image_to_ros, sc.image_to_gz),
    TypePair("sensor_msgs/msg/CameraInfo", "gz.msgs.CameraInfo", sc.camera_info_to_ros, sc.camera_info_to_gz),
    TypePair("sensor_msgs/msg/PointCloud2", "gz.msgs.PointCloudPacked", sc.point_cloud_to_ros, sc.point_cloud_to_gz),
    TypePair("sensor_msgs/msg/NavSatFix", "gz.msgs.NavSat", sc.nav_sat_to_ros, sc.nav_sat_fix_to_gz),
    TypePair("sensor_msgs/msg/MagneticField", "gz.msgs.Magnetometer", sc.magnetometer_to_ros, sc.magnetic_field_to_gz),
    TypePair(
        "sensor_msgs/msg/FluidPressure", "gz.msgs.FluidPressure", sc.fluid_pressure_to_ros, sc.fluid_pressure_to_gz
    ),
    TypePair("sensor_msgs/msg/BatteryState", "gz.msgs.BatteryState", sc.battery_state_to_ros, sc.battery_state_to_gz),
    TypePair("geometry_msgs/msg/Pose", "gz.msgs.Pose", c.pose_to_ros, c.pose_to_gz),
    TypePair("geometry_msgs/msg/PoseStamped", "gz.msgs.Pose", c.pose_stamped_to_ros, c.pose_stamped_to_gz),
    TypePair("geometry_msgs/msg/PoseArray", "gz.msgs.Pose_V", g.pose_v_to_pose_array, g.pose_array_to_pose_v),
    TypePair("geometry_msgs/msg/Transform", "gz.msgs.Pose", g.pose_to_transform, g.transform_to_pose),
    TypePair(
        "geometry_msgs/msg/TransformStamped", "gz.msgs.Pose", g.pose_to_transform_stamped, g.transform_stamped_to_pose
    ),
    TypePair(
        "geometry_msgs/msg/Vector3",
        "gz.msgs.Vector3d",
        g.vector3d_to_ros("geometry_msgs/msg/Vector3"),
        g.vector3d_to_gz,
    ),
    TypePair(
        "geometry_msgs/msg/Point", "gz.msgs.Vector3d", g.vector3d_to_ros("geometry_msgs/msg/Point"), g.vector3d_to_gz
    ),
    TypePair("geometry_msgs/msg/Wrench", "gz.msgs.Wrench", g.wrench_to_ros, g.wrench_to_gz),
    TypePair("geometry_msgs/msg/WrenchStamped", "gz.msgs.Wrench", g.wrench_stamped_to_ros, g.wrench_stamped_to_gz),
    TypePair(
        "std_msgs/msg/Float64",
        "gz.msgs.Double",
        c.scalar_to_ros("std_msgs/msg/Float64", float),
        c.scalar_to_gz(float, finite=True),
    ),
    TypePair(
        "std_msgs/msg/Float32",
        "gz.msgs.Float",
        c.scalar_to_ros("std_msgs/msg/Float32", float),
        c.scalar_to_gz(float, finite=True),
    ),
    TypePair("std_msgs/msg/Bool", "gz.msgs.Boolean", c.scalar_to_ros("std_msgs/msg/Bool", bool), c.scalar_to_gz(bool)),
    TypePair("std_msgs/msg/Int32", "gz.msgs.Int32", c.scalar_to_ros("std_msgs/msg/Int32", int), c.scalar_to_gz(int)),
    TypePair("std_msgs/msg/UInt32", "gz.msgs.UInt32", c.scalar_to_ros("std_msgs/msg/UInt32", int), c.scalar_to_gz(int)),
    TypePair(
        "std_msgs/msg/String", "gz.msgs.StringMsg", c.scalar_to_ros("std_msgs/msg/String", str), c.scalar_to_gz(str)
    ),
    TypePair("std_msgs/msg/Empty", "gz.msgs.Empty", c.empty_to_ros, c.empty_to_gz),
    TypePair("builtin_interfaces/msg/Time", "gz.msgs.Time", st.time_msg_to_ros, st.time_msg_to_gz),
    TypePair("std_msgs/msg/Header", "gz.msgs.Header", st.header_msg_to_ros, st.header_msg_to_gz),
    TypePair("std_msgs/msg/ColorRGBA", "gz.msgs.Color", st.color_to_ros, st.color_to_gz),
    TypePair("geometry_msgs/msg/Quaternion", "gz.msgs.Quaternion", st.quaternion_msg_to_ros, st.quaternion_msg_to_gz),
    TypePair("sensor_msgs/msg/Joy", "gz.msgs.Joy", st.joy_to_ros, st.joy_to_gz),
    TypePair(
        "trajectory_msgs/msg/JointTrajectory",
        "gz.msgs.JointTrajectory",
        st.joint_trajectory_to_ros,
        st.joint_trajectory_to_gz,
    ),
    TypePair("rcl_interfaces/msg/ParameterValue", "gz.msgs.Any", st.any_to_parameter_value, st.parameter_value_to_any),
    TypePair(
        "geometry_msgs/msg/PoseWithCovariance",
        "gz.msgs.PoseWithCovariance",
        cv.pose_with_covariance_to_ros,
        cv.pose_with_covariance_to_gz,
    ),
    TypePair(
        "geometry_msgs/msg/PoseWithCovarianceStamped",
        "gz.msgs.PoseWithCovariance",
        cv.pose_with_covariance_stamped_to_ros,
        cv.pose_with_covariance_stamped_to_gz,
    ),
    TypePair(
        "geometry_msgs/msg/TwistWithCovariance",
        "gz.msgs.TwistWithCovariance",
        cv.twist_with_covariance_to_ros,
        cv.twist_with_covariance_to_gz,
    ),
    TypePair(
        "geometry_msgs/msg/TwistWithCovarianceStamped",
        "gz.msgs.TwistWithCovariance",
        cv.twist_with_covariance_stamped_to_ros,
        cv.twist_with_covariance_stamped_to_gz,
    ),
    TypePair("ros_gz_interfaces/msg/Altimeter", "gz.msgs.Altimeter", gi.altimeter_to_ros, gi.altimeter_to_gz),
    TypePair("ros_gz_interfaces/msg/Entity", "gz.msgs.Entity", gi.entity_to_ros, gi.entity_to_gz),
    TypePair(
        "ros_gz_interfaces/msg/EntityWrench", "gz.msgs.EntityWrench", gi.entity_wrench_to_ros, gi.entity_wrench_to_gz
    ),
    TypePair("ros_gz_interfaces/msg/JointWrench", "gz.msgs.JointWrench", gi.joint_wrench_to_ros, gi.joint_wrench_to_gz),
    TypePair("ros_gz_interfaces/msg/Contact", "gz.msgs.Contact", gi.contact_to_ros, gi.contact_to_gz),
    TypePair("ros_gz_interfaces/msg/Contacts", "gz.msgs.Contacts", gi.contacts_to_ros, gi.contacts_to_gz),
    TypePair("ros_gz_interfaces/msg/Dataframe", "gz.msgs.Dataframe", gi.dataframe_to_ros, gi.dataframe_to_gz),
    TypePair("ros_gz_interfaces/msg/Float32Array", "gz.msgs.Float_V", gi.float_v_to_ros, gi.float_v_to_gz),
    TypePair("ros_gz_interfaces/msg/StringVec", "gz.msgs.StringMsg_V", gi.string_v_to_ros, gi.string_v_to_gz),
    TypePair("ros_gz_interfaces/msg/ParamVec", "gz.msgs.Param", gi.param_to_ros, gi.param_to_gz),
    TypePair("ros_gz_interfaces/msg/ParamVec", "gz.msgs.Param_V", gi.param_v_to_ros, gi.param_v_to_gz),
    TypePair("ros_gz_interfaces/msg/Light", "gz.msgs.Light", gs.light_to_ros, gs.light_to_gz),
    TypePair(
        "ros_gz_interfaces/msg/MaterialColor",
        "gz.msgs.MaterialColor",
        gs.material_color_to_ros,
        gs.material_color_to_gz,
    ),
    TypePair("ros_gz_interfaces/msg/SensorNoise", "gz.msgs.SensorNoise", gs.sensor_noise_to_ros, gs.sensor_noise_to_gz),
    TypePair("ros_gz_interfaces/msg/TrackVisual", "gz.msgs.TrackVisual", gs.track_visual_to_ros, gs.track_visual_to_gz),
    TypePair("ros_gz_interfaces/msg/GuiCamera", "gz.msgs.GUICamera", gs.gui_camera_to_ros, gs.gui_camera_to_gz),
    TypePair("ros_gz_interfaces/msg/VideoRecord", "gz.msgs.VideoRecord", gs.video_record_to_ros, gs.video_record_to_gz),
    TypePair(
        "nav_msgs/msg/Odometry",
        "gz.msgs.OdometryWithCovariance",
        cv.odometry_with_covariance_to_ros,
        cv.odometry_with_covariance_to_gz,
    ),
    TypePair("actuator_msgs/msg/Actuators", "gz.msgs.Actuators", ga.actuators_to_ros, ga.actuators_to_gz),
    TypePair("gps_msgs/msg/GPSFix", "gz.msgs.NavSat", ga.gps_fix_to_ros, ga.gps_fix_to_gz),
    TypePair(
        "vision_msgs/msg/Detection2D", "gz.msgs.AnnotatedAxisAligned2DBox", vc.detection2d_to_ros, vc.detection2d_to_gz
    ),
    TypePair(
        "vision_msgs/msg/Detection2DArray",
        "gz.msgs.AnnotatedAxisAligned2DBox_V",
        vc.detection2d_array_to_ros,
        vc.detection2d_array_to_gz,
    ),
    TypePair(
        "vision_msgs/msg/Detection3D", "gz.msgs.AnnotatedOriented3DBox", vc.detection3d_to_ros, vc.detection3d_to_gz
    ),
    TypePair(
        "vision_msgs/msg/Detection3DArray",
        "gz.msgs.AnnotatedOriented3DBox_V",
        vc.detection3d_array_to_ros,
        vc.detection3d_array_to_gz,
    ),
)

_BY_KEY = {(p.ros_type, p.gz_type): p for p in TYPE_PAIRS}


def normalize_ros_type(name: str) -> str:
    parts = name.strip().strip("/").split("/")
    if len(parts) == 2:
        return f"{parts[0]}/msg/{parts[1]}"
    return "/".join(parts)


def normalize_gz_type(name: str) -> str:
    name = name.strip()
    if name.startswith("ignition.msgs."):
        return "gz.msgs." + name[len("ignition.msgs.") :]
    return name


def lookup(ros_type: str, gz_type: str) -> TypePair | None:
    return _BY_KEY.get((normalize_ros_type(ros_type), normalize_gz_type(gz_type)))


def describe_pairs() -> str:
    return ", ".join(f"{p.ros_type}<->{p.gz_type}" for p in TYPE_PAIRS)
