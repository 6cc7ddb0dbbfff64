"""What users observe of message classes equals rosidl_generator_py's Jazzy classes: the same program runs
under the real generated packages (oracle venv) and under diffctl's, with field checks off (Jazzy's default)
and on (ROS_PYTHON_CHECK_FIELDS=1)."""

from __future__ import annotations

import pytest

from tests.interfaces.programs import assert_same, run_oracle, run_ours

PROGRAM = r'''
from geometry_msgs.msg import Twist, Vector3, Quaternion, PoseWithCovariance, Point
from std_msgs.msg import Int8, UInt8, Float32, String, Header, Byte, Char, Float64MultiArray, UInt8MultiArray
from std_msgs.msg import Empty, Bool, ByteMultiArray
from sensor_msgs.msg import Image, LaserScan, NavSatStatus, JointState, CameraInfo
from action_msgs.msg import GoalStatus, GoalInfo
from unique_identifier_msgs.msg import UUID
from rcl_interfaces.msg import ParameterDescriptor, ParameterValue, Log
from std_srvs.srv import Trigger, SetBool
from lifecycle_msgs.msg import Transition
from lifecycle_msgs.srv import ChangeState

TYPES = [Twist, Vector3, Quaternion, PoseWithCovariance, Int8, UInt8, Float32, String, Header, Byte, Char,
         Float64MultiArray, UInt8MultiArray, Empty, Bool, ByteMultiArray, Image, LaserScan, NavSatStatus,
         JointState, CameraInfo, GoalStatus, GoalInfo, UUID, ParameterDescriptor, ParameterValue, Log,
         Trigger.Request, Trigger.Response, SetBool.Request, Transition, ChangeState.Request,
         ChangeState.Response, ChangeState.Event]
for T in TYPES:
    n = T.__name__
    obs(n + ' repr', lambda T=T: T())
    obs(n + ' fields', lambda T=T: T.get_fields_and_field_types())
    obs(n + ' fields copy', lambda T=T: T.get_fields_and_field_types() is not T._fields_and_field_types)
    obs(n + ' slots', lambda T=T: T.__slots__)
    obs(n + ' slot types', lambda T=T: [slot(t) for t in T.SLOT_TYPES])
    obs(n + ' module', lambda T=T: (T.__module__, T.__qualname__, type(T).__name__))
    obs(n + ' kinds', lambda T=T: [kind(getattr(T(), f)) for f in T.get_fields_and_field_types()])
    obs(n + ' eq', lambda T=T: T() == T())
    obs(n + ' hash', lambda T=T: T.__hash__ is None)
    obs(n + ' typesupport', lambda T=T: (T._TYPE_SUPPORT, type(T)._CREATE_ROS_MESSAGE))
    obs(n + ' public', lambda T=T: sorted(a for a in dir(T) if not a.startswith('_')))

obs('quaternion default', lambda: (Quaternion.W__DEFAULT, Quaternion().w))
obs('navsat default', lambda: NavSatStatus().status)
obs('descriptor defaults', lambda: (ParameterDescriptor.READ_ONLY__DEFAULT, ParameterDescriptor().dynamic_typing))
obs('constants', lambda: (GoalStatus.STATUS_SUCCEEDED, GoalStatus().STATUS_ABORTED, NavSatStatus.SERVICE_GPS,
                          Transition.TRANSITION_ACTIVATE, ParameterDescriptor))
def set_const():
    GoalStatus.STATUS_SUCCEEDED = 5
obs('constant assign', set_const)
def set_inst_const():
    g = GoalStatus()
    g.STATUS_SUCCEEDED = 5
obs('instance constant assign', set_inst_const)
obs('unknown attribute', lambda: setattr(Twist(), 'foo', 1))
obs('unknown kwarg', lambda: Twist(foo=1, bar=2))
obs('int8 range', lambda: Int8(data=200))
obs('uint8 negative', lambda: UInt8(data=-1))
obs('float from int', lambda: Float32(data=3))
obs('float as str', lambda: Float32(data='x'))
def assign_vector():
    t = Twist()
    t.linear = 5
    return t
obs('sub message wrong', assign_vector)
obs('sub message ok', lambda: Twist(linear=Vector3(x=1.0)))
obs('string type', lambda: String(data=5))
obs('byte', lambda: (Byte(), Byte(data=b'a'), Byte(data=3)))
obs('char', lambda: (Char(), Char(data=65)))
obs('uuid default', lambda: UUID())
obs('uuid list', lambda: UUID(uuid=list(range(16))))
obs('uuid wrong dtype', lambda: UUID(uuid=numpy.zeros(16, dtype=numpy.int32)))
obs('uuid short', lambda: UUID(uuid=[1, 2]))
obs('float64 seq', lambda: Float64MultiArray(data=[1, 2.5]))
def assign_seq():
    m = Float64MultiArray()
    m.data = [1, 2]
    return m
obs('float64 seq assign ints', assign_seq)
def assign_array():
    m = Float64MultiArray()
    m.data = array.array('d', [1.0])
    return m
obs('float64 seq assign array', assign_array)
obs('float64 seq wrong typecode', lambda: Float64MultiArray(data=array.array('f', [1.0])))
obs('uint8 seq bytes', lambda: UInt8MultiArray(data=b'\x01\x02'))
obs('image data bytes', lambda: kind(Image(data=b'\x01\x02').data))
obs('byte seq', lambda: ByteMultiArray(data=[b'\x01', b'\x02']))
obs('byte seq ints', lambda: ByteMultiArray(data=[1, 2]))
obs('covariance', lambda: PoseWithCovariance(covariance=[1.0] * 36).covariance[:3])
obs('covariance short', lambda: PoseWithCovariance(covariance=[1.0] * 3))
obs('string seq', lambda: JointState(name=['a', 'b']))
obs('string seq wrong', lambda: JointState(name=['a', 2]))
obs('bool', lambda: Bool(data=1))
obs('eq other type', lambda: (Twist() == Vector3(), Twist() == 1, Twist(linear=Vector3(x=1.0)) == Twist()))
obs('eq arrays', lambda: (PoseWithCovariance() == PoseWithCovariance(),
                          PoseWithCovariance(covariance=[1.0] * 36) == PoseWithCovariance()))
obs('copy', lambda: (copy.copy(Twist(linear=Vector3(x=2.0))), copy.copy(Twist()).linear is not None))
def shallow():
    t = Twist()
    return copy.copy(t).linear is t.linear, copy.deepcopy(t).linear is t.linear, copy.deepcopy(t) == t
obs('copy depth', shallow)
obs('repr nested seq', lambda: LaserScan(ranges=[1.0, 2.0], intensities=[]))
obs('camera info', lambda: CameraInfo(d=[0.1], k=[1.0] * 9))
obs('check_fields kw', lambda: (Int8(data=300, check_fields=False).data, Int8(check_fields=True)._check_fields))
obs('srv class', lambda: (Trigger.Request, Trigger.Response, Trigger.Event, SetBool.Request().data))
obs('srv instantiate', lambda: Trigger())
obs('event', lambda: Trigger.Event())
obs('empty', lambda: (Empty(), Empty.__slots__, Empty.get_fields_and_field_types()))
def header_stamp():
    h = Header(frame_id='map')
    h.stamp.sec = 3
    return h
obs('header', header_stamp)
obs('log constants', lambda: (Log.INFO, Log.FATAL, type(Log.DEBUG).__name__))
obs('twist str', lambda: str(Twist()))
def star(module):
    ns = {}
    exec(f'from {module} import *', ns)
    return sorted(n for n in ns if not n.startswith('__'))
obs('import star', lambda: (star('std_srvs.srv'), star('lifecycle_msgs.msg')))
import pickle
obs('pickle', lambda: pickle.loads(pickle.dumps(PoseWithCovariance(covariance=[2.0] * 36))).covariance[:2])
obs('pickle eq', lambda: pickle.loads(pickle.dumps(JointState(name=['a'], position=[1.0]))) ==
    JointState(name=['a'], position=[1.0]))
obs('doc', lambda: (GoalStatus.__doc__, Twist.__doc__, type(Twist).__doc__))
obs('property doc', lambda: Twist.linear.__doc__)
obs('import type support', lambda: (Twist.__import_type_support__(), Twist._TYPE_SUPPORT is not None))
obs('srv import type support', lambda: (Trigger.__import_type_support__(), Trigger._TYPE_SUPPORT is not None))
import importlib
obs('module layout', lambda: (importlib.import_module('geometry_msgs.msg._twist').Twist is Twist,
                              importlib.import_module('sensor_msgs.msg._nav_sat_status').NavSatStatus.__name__,
                              importlib.import_module('std_srvs.srv._set_bool').SetBool_Request is SetBool.Request))
'''


@pytest.mark.parametrize("check", ["", "1"], ids=["checks-off", "checks-on"])
def test_classes_behave_as_rosidls(check: str) -> None:
    env = {"ROS_PYTHON_CHECK_FIELDS": check} if check else None
    assert_same(run_ours(PROGRAM, env), run_oracle(PROGRAM, env))
