"""Two test hosts as Linux network namespaces joined by a veth pair, removed again however a test ends.

Each host has its own loopback (brought up) and one address on the link between them, 10.77.N.1 and
10.77.N.2. Commands run on a host with `ip netns exec`, which execs in place: the pid `Procs` sees is the
program's own, so killing its process group stops it.
"""

from __future__ import annotations

import os
import random
import signal
import subprocess
import time
from dataclasses import dataclass, field


def _ip(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(["ip", *args], capture_output=True, text=True, timeout=10)


def netns_unavailable() -> str | None:
    """Why namespaces cannot be made here (None when they can): tried, not guessed."""
    if subprocess.run(["sh", "-c", "command -v ip"], capture_output=True).returncode != 0:
        return "the `ip` tool (iproute2) is not installed"
    probe = f"dctprobe{os.getpid()}"
    r = _ip("netns", "add", probe)
    if r.returncode != 0:
        return f"`ip netns add` is not permitted here: {r.stderr.strip()}"
    _ip("netns", "del", probe)
    return None


@dataclass
class Host:
    name: str  # the namespace
    address: str  # on the link to the other host

    def argv(self, *cmd: str) -> list[str]:
        return ["ip", "netns", "exec", self.name, *cmd]

    def run(self, *cmd: str, timeout_s: float = 30.0) -> subprocess.CompletedProcess[str]:
        return subprocess.run(self.argv(*cmd), capture_output=True, text=True, timeout=timeout_s)

    def pids(self) -> list[int]:
        out = _ip("netns", "pids", self.name).stdout
        return [int(p) for p in out.split()]


@dataclass
class HostPair:
    a: Host
    b: Host
    _links: list[str] = field(default_factory=list)

    @classmethod
    def create(cls) -> HostPair:
        tag = f"{os.getpid() % 100000}{random.randint(0, 99)}"
        net = random.randint(1, 254)
        pair = cls(Host(f"dct{tag}a", f"10.77.{net}.1"), Host(f"dct{tag}b", f"10.77.{net}.2"))
        try:
            pair._setup(f"dv{tag}a", f"dv{tag}b")
        except BaseException:
            pair.remove()
            raise
        return pair

    def _setup(self, veth_a: str, veth_b: str) -> None:
        steps: list[tuple[str, ...]] = [
            ("netns", "add", self.a.name),
            ("netns", "add", self.b.name),
            ("link", "add", veth_a, "type", "veth", "peer", "name", veth_b),
            ("link", "set", veth_a, "netns", self.a.name),
            ("link", "set", veth_b, "netns", self.b.name),
        ]
        for host, veth in ((self.a, veth_a), (self.b, veth_b)):
            steps += [
                ("-n", host.name, "addr", "add", f"{host.address}/24", "dev", veth),
                ("-n", host.name, "link", "set", veth, "up"),
                ("-n", host.name, "link", "set", "lo", "up"),
            ]
        for step in steps:
            r = _ip(*step)
            if r.returncode != 0:
                raise RuntimeError(f"ip {' '.join(step)}: {r.stderr.strip()}")
            if step[:2] == ("link", "add"):
                self._links.append(veth_a)

    def remove(self) -> None:
        """Kill whatever still runs in the two namespaces (only this test's programs can), then delete them."""
        for host in (self.a, self.b):
            for pid in host.pids():
                try:
                    os.kill(pid, signal.SIGKILL)
                except ProcessLookupError:
                    pass
        deadline = time.monotonic() + 5.0
        while any(h.pids() for h in (self.a, self.b)) and time.monotonic() < deadline:
            time.sleep(0.05)
        for host in (self.a, self.b):
            _ip("netns", "del", host.name)
        for link in self._links:  # only left in the root namespace if moving it failed
            _ip("link", "del", link)

    def exists(self) -> bool:
        names = _ip("netns", "list").stdout
        return self.a.name in names or self.b.name in names
