"""`Event`: something that happened during a launch, offered to every matching event handler."""

from ._private.ros_names import default_text


class Event:
    """Base of the events; `name` says which kind (handlers may match on it, see `event_named`)."""

    name = 'launch.Event'

    def __repr__(self) -> str:
        return default_text(self)  # under ROS's module names, as ros2 launch --print shows it
