"""The rosidl_runtime_py program of test_runtime_py.py: run by `make_runtime_golden.py` under upstream's
rosidl_runtime_py with the real generated classes (the golden file), and by the test under diffctl's."""

PROGRAM = r'''
import math
from collections import OrderedDict
from rosidl_runtime_py import (message_to_ordereddict, message_to_yaml, message_to_csv, set_message_fields,
                               get_message_slot_types, import_message_from_namespaced_type)
from rosidl_runtime_py.utilities import get_message, get_service, get_action, get_interface
from geometry_msgs.msg import Twist, PoseWithCovarianceStamped, Polygon, Point32
from sensor_msgs.msg import JointState, Image, LaserScan
from std_msgs.msg import String, Header, ByteMultiArray, Char
import test_msgs.msg as M
from test_msgs.action import Fibonacci

msgs = OrderedDict()
t = Twist(); t.linear.x = 1.5; t.angular.z = -0.25
msgs['twist'] = t
p = PoseWithCovarianceStamped(); p.header.frame_id = 'map'; p.pose.covariance[0] = 0.5
msgs['pose'] = p
msgs['polygon'] = Polygon(points=[Point32(x=1.0), Point32(y=2.0), Point32(z=3.0)])
msgs['joints'] = JointState(name=['left', 'right', 'caster'], position=[0.1, 0.2, 0.3])
msgs['image'] = Image(encoding='rgb8', data=[1, 2, 3, 4])
msgs['scan'] = LaserScan(ranges=[1.0, math.inf, 2.5], angle_min=-1.0)
msgs['string'] = String(data='a fairly long string with ünïcode')
msgs['bytes'] = ByteMultiArray(data=[b'a', b'\x00', b'\xff'])
msgs['char'] = Char(data=65)
msgs['basic'] = M.BasicTypes(byte_value=b'\x05', float32_value=1.5, uint64_value=2**63)
msgs['arrays'] = M.Arrays()
msgs['bounded'] = M.BoundedSequences(int32_values=[1, 2], string_values=['x'])
msgs['strings'] = M.Strings()
msgs['wstrings'] = M.WStrings()
msgs['nested'] = M.MultiNested()
msgs['fib_feedback'] = Fibonacci.Impl.FeedbackMessage(feedback=Fibonacci.Feedback(sequence=[0, 1, 1, 2, 3]))
for k, m in msgs.items():
    obs(k + ' dict', lambda m=m: message_to_ordereddict(m))
    obs(k + ' dict trunc', lambda m=m: message_to_ordereddict(m, truncate_length=2))
    obs(k + ' dict noarr nostr', lambda m=m: message_to_ordereddict(m, no_arr=True, no_str=True))
    obs(k + ' yaml', lambda m=m: message_to_yaml(m))
    obs(k + ' yaml flow', lambda m=m: message_to_yaml(m, flow_style=True, truncate_length=1))
    obs(k + ' csv', lambda m=m: message_to_csv(m))
    obs(k + ' csv opts', lambda m=m: message_to_csv(m, truncate_length=1, no_arr=True))
    obs(k + ' csv nostr', lambda m=m: message_to_csv(m, no_str=True, truncate_length=3))

def setting(cls, values, **kw):
    m = cls()
    stamps = set_message_fields(m, values, **kw)
    return m, len(stamps)
obs('set twist', lambda: setting(Twist, {'linear': {'x': 1.0, 'y': 2}, 'angular': {'z': -1.5}}))
obs('set joints', lambda: setting(JointState, {'name': ['a', 'b'], 'position': [1, 2], 'header': {'frame_id': 'f'}}))
obs('set polygon', lambda: setting(Polygon, {'points': [{'x': 1.0}, {'y': 2.0}]}))
obs('set pose cov', lambda: setting(PoseWithCovarianceStamped, {'pose': {'covariance': [1] * 36}}))
obs('set unknown field', lambda: setting(Twist, {'linear': {'w': 1.0}}))
obs('set not a dict', lambda: setting(Twist, {'linear': 3}))
obs('set wrong type', lambda: setting(String, {'data': 5}))
obs('set header auto', lambda: setting(PoseWithCovarianceStamped, {'header': 'auto'}, expand_header_auto=True))
obs('set time now', lambda: setting(Header, {'stamp': 'now'}, expand_time_now=True))
obs('set bounded', lambda: setting(M.BoundedSequences, {'int32_values': [1, 2, 3], 'string_values': ['a']}))
obs('set arrays', lambda: setting(M.Arrays, {'float64_values': [1, 2, 3], 'string_values': ['a', 'b', 'c']}))
obs('set uint8 from bytes', lambda: setting(Image, {'data': b'\x01\x02'}))
obs('slot types', lambda: list(get_message_slot_types(Twist())))

obs('get_message', lambda: get_message('std_msgs/msg/String'))
obs('get_message short', lambda: get_message('geometry_msgs/Twist'))
obs('get_message of a service', lambda: get_message('std_srvs/srv/Trigger'))
obs('get_service', lambda: (get_service('std_srvs/srv/SetBool'), get_service('std_srvs/Trigger').Request))
obs('get_service of a message', lambda: get_service('std_msgs/msg/String'))
obs('get_action', lambda: get_action('test_msgs/action/Fibonacci').Goal)
obs('get_action short', lambda: get_action('test_msgs/Fibonacci').Result)
obs('get_interface', lambda: get_interface('test_msgs/action/Fibonacci_FeedbackMessage'))
obs('get_message unknown', lambda: get_message('std_msgs/msg/Nope'))
obs('import from slot', lambda: import_message_from_namespaced_type(PoseWithCovarianceStamped.SLOT_TYPES[0]))
'''
