# use_sim_time: ROS time from /clock (zero before the first message), timers on it, Time/Duration arithmetic.
import itertools
import json
import time

import rclpy
from rclpy.clock import Clock, ClockType
from rclpy.duration import Duration
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from rclpy.parameter import Parameter
from rclpy.qos import QoSProfile, ReliabilityPolicy
from rclpy.time import Time
from rosgraph_msgs.msg import Clock as ClockMsg

out = []
rclpy.init()
sim = Node("sim_demo", parameter_overrides=[Parameter("use_sim_time", value=True)])
source = Node("clock_source")
ex = SingleThreadedExecutor()
ex.add_node(sim)
ex.add_node(source)
out.append(["before any clock", [sim.get_clock().now().nanoseconds, sim.get_clock().ros_time_is_active,
                                 sim.get_clock().clock_type.name]])
clock_pub = source.create_publisher(ClockMsg, "/clock", QoSProfile(depth=1, reliability=ReliabilityPolicy.BEST_EFFORT))
fired = []
sim.create_timer(1.0, lambda: fired.append(sim.get_clock().now().nanoseconds // 10**8))
sim_seconds = [100.0]


def tick():
    sim_seconds[0] += 0.1
    clock_pub.publish(ClockMsg(clock=Time(seconds=sim_seconds[0]).to_msg()))


source.create_timer(0.01, tick, clock=Clock(clock_type=ClockType.STEADY_TIME))
end = time.monotonic() + 3.0
while time.monotonic() < end and len(fired) < 3:
    ex.spin_once(timeout_sec=0.05)
now = sim.get_clock().now()
out.append(["follows /clock", [now.nanoseconds >= 100 * 10**9, now.clock_type.name]])
out.append(["sim timer fired on sim time", [len(fired) >= 3, fired[0] >= 1000 if fired else None]])
# A node switched to sim time at run time: its timer restarts on the sim clock, as rcl's timers do. What rcl
# fixes is the schedule, not when a callback runs: now() in the callback is at or past its due time by however
# late the executor came to it, and the next due time (now + time until the next call, read in the callback with
# the clock still) is a whole number of periods past the last one.
late = Node("late_sim_demo")
late_fired = []
late_timer = late.create_timer(
    0.5, lambda: late_fired.append((late.get_clock().now().nanoseconds, late_timer.time_until_next_call())))
ex.add_node(late)
ex.spin_once(timeout_sec=0.05)
late.set_parameters([Parameter("use_sim_time", value=True)])
end = time.monotonic() + 3.0
while time.monotonic() < end and len(late_fired) < 4:
    ex.spin_once(timeout_sec=0.05)
due = [now_ns + until_ns for now_ns, until_ns in late_fired]
out.append(["switched at run time", [len(late_fired) >= 4, late_fired[0][0] >= 100 * 10**9,
                                     all(b > a and (b - a) % (5 * 10**8) == 0 for a, b in itertools.pairwise(due))]])
late.destroy_node()
# A node detached from its time source (a simulator hosting it sets its time): /clock moves it no more, the
# override does. diffctl reaches the time source through rclcpp's accessor; rclpy has only the attribute.
hosted = Node("hosted_demo", parameter_overrides=[Parameter("use_sim_time", value=True)])
ex.add_node(hosted)
end = time.monotonic() + 3.0
while time.monotonic() < end and hosted.get_clock().now().nanoseconds == 0:
    ex.spin_once(timeout_sec=0.05)
source_of_time = getattr(hosted, "get_node_time_source_interface", lambda: hosted._time_source)()
source_of_time.detach_node()
hosted.get_clock().set_ros_time_override(Time(seconds=7, clock_type=ClockType.ROS_TIME))
before = sim_seconds[0]
end = time.monotonic() + 3.0
while time.monotonic() < end and sim_seconds[0] < before + 0.5:
    ex.spin_once(timeout_sec=0.05)
out.append(["detached", [hosted.get_clock().now().nanoseconds, hosted.get_clock().ros_time_is_active,
                         sim_seconds[0] >= before + 0.5]])
hosted.destroy_node()
# A time source made without a node (rclpy's keyword-only `node=None`): clocks follow what it is told, and a
# node attached later brings its use_sim_time (false here) and /clock subscription with it.
from rclpy.clock import ROSClock  # noqa: E402
from rclpy.time_source import TimeSource  # noqa: E402

alone = TimeSource()
followed = ROSClock()
alone.attach_clock(followed)
alone.ros_time_is_active = True
alone.clock_callback(ClockMsg(clock=Time(seconds=3, nanoseconds=4).to_msg()))
wall_node = Node("attached_later_demo")
try:
    alone.attach_node("not a node")
    refused = "no error"
except TypeError as e:
    refused = str(e)
seen = [followed.ros_time_is_active, followed.now().nanoseconds, alone._clock_sub is None, refused]
alone.attach_node(wall_node)
seen += [alone._get_node() is wall_node, alone.ros_time_is_active, followed.ros_time_is_active,
         alone._clock_sub is None, wall_node.get_parameter("use_sim_time").value]
wall_node.set_parameters([Parameter("use_sim_time", value=True)])
seen += [alone.ros_time_is_active, alone._clock_sub is not None]
alone.detach_node()
seen += [alone._get_node(), alone._clock_sub is None, followed.ros_time_is_active]
out.append(["time source without a node", seen])
wall_node.destroy_node()
# rclpy takes /clock in its executor: a node in none yet reads 0 however long /clock has flowed (a node that
# keeps now() from its constructor starts from 0), and follows once spun.
idle = Node("idle_sim_demo", parameter_overrides=[Parameter("use_sim_time", value=True)])
before = sim_seconds[0]
end = time.monotonic() + 3.0
while time.monotonic() < end and sim_seconds[0] < before + 0.5:
    ex.spin_once(timeout_sec=0.05)
out.append(["not in an executor", [idle.get_clock().now().nanoseconds, sim_seconds[0] >= before + 0.5]])
ex.add_node(idle)
end = time.monotonic() + 3.0
while time.monotonic() < end and idle.get_clock().now().nanoseconds == 0:
    ex.spin_once(timeout_sec=0.05)
out.append(["spun", [idle.get_clock().now().nanoseconds >= 100 * 10**9]])
idle.destroy_node()
sim.set_parameters([Parameter("use_sim_time", value=False)])
wall = sim.get_clock().now().nanoseconds
out.append(["back to wall time", [abs(wall - time.time_ns()) < 10**9, sim.get_clock().ros_time_is_active]])
t = Time(seconds=5, nanoseconds=5, clock_type=ClockType.ROS_TIME)
out.append(["time math", [repr(t + Duration(seconds=1)), repr(t - Time(seconds=1, clock_type=ClockType.ROS_TIME)),
                          repr(Time.from_msg(t.to_msg())), str(Duration(seconds=2.5)), t.seconds_nanoseconds()]])
try:
    Time(seconds=1) - Duration(seconds=2)
    out.append(["negative time", "no error"])
except ValueError as e:
    out.append(["negative time", str(e)])
import threading  # noqa: E402

t0 = time.monotonic()
slept = Clock().sleep_for(Duration(seconds=0.2))
out.append(["sleep_for", [slept, 0.15 < time.monotonic() - t0 < 1.0]])
try:
    Clock().sleep_until(Time(seconds=1, clock_type=ClockType.ROS_TIME))
except ValueError as e:
    out.append(["sleep_until other clock type", str(e)])
rate_node = Node("rate_demo")
rate = rate_node.create_rate(20)
spinner = threading.Thread(target=rclpy.spin, args=(rate_node,), daemon=True)
spinner.start()
t0 = time.monotonic()
for _ in range(5):
    rate.sleep()
out.append(["rate 20 Hz x5", 0.15 < time.monotonic() - t0 < 0.6])
sim.destroy_node()
source.destroy_node()
rclpy.shutdown()
spinner.join(2)
try:
    rate.sleep()
    out.append(["rate after shutdown", "slept"])
except Exception as e:
    out.append(["rate after shutdown", type(e).__name__ + ": " + str(e)])
print(json.dumps(out))
