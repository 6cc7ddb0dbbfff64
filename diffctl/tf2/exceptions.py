"""tf2's exception types (tf2_py's names; all are TransformException)."""

from __future__ import annotations


class TransformException(Exception):
    """Base of every tf2 error."""


class LookupException(TransformException):
    """A frame that was asked for is not in the buffer."""


class ConnectivityException(TransformException):
    """The two frames are in different trees."""


class ExtrapolationException(TransformException):
    """The time asked for is outside the data the buffer holds."""


class InvalidArgumentException(TransformException):
    """An empty frame id, one starting with '/', or a non-finite transform."""


class TimeoutException(TransformException):
    """A wait for a transform ran out."""
