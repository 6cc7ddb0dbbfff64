"""Read-only public attributes kept in one dict per object (events' payloads, actions' operands)."""

from __future__ import annotations


def field(key: str, doc: str | None = None) -> property:
    """A property reading `self._fields[key]`; it has no setter."""
    return property(lambda self: self._fields[key], doc=doc)
