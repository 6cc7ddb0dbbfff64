"""`diffctl router`: a Zenoh router alone, like rmw_zenoh's rmw_zenohd."""

from __future__ import annotations

import signal

import click


@click.command()
@click.option(
    "--listen",
    "listen",
    multiple=True,
    metavar="ENDPOINT",
    help="Endpoint to listen on (repeatable). Default: $DIFFCTL_ROUTER or tcp/127.0.0.1:7447.",
)
@click.option(
    "--config",
    "config_file",
    type=click.Path(dir_okay=False),
    default=None,
    help="A Zenoh JSON5 config file (TLS, user/password, access control, several listeners).",
)
def router(listen: tuple[str, ...], config_file: str | None) -> None:
    """Run a Zenoh router until Ctrl-C. Loopback only unless --listen or --config says otherwise.

    \b
    Example:
      diffctl router
      diffctl router --listen tcp/127.0.0.1:7448
      diffctl router --config config/router_tls.json5
    """
    from diffctl.bus.router import start_router
    from diffctl.bus.session import endpoint_answers, router_endpoint
    from diffctl.console import info
    from diffctl.errors import ConfigError
    from diffctl.signals import stop_on_signals

    eps = list(listen)
    if not config_file:
        for ep in eps or [router_endpoint()]:
            if ep.startswith("tcp/") and endpoint_answers(ep):
                raise ConfigError(f"something already listens on {ep}", hint="a router is running there already?")
    # before the port opens: a client may signal the router as soon as it answers
    stop = stop_on_signals(signal.SIGHUP)
    handle = start_router(eps or None, config_file)
    info(f"router {handle.zid} listening on {config_file or ', '.join(handle.endpoints)}")
    stop.wait()
    handle.close()
