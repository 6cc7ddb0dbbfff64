"""Bus clients the fault tests run as their own processes (so they can be SIGKILLed or left slow on purpose).

    python -m tests.reliability.bus_clients teleop VX WZ       # one TwistStamped per odometry sample (stamp 0
                                                               # = "now": paced by sim time, never stale)
    python -m tests.reliability.bus_clients flood RATE_HZ VX   # TwistStamped (stamp 0 = "now") at RATE_HZ wall
    python -m tests.reliability.bus_clients slow DELAY_S       # subscribes to the busy topics, sleeps DELAY_S
                                                               # in every callback
Each prints one line when it is connected and then runs until killed.
"""

from __future__ import annotations

import sys
import time
from typing import Any

from diffctl.interfaces import types
from tests.probe import Probe

CMD = "/diffbot_base_controller/cmd_vel"
ODOM = "/diffbot_base_controller/odom"
TWIST_STAMPED = "geometry_msgs/msg/TwistStamped"


def teleop(vx: float, wz: float) -> None:
    node = Probe("fault_teleop")
    pub = node.create_publisher(CMD, TWIST_STAMPED)
    cmd = types.new(TWIST_STAMPED, {"twist": {"linear": {"x": vx}, "angular": {"z": wz}}})

    def on_odom(_m: Any) -> None:
        pub.publish(cmd)

    node.create_subscription(ODOM, "nav_msgs/msg/Odometry", on_odom)
    print("teleop ready", flush=True)
    node.spin()


def flood(rate_hz: float, vx: float) -> None:
    node = Probe("fault_flood")
    pub = node.create_publisher(CMD, TWIST_STAMPED)
    cmd = types.new(TWIST_STAMPED, {"twist": {"linear": {"x": vx}}})
    period = 1.0 / rate_hz
    print("flood ready", flush=True)
    sent, t0 = 0, time.monotonic()
    next_t = t0
    while True:
        pub.publish(cmd)
        sent += 1
        next_t += period
        delay = next_t - time.monotonic()
        if delay > 0:
            time.sleep(delay)
        if sent % int(rate_hz) == 0:
            print(f"flood sent {sent} ({sent / (time.monotonic() - t0):.0f}/s)", flush=True)


def slow(delay_s: float) -> None:
    node = Probe("fault_slow_subscriber")

    def stall(_m: Any) -> None:
        time.sleep(delay_s)

    for topic, typename in (
        ("/joint_states", "sensor_msgs/msg/JointState"),
        (ODOM, "nav_msgs/msg/Odometry"),
        ("/tf", "tf2_msgs/msg/TFMessage"),
        ("/clock", "rosgraph_msgs/msg/Clock"),
        ("/scan", "sensor_msgs/msg/LaserScan"),
        (CMD, TWIST_STAMPED),
    ):
        node.create_subscription(topic, typename, stall)
    print("slow subscriber ready", flush=True)
    node.spin()


def main(argv: list[str]) -> None:
    mode, *args = argv
    {"teleop": teleop, "flood": flood, "slow": slow}[mode](*(float(a) for a in args))


if __name__ == "__main__":
    main(sys.argv[1:])
