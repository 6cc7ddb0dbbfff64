"""Where in a user's file an exception was raised, or an entity made, for one-line error messages."""

from __future__ import annotations

import os
import sys
import traceback
from typing import Any

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


# the code between a launch file and the entities it makes: diffctl, the standard library, installed packages
_NOT_USERS = (_OURS + os.sep, _STDLIB + os.sep, '<')
_INSTALLED = (os.sep + 'site-packages' + os.sep, os.sep + 'dist-packages' + os.sep)
# a launch file is a few constructors away (Node, ExecuteProcess, ExecuteLocal, Action) or behind a helper's few;
# an action launch makes itself while running, or a frontend while parsing, is found by none within this many
_LOOKED_AT = 16


def creation_site(made: Any) -> str | None:
    """'file:line' of the code that is making `made` (called from its constructor): the innermost frame of the
    user's own files, past `made`'s own constructors and installed helper packages; None when none is found
    (an entity a frontend parsed: its markup location is kept instead)."""
    frame = sys._getframe(1)
    for _ in range(_LOOKED_AT):
        if frame is None:
            break
        path = frame.f_code.co_filename
        if not path.startswith(_NOT_USERS) and not any(part in path for part in _INSTALLED) \
                and not (frame.f_code.co_name == '__init__' and frame.f_locals.get('self') is made):
            return f'{path}:{frame.f_lineno}'
        frame = frame.f_back
    return None
