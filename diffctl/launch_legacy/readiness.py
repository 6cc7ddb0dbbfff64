"""Readiness: an entity may wait until a process started, exited with 0 or printed a line, or a topic or
service is up (beyond ros2 launch, which has no readiness at all).

`WaitFor` is the description-level form shared by both frontends:

    YAML                                   Python
    wait_for:                              wait_for=[
      - started: sim                           WaitFor.started("sim"),       # or the Node object
      - exited: spawn_entity                   WaitFor.exited(spawn_entity),
      - log: {process: sim, regex: ready}      WaitFor.log(sim, "ready"),
      - topic: /robot_description              WaitFor.topic("/robot_description"),
      - service: /controller_manager/list_controllers ]
    wait_timeout: 30                       wait_timeout=30.0

Bus conditions are answered by probes the CLI injects (`{"topic": fn(name) -> bool, "service": …}`), polled
off the supervisor's thread by `ProbePoller`, since a probe may block on the network.
"""

from __future__ import annotations

import re
import threading
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

from diffctl.errors import LaunchError, suggest
from diffctl.launch_legacy.plan import WAIT_KINDS

Probes = Mapping[str, Callable[[str], bool]]


@dataclass
class WaitFor:
    kind: str
    target: Any  # process name (str or substitutions), the action object of a process, or a topic/service name
    pattern: str | None = None

    @classmethod
    def started(cls, process: Any) -> WaitFor:
        return cls("started", process)

    @classmethod
    def exited(cls, process: Any) -> WaitFor:
        return cls("exited", process)

    @classmethod
    def log(cls, process: Any, regex: str) -> WaitFor:
        return cls("log", process, compile_pattern(regex))

    @classmethod
    def topic(cls, name: Any) -> WaitFor:
        return cls("topic", name)

    @classmethod
    def service(cls, name: Any) -> WaitFor:
        return cls("service", name)


def compile_pattern(regex: str) -> str:
    try:
        re.compile(regex)
    except re.error as e:
        raise LaunchError(f"log pattern {regex!r} is not a valid regular expression: {e}") from None
    return regex


def parse_wait_for(value: Any, parse_text: Callable[[str], Any] = lambda s: s) -> list[WaitFor]:
    """A YAML/dict `wait_for` value (one mapping or a list of them, or WaitFor objects) → WaitFor list."""
    if value is None:
        return []
    items = value if isinstance(value, (list, tuple)) else [value]
    out: list[WaitFor] = []
    for item in items:
        if isinstance(item, WaitFor):
            out.append(item)
            continue
        if not isinstance(item, Mapping) or len(item) != 1:
            raise LaunchError(
                f"wait_for entry {item!r} must be a mapping with one key",
                hint="valid keys: " + ", ".join(WAIT_KINDS) + " (e.g. `- exited: spawn_entity`)",
            )
        ((kind, arg),) = item.items()
        kind = str(kind)
        if kind not in WAIT_KINDS:
            raise LaunchError(
                f"unknown wait_for condition {kind!r}{suggest(kind, WAIT_KINDS)}",
                hint="valid: " + ", ".join(WAIT_KINDS),
            )
        if kind == "log":
            if not isinstance(arg, Mapping) or set(arg) != {"process", "regex"}:
                raise LaunchError("wait_for `log` needs {process: NAME, regex: PATTERN}")
            out.append(WaitFor("log", parse_text(str(arg["process"])), compile_pattern(str(arg["regex"]))))
        else:
            if isinstance(arg, (Mapping, list)) or arg is None:
                raise LaunchError(f"wait_for `{kind}` takes a name, got {arg!r}")
            out.append(WaitFor(kind, arg if not isinstance(arg, str) else parse_text(arg)))
    return out


def parse_timeout(value: Any) -> float | None:
    if value is None:
        return None
    try:
        t = float(value)
    except (TypeError, ValueError):
        raise LaunchError(f"wait_timeout {value!r} is not a number of seconds") from None
    if not t > 0 or t != t or t == float("inf"):
        raise LaunchError(f"wait_timeout {value!r} must be a positive number of seconds")
    return t


class ProbePoller:
    """Polls bus probes on a worker thread; `ready(kind, name)` answers from the last poll without blocking."""

    def __init__(self, probes: Probes, notify: Callable[[], None] | None = None, period_s: float = 0.1) -> None:
        self.probes = probes
        self.notify = notify or (lambda: None)
        self.period_s = period_s
        self._wanted: set[tuple[str, str]] = set()
        self._ready: set[tuple[str, str]] = set()
        self._lock = threading.Lock()
        self._wake = threading.Event()
        self._stop = False
        self._thread: threading.Thread | None = None

    def want(self, kind: str, name: str) -> None:
        if kind not in self.probes:
            raise LaunchError(f"no probe for {kind!r} conditions (the bus is not available)")
        with self._lock:
            if (kind, name) in self._ready:
                return
            self._wanted.add((kind, name))
        if self._thread is None:
            self._thread = threading.Thread(target=self._run, name="diffctl-launch-probes", daemon=True)
            self._thread.start()
        self._wake.set()

    def ready(self, kind: str, name: str) -> bool:
        with self._lock:
            return (kind, name) in self._ready

    def _run(self) -> None:
        while not self._stop:
            with self._lock:
                todo = sorted(self._wanted)
            changed = False
            for kind, name in todo:
                try:
                    ok = bool(self.probes[kind](name))
                except Exception:
                    ok = False  # a probe that fails is "not ready yet"; the gate's timeout bounds the wait
                if ok:
                    with self._lock:
                        self._wanted.discard((kind, name))
                        self._ready.add((kind, name))
                    changed = True
            if changed:
                self.notify()
            self._wake.wait(self.period_s)
            self._wake.clear()

    def close(self) -> None:
        self._stop = True
        self._wake.set()
        if self._thread is not None:
            self._thread.join(timeout=1.0)
