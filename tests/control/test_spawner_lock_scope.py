"""The spawner's lock: spawners of one bus queue behind each other, spawners of another bus do not."""

from __future__ import annotations

import pytest

from diffctl.control.spawner import bus_scope, lock_path, spawner_lock
from diffctl.errors import RuntimeFailure


class Log:
    def __init__(self) -> None:
        self.warnings: list[str] = []

    def warn(self, text: str) -> None:
        self.warnings.append(text)


def test_the_lock_is_per_router_endpoint_and_domain(monkeypatch: pytest.MonkeyPatch, tmp_path) -> None:
    monkeypatch.setenv("ROS_HOME", str(tmp_path))
    monkeypatch.delenv("ZENOH_SESSION_CONFIG_URI", raising=False)
    monkeypatch.delenv("ZENOH_CONFIG_OVERRIDE", raising=False)
    monkeypatch.delenv("ROS_DOMAIN_ID", raising=False)
    monkeypatch.setenv("DIFFCTL_ROUTER", "tcp/127.0.0.1:7001")
    first = bus_scope()
    assert bus_scope() == first  # the same bus, the same lock
    monkeypatch.setenv("ROS_DOMAIN_ID", "3")
    other_domain = bus_scope()
    monkeypatch.setenv("DIFFCTL_ROUTER", "tcp/127.0.0.1:7002")
    other_router = bus_scope()
    assert len({first, other_domain, other_router}) == 3
    assert len({lock_path(first), lock_path(other_domain), lock_path(other_router)}) == 3
    assert all(p.parent == tmp_path / "locks" for p in (lock_path(first), lock_path(other_router)))

    log = Log()
    with spawner_lock(log, scope=first):
        with spawner_lock(log, attempts=1, wait_s=0.0, scope=other_router):
            pass  # another stack's spawner goes ahead
        # One of the same bus waits its turn (here: gives up at once).
        with (
            pytest.raises(RuntimeFailure, match="could not take the spawner lock"),
            spawner_lock(log, attempts=1, wait_s=0.0, scope=first),
        ):
            pass
    assert log.warnings == [f"Attempt 1 of 1: another spawner holds {lock_path(first)}"]
