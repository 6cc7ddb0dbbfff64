"""`Event`: something that happened while launching, matched by event handlers."""


class Event:
    """Base of every launch event; `name` identifies the kind of event."""

    name = 'launch.Event'
