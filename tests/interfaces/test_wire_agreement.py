"""Wire agreement with the real Jazzy build: CDR bytes from rclpy.serialization.serialize_message equal
diffctl's for messages of many shapes (nested, fixed arrays, strings, sequences, bounded, bytes, bools),
diffctl decodes the real bytes to messages that print as the real ones, and type hashes are rosidl's."""

from __future__ import annotations

import json

from tests.interfaces.programs import run_oracle, run_ours

MESSAGES = r'''
import math
msgs = {}
from geometry_msgs.msg import Twist, PoseWithCovarianceStamped, Polygon, Point32
t = Twist(); t.linear.x = 1.5; t.angular.z = -0.25
msgs['twist'] = t
p = PoseWithCovarianceStamped(); p.header.frame_id = 'map'; p.header.stamp.sec = 5; p.header.stamp.nanosec = 7
p.pose.covariance[0] = 0.1; p.pose.covariance[35] = 2.0; p.pose.pose.orientation.w = 0.5
msgs['pose_cov'] = p
msgs['polygon'] = Polygon(points=[Point32(x=1.0, y=2.0, z=3.0), Point32(x=-1.0)])
from sensor_msgs.msg import LaserScan, Image, JointState, PointCloud2, PointField, NavSatStatus
msgs['scan'] = LaserScan(header=p.header, angle_min=-1.5, angle_max=1.5, ranges=[1.0, 2.5, math.inf],
                         intensities=[0.5], range_max=30.0)
msgs['image'] = Image(height=2, width=3, encoding='mono8', step=3, data=bytes(range(6)), is_bigendian=1)
msgs['joints'] = JointState(name=['left_wheel', 'right'], position=[0.1, -0.2], velocity=[], effort=[3.0, 4.0])
msgs['cloud'] = PointCloud2(height=1, width=2, fields=[PointField(name='x', offset=0, datatype=7, count=1)],
                            is_bigendian=False, point_step=4, row_step=8, data=[1, 2, 3, 4, 5, 6, 7, 8],
                            is_dense=True)
msgs['navsat_status'] = NavSatStatus()
from std_msgs.msg import String, Int8MultiArray, MultiArrayDimension, Char, Byte, Bool, ColorRGBA, Empty
msgs['string'] = String(data='héllo wörld ✓')
msgs['int8multi'] = Int8MultiArray(data=[-128, 0, 127])
msgs['int8multi'].layout.dim = [MultiArrayDimension(label='x', size=3, stride=3)]
msgs['char'] = Char(data=200)
msgs['byte'] = Byte(data=b'\x7f')
msgs['bool'] = Bool(data=True)
msgs['color'] = ColorRGBA(r=0.5, a=1.0)
msgs['empty'] = Empty()
from rcl_interfaces.msg import ParameterDescriptor, ParameterEvent, Parameter, ParameterValue, Log
from rcl_interfaces.msg import FloatingPointRange
msgs['descriptor'] = ParameterDescriptor(name='speed', type=3, description='m/s', read_only=True,
                                         floating_point_range=[FloatingPointRange(from_value=0.0, to_value=2.0)])
pe = ParameterEvent(node='/talker')
pe.new_parameters = [Parameter(name='a', value=ParameterValue(type=7, bool_array_value=[True, False, True])),
                     Parameter(name='b', value=ParameterValue(type=5, byte_array_value=[b'\x01', b'\xff'])),
                     Parameter(name='c', value=ParameterValue(type=9, string_array_value=['x', '', 'yz']))]
msgs['param_event'] = pe
msgs['log'] = Log(level=20, name='talker', msg='hi', file='a.py', function='f', line=3)
from action_msgs.msg import GoalStatusArray, GoalStatus
gs = GoalStatus(status=4)
gs.goal_info.goal_id.uuid = numpy.arange(16, dtype=numpy.uint8)
gs.goal_info.stamp.sec = 9
msgs['goal_status'] = GoalStatusArray(status_list=[gs, GoalStatus()])
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus, KeyValue
msgs['diag'] = DiagnosticArray(status=[DiagnosticStatus(level=b'\x02', name='n', message='m',
                                                        values=[KeyValue(key='k', value='v')])])
from visualization_msgs.msg import Marker
from geometry_msgs.msg import Point
msgs['marker'] = Marker(ns='a', id=3, type=4, points=[Point(x=1.0)], text='t', frame_locked=True)
from nav_msgs.msg import Odometry
o = Odometry(child_frame_id='base_link'); o.twist.twist.linear.x = 0.3; o.twist.covariance[7] = 1.0
msgs['odom'] = o
from std_srvs.srv import SetBool
msgs['setbool_req'] = SetBool.Request(data=True)
msgs['setbool_resp'] = SetBool.Response(success=True, message='ok')
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint
msgs['traj'] = JointTrajectory(joint_names=['a'], points=[JointTrajectoryPoint(positions=[1.0, 2.0])])
'''


def same_wire(ours_hex: str, real_hex: str) -> bool:
    """Equal bytes, but for padding: Fast CDR leaves alignment padding uninitialized (any value) where diffctl
    writes zeros, and its serialize_message counts the alignment of empty sequences into the length (bytes
    past the data, which every reader ignores). A data byte that differed would also fail the decoding
    comparison."""
    ours, real = bytes.fromhex(ours_hex), bytes.fromhex(real_hex)
    return len(ours) <= len(real) and all(a == b or a == 0 for a, b in zip(ours, real[: len(ours)], strict=True))


def test_serialized_bytes_and_decoding_match_the_real_rclpy() -> None:
    oracle = run_oracle(MESSAGES + r'''
from rclpy.serialization import serialize_message
for k, m in msgs.items():
    obs(k, lambda m=m: serialize_message(m).hex())
    obs(k + ' repr', lambda m=m: m)
''')
    hexes = {k: v[1] for k, v in oracle.items() if not k.endswith(" repr")}
    assert all(v[0] == "ok" for v in oracle.values()), oracle
    ours = run_ours(MESSAGES + f"HEX = {json.dumps(hexes)}\n" + r'''
from diffctl.interfaces import serialize, deserialize
for k, m in msgs.items():
    obs(k, lambda m=m: serialize(m).hex())
    obs(k + ' repr', lambda k=k, m=m: deserialize(bytes.fromhex(HEX[k]), type(m)))
    obs(k + ' roundtrip', lambda m=m: deserialize(serialize(m), type(m)) == m)
''')
    for k in hexes:
        assert ours[k][0] == "ok", f"{k}: {ours[k]}"
        assert same_wire(ours[k][1], oracle[k][1]), f"{k}: diffctl {ours[k][1]} != rosidl {oracle[k][1]}"
        assert ours[k + " repr"] == oracle[k + " repr"], k
        assert ours[k + " roundtrip"] == ["ok", True], k


WRONG = r'''
from geometry_msgs.msg import Twist, Polygon
from std_msgs.msg import String, Int8, UInt8, Float64MultiArray, Bool, Int32MultiArray, UInt8MultiArray
from sensor_msgs.msg import JointState
cases = {"uint8 256": lambda: UInt8(data=256), "int8 -129": lambda: Int8(data=-129), "bool 1": lambda: Bool(data=1),
         "bool str": lambda: Bool(data="x"), "float seq of ints": lambda: Float64MultiArray(data=[1, 2]),
         "int32 seq overflow": lambda: Int32MultiArray(data=[2**32 + 1]),
         "uint8 seq 300": lambda: UInt8MultiArray(data=[300]), "int in str": lambda: String(data=5),
         "None in str": lambda: String(data=None), "int in string seq": lambda: JointState(name=[1]),
         "int as message": lambda: Twist(linear=5), "int in message seq": lambda: Polygon(points=[5]),
         "str in float seq": lambda: JointState(position=["a"])}
'''


def test_wrong_field_types_serialize_as_rosidl_reads_them() -> None:
    """Field checks are off by default: what a publish of a wrongly typed field sends (or raises) is rosidl's."""
    oracle = run_oracle(WRONG + r'''
from rclpy.serialization import serialize_message
for k, make in cases.items():
    obs(k, lambda make=make: serialize_message(make()).hex())
''')
    ours = run_ours(WRONG + r'''
from diffctl.interfaces import serialize
for k, make in cases.items():
    obs(k, lambda make=make: serialize(make()).hex())
''')
    for k, real in oracle.items():
        if real[0] == "ok":
            assert ours[k][0] == "ok" and same_wire(ours[k][1], real[1]), (k, ours[k], real)
        else:
            assert ours[k] == real, k


SWEEP = r'''
import importlib
import rosidl_parser.definition as D
PACKAGES = %r

def value_for(t, depth, seed):
    if isinstance(t, D.AbstractNestedType):
        n = t.size if isinstance(t, D.Array) else min(2, getattr(t, "maximum_size", 2))
        items = [value_for(t.value_type, depth, seed + i) for i in range(n)]
        return items
    if isinstance(t, D.BasicType):
        name = t.typename
        if name == "boolean":
            return seed %% 2 == 0
        if name == "octet":
            return bytes([seed %% 256])
        if name in ("float", "double"):
            return seed * 0.5
        return seed %% 100
    if isinstance(t, D.AbstractGenericString):
        return ("ab" * seed)[: getattr(t, "maximum_size", 99) or 99]
    module = importlib.import_module(".".join(t.namespaces))
    return filled(getattr(module, t.name), depth + 1, seed)

def filled(cls, depth, seed):
    msg = cls()
    if depth > 3:
        return msg
    for i, (name, t) in enumerate(zip(cls.get_fields_and_field_types(), cls.SLOT_TYPES)):
        setattr(msg, name, value_for(t, depth, seed + i))
    return msg

msgs = {}
for pkg in PACKAGES:
    for kind in ("msg", "srv"):
        try:
            module = importlib.import_module(f"{pkg}.{kind}")
        except ImportError:
            continue
        names = [n for n in dir(module) if n[:1].isupper()]
        if kind == "srv":
            names = [n for n in names if n.endswith(("_Request", "_Response", "_Event"))]
        for name in sorted(names):
            msgs[f"{pkg}/{kind}/{name}"] = filled(getattr(module, name), 0, 1)
'''
SWEEP_PACKAGES = ["std_msgs", "geometry_msgs", "sensor_msgs", "nav_msgs", "builtin_interfaces", "rcl_interfaces",
                  "action_msgs", "lifecycle_msgs", "diagnostic_msgs", "visualization_msgs", "trajectory_msgs",
                  "shape_msgs", "unique_identifier_msgs", "rosgraph_msgs", "service_msgs",
                  "type_description_interfaces", "rmw_dds_common"]


def test_every_message_type_filled_in_agrees_on_the_wire() -> None:
    """Every message type (and service part) of the Jazzy packages both sides have, each field filled in
    from its SLOT_TYPES (values, sequences of two, bounded strings at their bounds): the same bytes, and
    diffctl reads the real bytes back to the same message."""
    program = SWEEP % SWEEP_PACKAGES
    oracle = run_oracle(program + r'''
from rclpy.serialization import serialize_message
for k, m in msgs.items():
    obs(k, lambda m=m: serialize_message(m).hex())
    obs(k + ' repr', lambda m=m: m)
''')
    assert len(oracle) > 2 * 200 and all(v[0] == "ok" for v in oracle.values()), oracle
    hexes = {k: v[1] for k, v in oracle.items() if not k.endswith(" repr")}
    ours = run_ours(program + f"HEX = {json.dumps(hexes)}\n" + r'''
from diffctl.interfaces import serialize, deserialize
for k, m in msgs.items():
    obs(k, lambda m=m: serialize(m).hex())
    obs(k + ' repr', lambda k=k, m=m: deserialize(bytes.fromhex(HEX[k]), type(m)))
''')
    bad = [k for k in hexes if ours[k][0] != "ok" or not same_wire(ours[k][1], oracle[k][1])]
    bad += [k for k in oracle if k.endswith(" repr") and ours[k] != oracle[k]]
    assert not bad, "\n".join(f"{k}: diffctl {ours[k]} != rosidl {oracle[k]}" for k in bad[:5])
