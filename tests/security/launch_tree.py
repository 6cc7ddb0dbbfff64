"""What a running launch exposes: every listening socket of every process in its tree, from /proc."""

from __future__ import annotations

import os
import socket
from dataclasses import dataclass
from pathlib import Path

import psutil

LOOPBACK = {"127.0.0.1", "::1"}
TCP_LISTEN = "0A"


@dataclass(frozen=True)
class OpenSocket:
    process: str
    pid: int
    proto: str  # "tcp" | "udp"
    address: str
    port: int

    def __str__(self) -> str:
        return f"{self.process} (pid {self.pid}) {self.proto} {self.address}:{self.port}"


def tree(root_pid: int) -> list[psutil.Process]:
    root = psutil.Process(root_pid)
    return [root, *root.children(recursive=True)]


def _label(p: psutil.Process) -> str:
    try:
        argv = p.cmdline()
    except psutil.Error:
        return "?"
    # `python -m diffctl sim run …` → "diffctl sim run"
    if "diffctl" in argv:
        i = argv.index("diffctl")
        return " ".join(argv[i : i + 3])
    return " ".join(argv[:3])


def _hex_address(text: str) -> tuple[str, int]:
    """`0100007F:1CE7` (/proc/net/tcp's host-order words) → ("127.0.0.1", 7399); IPv6 likewise."""
    addr, port = text.split(":")
    raw = bytes.fromhex(addr)
    # Each 32-bit word is stored in host byte order (little-endian here).
    words = b"".join(raw[i : i + 4][::-1] for i in range(0, len(raw), 4))
    family = socket.AF_INET if len(words) == 4 else socket.AF_INET6
    ip = socket.inet_ntop(family, words)
    if ip.startswith("::ffff:") and "." in ip:
        ip = ip.removeprefix("::ffff:")
    return ip, int(port, 16)


def _socket_table(pid: int) -> dict[int, tuple[str, str, int, bool]]:
    """inode → (proto, ip, port, listening) from the tables of the process's own network namespace
    (psutil reads the caller's, which misses processes in another namespace)."""
    table = {}
    for name in ("tcp", "tcp6", "udp", "udp6"):
        try:
            lines = Path(f"/proc/{pid}/net/{name}").read_text().splitlines()[1:]
        except OSError:
            continue
        for line in lines:
            f = line.split()
            ip, port = _hex_address(f[1])
            table[int(f[9])] = (name.rstrip("6"), ip, port, f[3] == TCP_LISTEN)
    return table


def _socket_inodes(pid: int) -> set[int]:
    inodes = set()
    fd_dir = Path(f"/proc/{pid}/fd")
    try:
        fds = list(fd_dir.iterdir())
    except OSError:
        return inodes
    for fd in fds:
        try:
            target = os.readlink(fd)
        except OSError:
            continue
        if target.startswith("socket:["):
            inodes.add(int(target[8:-1]))
    return inodes


def listening_sockets(procs: list[psutil.Process]) -> list[OpenSocket]:
    """TCP sockets in LISTEN and every bound UDP socket (UDP has no listen: bound is reachable)."""
    found = []
    for p in procs:
        table = _socket_table(p.pid)
        for inode in _socket_inodes(p.pid):
            if inode not in table:
                continue
            proto, ip, port, listening = table[inode]
            if proto == "tcp" and not listening:
                continue
            if proto == "udp" and port == 0:
                continue
            found.append(OpenSocket(_label(p), p.pid, proto, ip, port))
    return found


def labels(procs: list[psutil.Process]) -> list[str]:
    return [_label(p) for p in procs]
