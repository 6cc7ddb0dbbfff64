"""The secured two-host deployment of config/security/, made concrete for a test: throwaway certificates from
config/security/make_certs.sh, each host's folder (its certificates and users.txt), and the shipped example
configs with their placeholders (/etc/diffctl/certs/, 192.168.1.10) replaced."""

from __future__ import annotations

import shutil
import subprocess
from dataclasses import dataclass
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
EXAMPLES = REPO / "config" / "security"
CERT_DIR_PLACEHOLDER = "/etc/diffctl/certs/"
HOST_A_PLACEHOLDER = "192.168.1.10"
LOCAL_LOGIN = "diffctl:change-me-local"
VISITOR_PASSWORD = "visitor-pw"


def _replace(text: str, old: str, new: str) -> str:
    # A placeholder that vanished from an example would make the test quietly prove something else.
    assert old in text, f"{old!r} is no longer in the example config"
    return text.replace(old, new)


@dataclass(frozen=True)
class Deployment:
    root: Path
    host_a_address: str

    @property
    def router_a(self) -> Path:
        return self.root / "a" / "router_a.json5"

    @property
    def session_a(self) -> Path:
        return self.root / "a" / "session.json5"

    @property
    def router_b(self) -> Path:
        return self.root / "b" / "router_b.json5"

    @property
    def session_b(self) -> Path:
        return self.root / "b" / "session.json5"

    def client(self, name: str) -> Path:
        """A client straight to router A: laptop (as shipped), visitor (logged in, in no policy),
        wrong_password, no_certificate or other_ca."""
        return self.root / "clients" / f"{name}.json5"


def _certs(folder: Path, *names: str) -> None:
    r = subprocess.run(
        [str(EXAMPLES / "make_certs.sh"), str(folder), *names], capture_output=True, text=True, timeout=60
    )
    assert r.returncode == 0, f"make_certs.sh failed: {r.stderr}"


def build(root: Path, host_a_address: str, host_b_address: str) -> Deployment:
    d = Deployment(root, host_a_address)
    ca, rogue = root / "ca", root / "rogue_ca"
    _certs(ca, f"router-a={host_a_address}", f"router-b={host_b_address}", "laptop", "visitor")
    _certs(rogue, "intruder")  # a well-formed certificate from a CA nobody trusts

    files = {
        "a": [ca / "ca.pem", ca / "router-a.pem", ca / "router-a.key"],
        "b": [ca / "ca.pem", ca / "router-b.pem", ca / "router-b.key"],
        "clients": [
            ca / "ca.pem",
            ca / "laptop.pem",
            ca / "laptop.key",
            ca / "visitor.pem",
            ca / "visitor.key",
            rogue / "intruder.pem",
            rogue / "intruder.key",
        ],
    }
    for host, paths in files.items():
        (root / host).mkdir(mode=0o700)
        for p in paths:
            shutil.copy(p, root / host / p.name)
    (root / "a" / "users.txt").write_text(
        f"{LOCAL_LOGIN}\nhost-b:change-me-host-b\nlaptop:change-me-laptop\nvisitor:{VISITOR_PASSWORD}\n"
    )
    (root / "b" / "users.txt").write_text(f"{LOCAL_LOGIN}\n")

    def concrete(example: str, host: str) -> str:
        text = _replace((EXAMPLES / example).read_text(), CERT_DIR_PLACEHOLDER, f"{root / host}/")
        return text.replace(HOST_A_PLACEHOLDER, host_a_address)

    d.router_a.write_text(concrete("router_a.json5", "a"))
    d.session_a.write_text(concrete("session.json5", "a"))
    d.router_b.write_text(concrete("router_b.json5", "b"))
    d.session_b.write_text(concrete("session.json5", "b"))

    client = concrete("client.json5", "clients")
    d.client("laptop").write_text(client)  # as shipped: in router A's access-control list
    visitor = _replace(_replace(client, "laptop", "visitor"), "change-me-visitor", VISITOR_PASSWORD)
    d.client("visitor").write_text(visitor)
    d.client("wrong_password").write_text(_replace(visitor, f'"{VISITOR_PASSWORD}"', '"guessed"'))
    d.client("other_ca").write_text(_replace(visitor, "visitor.", "intruder."))
    no_cert = [
        line
        for line in visitor.splitlines()
        if not line.strip().startswith(("connect_private_key", "connect_certificate", "enable_mtls"))
    ]
    assert len(no_cert) == len(visitor.splitlines()) - 3
    d.client("no_certificate").write_text("\n".join(no_cert) + "\n")
    return d
