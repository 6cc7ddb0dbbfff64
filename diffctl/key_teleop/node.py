"""key_teleop's node (node name key_teleop) and its full-screen terminal: at `hz` it reads the keys waiting,
works out the velocity of the arrows held, shows it and publishes it on `key_vel` (system-default QoS),
TwistStamped (frame key_teleop, stamped with the wall clock) unless twist_stamped_enabled is false. q quits."""

from __future__ import annotations

import curses
import time
from typing import Any

from diffctl.key_teleop.held_keys import DOWN, LEFT, RIGHT, UP, Rates, velocity

NODE_NAME = "key_teleop"
ARROWS = {curses.KEY_UP: UP, curses.KEY_DOWN: DOWN, curses.KEY_LEFT: LEFT, curses.KEY_RIGHT: RIGHT}
LINES = 10


def declare(node: Any) -> tuple[bool, float, Rates]:
    stamped = bool(node.declare_parameter("twist_stamped_enabled", True).value)
    hz = node.declare_parameter("hz", 10).value
    rates = Rates(*(float(node.declare_parameter(name, default).value) for name, default in
                    (("forward_rate", 0.8), ("backward_rate", 0.5), ("rotation_rate", 1.0))))
    if not hz > 0:
        from diffctl.errors import ParameterError

        raise ParameterError(f"{hz!r} invalid; valid: a rate above 0 Hz", field="hz")
    return stamped, float(hz), rates


def show(screen: Any, lines: dict[int, str]) -> None:
    """Each text on its line of a screen split in ten, from column 10, as key_teleop draws it."""
    screen.clear()
    height, width = screen.getmaxyx()
    for number, text in lines.items():
        y = int(height / LINES * number)
        for row, part in enumerate(text.split("\n")):
            if 0 <= y + row < height and width > 10:
                screen.addstr(y + row, 10, part.ljust(width)[: width - 11])
    screen.refresh()


def drive(screen: Any, node: Any, stamped: bool, hz: float, rates: Rates) -> None:
    from diffctl.client.clock import Clock
    from diffctl.client.qos import qos_profile_system_default
    from diffctl.interfaces import get_interface

    screen.nodelay(True)
    try:
        curses.curs_set(0)
    except curses.error:
        pass  # a terminal that cannot hide its cursor
    twist_cls = get_interface("geometry_msgs/msg/Twist")
    stamped_cls = get_interface("geometry_msgs/msg/TwistStamped")
    pub = node.create_publisher(stamped_cls if stamped else twist_cls, "key_vel", qos_profile_system_default)
    clock, wall = node.get_clock(), Clock()
    last_seen: dict[str, int] = {}
    while True:
        while (key := screen.getch()) != -1:
            if key == ord("q"):
                return
            if key in ARROWS:
                last_seen[ARROWS[key]] = clock.now_ns()
        linear, angular = velocity(last_seen, clock.now_ns(), rates)
        show(screen, {2: f"Linear: {linear:f}, Angular: {angular:f}", 5: "Use arrow keys to move, q to exit."})
        twist = twist_cls()
        twist.linear.x, twist.angular.z = linear, angular
        if stamped:
            out = stamped_cls(twist=twist)
            out.header.stamp = wall.now().to_msg()
            out.header.frame_id = "key_teleop"
            pub.publish(out)
        else:
            pub.publish(twist)
        time.sleep(1.0 / hz)


def run() -> int:
    import sys

    from diffctl.client import component
    from diffctl.client.node import Node
    from diffctl.errors import ConfigError

    if not sys.stdin.isatty() or not sys.stdout.isatty():
        raise ConfigError("key_teleop draws on a terminal and reads its keys, and stdin/stdout is not one",
                          hint="run it in a terminal; in a launch file give its Node one (prefix='xterm -e')")
    started = component.start(lambda: Node(NODE_NAME))
    try:
        settings = declare(started.node)
        curses.wrapper(drive, started.node, *settings)
    except KeyboardInterrupt:
        pass
    finally:
        started.stop()
    return 0
