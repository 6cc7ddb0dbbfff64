"""Where in a user's file an exception was raised, for one-line error messages."""

from __future__ import annotations

import os
import traceback

_OURS = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # diffctl/
_STDLIB = os.path.dirname(os.__file__)


def user_location(exc: BaseException) -> str | None:
    """'file:line' of the innermost frame of `exc` outside diffctl and the standard library.

    A markup file's location, recorded while parsing it, wins.
    """
    location = getattr(exc, 'launch_location', None)
    if location:
        return location
    found = None
    for frame in traceback.extract_tb(exc.__traceback__):
        path = os.path.abspath(frame.filename)
        if path.startswith(_OURS + os.sep) or path.startswith(_STDLIB + os.sep) or frame.filename.startswith('<'):
            continue
        found = f'{frame.filename}:{frame.lineno}'
    if found is None and exc.__cause__ is not None:
        return user_location(exc.__cause__)
    return found
