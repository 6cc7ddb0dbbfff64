"""Who may watch and who may drive: the command token and the WebSocket Origin / Host checks.

Watching needs nothing but reaching the port (loopback by default). Anything that publishes (teleop, the
message publisher) needs the random token printed in the URL at start. The Origin check stops another web
site open in the same browser from talking to the socket; the Host check stops DNS-rebinding pages.
"""

from __future__ import annotations

import hmac
import secrets
from dataclasses import dataclass
from urllib.parse import parse_qs, urlsplit

LOOPBACK_NAMES = ("127.0.0.1", "localhost", "[::1]")


def new_token() -> str:
    return secrets.token_urlsafe(18)


def token_matches(given: str | None, expected: str) -> bool:
    return given is not None and hmac.compare_digest(given.encode(), expected.encode())


def query_token(path: str) -> str | None:
    """The `token` query parameter of a request path like `/ws?token=abc`."""
    values = parse_qs(urlsplit(path).query).get("token")
    return values[0] if values else None


@dataclass(frozen=True)
class HostPolicy:
    """The host:port names this server answers to."""

    host: str
    port: int

    def allowed_hosts(self) -> set[str]:
        names = {self.host if ":" not in self.host else f"[{self.host}]"}
        if self.host in ("127.0.0.1", "localhost", "::1"):
            names |= set(LOOPBACK_NAMES)
        return {f"{n}:{self.port}" for n in names} | ({*names} if self.port == 80 else set())

    def host_ok(self, host_header: str | None) -> bool:
        if self.host in ("0.0.0.0", "::"):
            # Listening on every interface was asked for explicitly; any name that reaches us is accepted.
            return bool(host_header)
        return host_header is not None and host_header.lower() in self.allowed_hosts()

    def origin_ok(self, origin: str | None, host_header: str | None) -> bool:
        """Same host:port only. No Origin means a non-browser client, which cannot be driven by a web page."""
        if origin is None:
            return True
        parts = urlsplit(origin)
        if parts.scheme not in ("http", "https") or not parts.netloc:
            return False
        return host_header is not None and parts.netloc.lower() == host_header.lower() and self.host_ok(host_header)
