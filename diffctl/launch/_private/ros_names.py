"""The text Python gives an object without a `__repr__` of its own, with ROS's module names.

ros2 launch --print, and launch's messages, show entities, event handlers, events, substitutions and the like
as `<launch.actions.timer_action.TimerAction object at 0x…>`; diffctl's classes live in `diffctl.launch…`
(and `diffctl.launch_ros…`, …), so the default text would name those. Users see the names they import.
"""

from __future__ import annotations

from typing import Any

# diffctl's packages that are ROS packages under their ROS name (the overlay's aliases)
_ROS_PACKAGES = frozenset(
    {'launch', 'launch_ros', 'launch_xml', 'launch_yaml', 'launch_testing', 'launch_pytest', 'launch_testing_ros'})


def ros_module(module: str) -> str:
    """`diffctl.launch.actions.x` → `launch.actions.x`; any other module name as it is."""
    head, _, rest = module.partition('.')
    if head == 'diffctl' and rest.partition('.')[0] in _ROS_PACKAGES:
        return rest
    return module


def default_text(thing: Any) -> str:
    """`object.__repr__(thing)`, the class's module named as ROS names it."""
    kind = type(thing)
    return f'<{ros_module(kind.__module__)}.{kind.__qualname__} object at {id(thing):#x}>'
