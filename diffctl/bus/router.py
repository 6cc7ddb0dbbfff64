"""The Zenoh router: `diffctl router` runs one alone; `diffctl launch` embeds one unless one answers."""

from __future__ import annotations

import zenoh

from diffctl.bus.session import _init_log, endpoint_answers, router_config, router_endpoint
from diffctl.errors import ConfigError


class RouterHandle:
    """A router session running in this process."""

    def __init__(self, session: zenoh.Session, endpoints: list[str]) -> None:
        self.session = session
        self.endpoints = endpoints

    @property
    def zid(self) -> str:
        return str(self.session.zid())

    def close(self) -> None:
        try:
            self.session.close()
        except Exception:
            pass


def start_router(listen: list[str] | None = None, config_file: str | None = None) -> RouterHandle:
    _init_log()
    eps = listen or [router_endpoint()]
    try:
        session = zenoh.open(router_config(listen=eps if (listen or not config_file) else None,
                                           config_file=config_file))
    except zenoh.ZError as e:
        raise ConfigError(f"cannot start the Zenoh router on {', '.join(eps)}: {e}",
                          hint="is another router or program using that port?") from None
    return RouterHandle(session, eps)


def ensure_router() -> RouterHandle | None:
    """Start a router on the configured endpoint unless one already answers there (then None)."""
    ep = router_endpoint()
    if endpoint_answers(ep):
        return None
    return start_router([ep])
