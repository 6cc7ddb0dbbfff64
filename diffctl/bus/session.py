"""Zenoh sessions as rmw_zenoh sets them up: one peer session per process, connected to a router.

Peers connect to the router endpoint (env DIFFCTL_ROUTER, default tcp/127.0.0.1:7447), listen on
tcp/127.0.0.1:0 and never multicast-scout, so nothing is reachable beyond loopback unless a config says so.
rmw_zenoh's ZENOH_SESSION_CONFIG_URI / ZENOH_ROUTER_CONFIG_URI / ZENOH_CONFIG_OVERRIDE are honoured, and
ROS_DOMAIN_ID selects the domain (the first chunk of every key).
"""

from __future__ import annotations

import atexit
import json
import os
import socket
import threading
import time
import weakref
from collections.abc import Callable

import zenoh

from diffctl.errors import ConfigError, NoRouterError

DEFAULT_ROUTER = "tcp/127.0.0.1:7447"
CONNECT_TIMEOUT_MS = 1500

_session: zenoh.Session | None = None
_session_lock = threading.Lock()
_mode = "peer"
_log_initialised = False


def router_endpoint() -> str:
    return os.environ.get("DIFFCTL_ROUTER", DEFAULT_ROUTER)


def domain_id() -> int:
    raw = os.environ.get("ROS_DOMAIN_ID", "0") or "0"
    try:
        d = int(raw)
    except ValueError:
        raise ConfigError(f"ROS_DOMAIN_ID={raw!r} is not an integer", hint="valid: 0..232") from None
    if not 0 <= d <= 232:
        raise ConfigError(f"ROS_DOMAIN_ID={d} is out of range", hint="valid: 0..232")
    return d


def _init_log() -> None:
    global _log_initialised
    if not _log_initialised:
        zenoh.init_log_from_env_or("error")
        _log_initialised = True


def _apply_overrides(cfg: zenoh.Config) -> None:
    # rmw_zenoh's syntax: 'key/path=json5value;other/key=value'
    raw = os.environ.get("ZENOH_CONFIG_OVERRIDE", "").strip()
    for item in filter(None, (s.strip() for s in raw.split(";"))):
        if "=" not in item:
            raise ConfigError(f"ZENOH_CONFIG_OVERRIDE entry {item!r} must be key/path=value")
        k, v = item.split("=", 1)
        try:
            cfg.insert_json5(k.strip(), v.strip())
        except Exception as e:
            raise ConfigError(f"ZENOH_CONFIG_OVERRIDE entry {item!r}: {e}") from None


def _from_file(env: str) -> zenoh.Config | None:
    path = os.environ.get(env)
    if not path:
        return None
    try:
        return zenoh.Config.from_file(path)
    except Exception as e:
        raise ConfigError(f"cannot load Zenoh config: {e}", source=path, field=env) from None


def use_client_mode() -> None:
    """Open this process's session as a Zenoh client (before first use).

    One-shot graph tools (`topic list`, `node info`, …) need a complete picture at once: a client asks the
    router, which knows every token, whereas a fresh peer's first liveliness query can miss tokens still
    being gossiped. Long-running components stay peers, with direct links, as rmw_zenoh does.
    """
    global _mode
    _mode = "client"


def _fill_safe_defaults(cfg: zenoh.Config, mode: str, endpoint: str) -> None:
    """What a config file leaves unset gets diffctl's defaults, not Zenoh's: Zenoh's default listener is
    `tcp/[::]:<port>` (every interface) and it multicast-scouts the LAN. What the file does say is kept."""
    if json.loads(cfg.get_json("mode")) is None:
        cfg.insert_json5("mode", json.dumps(mode))
    mode = json.loads(cfg.get_json("mode"))
    if mode != "router" and not json.loads(cfg.get_json("connect/endpoints")):
        cfg.insert_json5("connect/endpoints", json.dumps([endpoint]))
    if isinstance(json.loads(cfg.get_json("listen/endpoints")), dict):  # unset: Zenoh's per-mode defaults
        loopback = {"router": [endpoint], "peer": ["tcp/127.0.0.1:0"]}.get(mode, [])
        cfg.insert_json5("listen/endpoints", json.dumps(loopback))
    if json.loads(cfg.get_json("scouting/multicast/enabled")) is None:
        cfg.insert_json5("scouting/multicast/enabled", "false")


def connect_endpoints(cfg: zenoh.Config) -> list[str]:
    """The endpoints a session built from `cfg` connects to (for messages naming them)."""
    eps = json.loads(cfg.get_json("connect/endpoints"))
    return [str(e) for e in eps] if isinstance(eps, list) else []


def peer_config(endpoint: str | None = None) -> zenoh.Config:
    cfg = _from_file("ZENOH_SESSION_CONFIG_URI")
    if cfg is None:
        cfg = zenoh.Config()
        cfg.insert_json5("mode", json.dumps(_mode))
        cfg.insert_json5("connect/endpoints", json.dumps([endpoint or router_endpoint()]))
        cfg.insert_json5("listen/endpoints", '["tcp/127.0.0.1:0"]' if _mode == "peer" else "[]")
        cfg.insert_json5("scouting/multicast/enabled", "false")
        cfg.insert_json5("scouting/gossip/enabled", "true")
    else:
        _fill_safe_defaults(cfg, _mode, endpoint or router_endpoint())
    # Zenoh maps a 16 MB shared-memory pool into every process that publishes a large sample; over loopback
    # TCP the copies are cheap, and seven such pools would blow the stack's memory budget.
    cfg.insert_json5("transport/shared_memory/enabled", "false")
    cfg.insert_json5("connect/timeout_ms", str(CONNECT_TIMEOUT_MS))
    cfg.insert_json5("connect/exit_on_failure", "true")
    # A session opened while its router is still starting (a tool started with the launch) tries again after
    # 0.1 s, not Zenoh's default 1 s: with that, it connected a second after the router was up.
    # A user's config file keeps its own.
    if json.loads(cfg.get_json("connect/retry")) is None:
        cfg.insert_json5("connect/retry", "{period_init_ms: 100, period_max_ms: 1000, period_increase_factor: 2}")
    # Advanced (latched) publishers need timestamps, as rmw_zenoh enables them.
    cfg.insert_json5("timestamping/enabled", "true")
    _apply_overrides(cfg)
    return cfg


def router_config(listen: list[str] | None = None, config_file: str | None = None) -> zenoh.Config:
    if config_file:
        try:
            cfg = zenoh.Config.from_file(config_file)
        except Exception as e:
            raise ConfigError(f"cannot load Zenoh router config: {e}", source=config_file) from None
    else:
        cfg = _from_file("ZENOH_ROUTER_CONFIG_URI")
        if cfg is None:
            cfg = zenoh.Config()
            cfg.insert_json5("listen/endpoints", json.dumps(listen or [router_endpoint()]))
            cfg.insert_json5("scouting/multicast/enabled", "false")
    if listen and config_file:
        cfg.insert_json5("listen/endpoints", json.dumps(listen))
    cfg.insert_json5("mode", '"router"')
    _fill_safe_defaults(cfg, "router", (listen or [router_endpoint()])[0])
    cfg.insert_json5("transport/shared_memory/enabled", "false")
    # A router otherwise waits 500 ms for scouting before it returns.
    cfg.insert_json5("scouting/delay", "0")
    cfg.insert_json5("timestamping/enabled", "true")
    _apply_overrides(cfg)
    return cfg


def open_session() -> zenoh.Session:
    """This process's peer session (opened on first use, closed at exit). NoRouterError when none answers."""
    global _session, _closing
    with _session_lock:
        if _session is None:
            _init_log()
            _closing = False
            _older_than_session.clear()
            _older_than_session.update(_zenoh_callback_threads())
            cfg = peer_config(router_endpoint())
            try:
                _session = zenoh.open(cfg)
            except zenoh.ZError as e:
                if "connect" in str(e).lower() or "timeout" in str(e).lower():
                    raise _no_router(connect_endpoints(cfg)) from None
                raise ConfigError(f"cannot open a Zenoh session: {e}") from None
            # Closed (and its callback threads joined) before the interpreter finalizes: threading's exit hooks
            # run before it waits for non-daemon threads; plain atexit handlers run after, too late for the
            # executors' and Zenoh's daemon threads.
            global _exit_hook
            if not _exit_hook:
                register = getattr(threading, "_register_atexit", atexit.register)
                register(_close_at_exit)
                _exit_hook = True
        return _session


_exit_hook = False
_exiting = False


def _close_at_exit() -> None:
    global _exiting
    _exiting = True
    close_session()


def exiting() -> bool:
    """Whether the session is closing because the interpreter is ending (the program returned or called
    sys.exit, with or without rclpy.shutdown())."""
    return _exiting


def _no_router(endpoints: list[str]) -> NoRouterError:
    """Nothing listening and a router that turned this session away look alike to Zenoh; a TCP probe tells
    them apart, so a refused certificate or password is not reported as a missing router."""
    where = ", ".join(endpoints) or router_endpoint()
    listening = [ep for ep in endpoints if _answers_quietly(ep)]
    if listening:
        config = os.environ.get("ZENOH_SESSION_CONFIG_URI")
        return NoRouterError(
            f"the Zenoh router at {', '.join(listening)} refused this session",
            hint="check the TLS certificate, user and password"
            + (f" in ZENOH_SESSION_CONFIG_URI={config}" if config else " (ZENOH_SESSION_CONFIG_URI)"),
        )
    return NoRouterError(
        f"no Zenoh router answers at {where}",
        hint="start one with `diffctl router`, or run `diffctl launch …`, which embeds one",
    )


def _answers_quietly(endpoint: str) -> bool:
    try:
        return endpoint_answers(endpoint)
    except ConfigError:
        return False


_before_close: list[Callable[[], None]] = []  # run in order
_closing = False
_join_after_close: weakref.WeakSet[threading.Thread] = weakref.WeakSet()
_older_than_session: weakref.WeakSet[threading.Thread] = weakref.WeakSet()  # another session's, not waited for
# zenoh-python runs each Python callback (subscriber, liveliness subscriber, reply handler, matching listener) on
# a daemon thread of its own, which threading names after its target.
ZENOH_CALLBACK_THREAD_SUFFIX = "(pyo3-closure)"
AFTER_CLOSE_JOIN_S = 5.0


def before_close(fn: Callable[[], None], *, first: bool = False) -> None:
    """Run `fn` when the process's session closes (at the latest at exit), before it does: the bus's and the
    client library's threads stop there (`first`: before the bus's own, as what runs user callbacks), so none
    is inside a Zenoh call or publishing when the session goes or the interpreter finalizes (a thread caught
    in Zenoh's Rust frames by finalization is cancelled, and that unwinding aborts the process: "FATAL:
    exception not rethrown")."""
    if fn not in _before_close:
        _before_close.insert(0, fn) if first else _before_close.append(fn)


def join_after_close(thread: threading.Thread) -> None:
    """`thread`, a daemon that may be inside a Zenoh call, has ended when close_session returns (the call fails
    fast once the session is closed; the thread then needs the interpreter once more to end)."""
    _join_after_close.add(thread)


def _zenoh_callback_threads() -> list[threading.Thread]:
    return [t for t in threading.enumerate() if t.name.endswith(ZENOH_CALLBACK_THREAD_SUFFIX)]


def _threads_into_python() -> list[threading.Thread]:
    me = threading.current_thread()
    ours = [t for t in _zenoh_callback_threads() if t not in _older_than_session]
    return [t for t in {*ours, *_join_after_close} if t is not me]


def _join_threads_into_python(timeout_s: float) -> None:
    """Closing the session ends Zenoh's callback threads, but they are daemons and nothing waits for them: one
    still waking from its channel when the interpreter finalizes is ended by CPython with pthread_exit inside
    zenoh-python's Rust frames, which aborts the process ("FATAL: exception not rethrown", exit -6)."""
    deadline = time.monotonic() + timeout_s
    for t in _threads_into_python():
        if t.is_alive():  # started, not ended (one registered just before its start is not joinable yet)
            t.join(max(0.0, deadline - time.monotonic()))


def closing() -> bool:
    """Whether the session is closing or closed (until another opens): publishing then is pointless and
    must stay silent."""
    return _closing


def close_session() -> None:
    global _session, _closing
    with _session_lock:
        if _session is None:
            return
        _closing = True
    for fn in list(_before_close):
        try:
            fn()
        except Exception:
            pass  # one part failing to stop must not keep the others (or the session) open
    with _session_lock:
        s, _session = _session, None
    if s is not None:
        try:
            s.close()
        except Exception:
            pass
        _join_threads_into_python(AFTER_CLOSE_JOIN_S)


def endpoint_answers(endpoint: str, timeout_s: float = 0.3) -> bool:
    """Whether something accepts TCP connections at a tcp/HOST:PORT endpoint (a router, presumably)."""
    host, port = parse_tcp_endpoint(endpoint)
    try:
        with socket.create_connection((host, port), timeout=timeout_s):
            return True
    except OSError:
        return False


def parse_tcp_endpoint(endpoint: str) -> tuple[str, int]:
    proto, _, addr = endpoint.partition("/")
    if proto not in ("tcp", "tls") or ":" not in addr:
        raise ConfigError(f"router endpoint {endpoint!r} is not of the form tcp/HOST:PORT")
    host, _, port = addr.rpartition(":")
    host = host.strip("[]")
    try:
        return host, int(port.split("#")[0])
    except ValueError:
        raise ConfigError(f"router endpoint {endpoint!r} has no valid port") from None
