"""`Event`: something that happened during a launch, offered to every matching event handler."""


class Event:
    """Base of the events; `name` says which kind (handlers may match on it, see `event_named`)."""

    name = 'launch.Event'
