"""The one registry of action classes: frontend tag → class, and the attributes each tag accepts.

Action classes register themselves with `@register`; the YAML and XML frontends look tags up here (unknown
tag → close-match suggestion) and check every attribute against the class's `frontend_attrs` plus the
attributes every entity takes (`COMMON_ATTRS`). Python launch files construct the same classes.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, TypeVar

from diffctl.errors import LaunchError, suggest

if TYPE_CHECKING:
    from diffctl.launch_legacy.actions import Action

COMMON_ATTRS: tuple[str, ...] = ("if", "unless", "wait_for", "wait_timeout")

_ACTIONS: dict[str, type[Action]] = {}

A = TypeVar("A", bound="type[Action]")


def register(cls: A) -> A:
    for tag in cls.frontend_tags:
        if tag in _ACTIONS:
            raise RuntimeError(f"YAML tag {tag!r} registered twice")
        _ACTIONS[tag] = cls
    return cls


def actions() -> dict[str, type[Action]]:
    # Importing the modules runs their @register decorators.
    import diffctl.launch_legacy.actions
    import diffctl.launch_legacy.composable
    import diffctl.launch_legacy.event_actions
    import diffctl.launch_legacy.event_handlers
    import diffctl.launch_legacy.include_action
    import diffctl.launch_legacy.lifecycle
    import diffctl.launch_legacy.process_actions
    import diffctl.launch_legacy.ros_actions  # noqa: F401

    return _ACTIONS


def lookup(tag: str) -> type[Action]:
    table = actions()
    if tag not in table:
        raise LaunchError(f"unknown tag {tag!r}{suggest(tag, table)}", hint="valid tags: " + ", ".join(sorted(table)))
    return table[tag]


def attributes(tag: str) -> tuple[str, ...]:
    return lookup(tag).frontend_attrs + COMMON_ATTRS
