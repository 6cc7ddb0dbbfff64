"""Session and router configs: shipped examples are safe as written, config files get loopback defaults for
what they leave out, TLS endpoints parse, and a router that turns a session away is not called missing."""

from __future__ import annotations

import json
import socket
from pathlib import Path

import pytest
import zenoh

from diffctl.bus import session
from diffctl.errors import NoRouterError
from tests.conftest import free_port

EXAMPLES = Path(__file__).resolve().parents[2] / "config" / "security"
WILDCARDS = ("0.0.0.0", "[::]")


def value(cfg: zenoh.Config, key: str):
    return json.loads(cfg.get_json(key))


@pytest.mark.parametrize("name", ["router_a", "router_b", "session", "client"])
def test_shipped_examples_load_and_expose_nothing_by_accident(name: str) -> None:
    cfg = zenoh.Config.from_file(str(EXAMPLES / f"{name}.json5"))
    listen = value(cfg, "listen/endpoints")
    assert isinstance(listen, list), f"{name} leaves listen/endpoints to Zenoh's all-interfaces default"
    assert not [ep for ep in listen if any(w in ep for w in WILDCARDS)]
    assert all(ep.startswith("tcp/127.0.0.1:") or ep.startswith("tls/") for ep in listen), listen
    assert value(cfg, "scouting/multicast/enabled") is False
    if name.startswith("router"):
        assert value(cfg, "transport/auth/usrpwd/dictionary_file")
        assert value(cfg, "transport/link/tls/enable_mtls") is True
    if name == "router_a":
        acl = value(cfg, "access_control")
        assert acl["enabled"] is True and acl["default_permission"] == "deny"
        rule_ids = {r["id"] for r in acl["rules"]}
        assert all(set(p["rules"]) <= rule_ids for p in acl["policies"])


def test_config_files_get_loopback_defaults(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    sparse = tmp_path / "sparse.json5"
    sparse.write_text('{ transport: { auth: { usrpwd: { user: "u", password: "p" } } } }')
    monkeypatch.setenv("DIFFCTL_ROUTER", "tls/[::1]:7448")
    monkeypatch.setenv("ZENOH_SESSION_CONFIG_URI", str(sparse))
    monkeypatch.delenv("ZENOH_CONFIG_OVERRIDE", raising=False)
    peer = session.peer_config(session.router_endpoint())
    assert value(peer, "mode") == "peer"
    assert value(peer, "listen/endpoints") == ["tcp/127.0.0.1:0"]
    assert value(peer, "connect/endpoints") == ["tls/[::1]:7448"]
    assert value(peer, "scouting/multicast/enabled") is False
    assert value(peer, "transport/auth/usrpwd/user") == "u"  # what the file says is kept
    # A router still starting is asked again after 0.1 s (Zenoh's default waits a whole second) …
    assert value(peer, "connect/retry")["period_init_ms"] == 100
    assert session.parse_tcp_endpoint("tls/[::1]:7448") == ("::1", 7448)

    explicit = tmp_path / "explicit.json5"
    explicit.write_text(
        '{ mode: "client", connect: { endpoints: ["tls/10.0.0.1:7448"], retry: { period_init_ms: 2500 } } }'
    )
    monkeypatch.setenv("ZENOH_SESSION_CONFIG_URI", str(explicit))
    client = session.peer_config(session.router_endpoint())
    assert value(client, "connect/endpoints") == ["tls/10.0.0.1:7448"]
    assert value(client, "connect/retry")["period_init_ms"] == 2500  # … unless the file says otherwise
    assert value(client, "listen/endpoints") == []

    router = session.router_config(config_file=str(sparse))
    assert value(router, "mode") == "router"
    assert value(router, "listen/endpoints") == ["tls/[::1]:7448"]  # DIFFCTL_ROUTER, not Zenoh's tcp/[::]
    assert value(router, "scouting/multicast/enabled") is False
    router = session.router_config(listen=["tcp/127.0.0.1:7450"], config_file=str(sparse))
    assert value(router, "listen/endpoints") == ["tcp/127.0.0.1:7450"]


def test_refused_session_is_not_reported_as_a_missing_router() -> None:
    with socket.socket() as listener:
        listener.bind(("127.0.0.1", 0))
        listener.listen()
        port = listener.getsockname()[1]
        refused = session._no_router([f"tls/127.0.0.1:{port}"])
    assert isinstance(refused, NoRouterError)
    assert f"router at tls/127.0.0.1:{port} refused this session" in str(refused)
    assert "certificate" in str(refused)
    missing = session._no_router([f"tcp/127.0.0.1:{free_port()}"])
    assert "no Zenoh router answers" in str(missing) and "diffctl router" in str(missing)
