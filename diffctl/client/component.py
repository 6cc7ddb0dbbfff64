"""How each of diffctl's own nodes runs as its process: as an rclpy program runs.

`run(make)` initialises the client with the process's `--ros-args` (so `--log-level`, remaps and parameter
files apply as to any ROS node), builds the node with `make()`, spins it until SIGINT/SIGTERM, shutdown, or the
loss of the Zenoh router, then tears down in rclpy's order. `start(make)` is the same for a program whose main
thread has its own loop (a terminal, a game pad, a web server): the node spins on a thread of its own and
`stop()` tears it down. A parameter refused while `make()` declares it is bad input: one line naming the
parameter and the value, exit code 2, the node gone before it published.
"""

from __future__ import annotations

import os
import signal
import sys
import threading
import time
from collections.abc import Callable
from typing import Any

from diffctl import ros_args
from diffctl.client import exceptions, runtime
from diffctl.client.executors import ExternalShutdownException, SingleThreadedExecutor
from diffctl.errors import ConfigError

BAD_PARAMETER = (exceptions.InvalidParameterTypeException, exceptions.InvalidParameterValueException,
                 exceptions.ParameterUninitializedException)


def spin_once(executor: Any, node: Any) -> None:
    """One turn of the executor. A callback that raises (a message that decodes but makes no sense to it) is
    reported and the node goes on: bad input never ends one of diffctl's nodes (a user's rclpy node still
    ends, as rclpy's does)."""
    try:
        executor.spin_once()
    except (ExternalShutdownException, KeyboardInterrupt):
        raise
    except Exception as e:
        node.bus_node.throttled(f"callback{type(e).__name__}", f"a callback raised {type(e).__name__}: {e}",
                                level="ERROR")


def init() -> None:
    """The client, initialised once with this process's `--ros-args` (a no-op when already initialised)."""
    if not runtime.ok():
        runtime.init(args=["diffctl", "--ros-args", *ros_args.current_argv()])


def run(make: Callable[[], Any], *, executor: Any = None,
        on_stop: Callable[[BaseException], None] | None = None) -> int:
    """`on_stop(e)`: told what ended the spin (KeyboardInterrupt or ExternalShutdownException), for a program
    whose upstream says so (twist_stamper, relay_field print a line)."""
    init()
    lost = threading.Event()
    node = None
    try:
        try:
            node = make()
        except BAD_PARAMETER as e:
            raise ConfigError(str(e)) from None
        _watch_router(node, lost)
        executor = executor or SingleThreadedExecutor()
        executor.add_node(node)
        while runtime.ok():
            spin_once(executor, node)
    except (KeyboardInterrupt, ExternalShutdownException) as e:
        _deaf_to_interrupts()
        if on_stop is not None:
            on_stop(e)
    except exceptions.RCLError:
        # A SIGINT/SIGTERM that came while the node or its executor was being made shut the client down under
        # them (rclpy refuses them then): the node was asked to end, and ends.
        if runtime.ok():
            raise
    finally:
        _deaf_to_interrupts()
        if node is not None:
            node.destroy_node()
        runtime.try_shutdown()
        _deaf_to_interrupts()  # shutdown gave SIGINT back to Python's handler
        from diffctl.bus.session import close_session

        # Zenoh's callback threads are not daemons: close the session before the interpreter joins them.
        close_session()
    if lost.is_set():
        print(f"error: lost the Zenoh router at {_router()}; shut down", file=sys.stderr)
        return 1
    return 0


def _deaf_to_interrupts() -> None:
    """From here the node is ending: a further SIGINT (`diffctl run` and launch pass one on when the first
    seemed unheard; a second Ctrl-C) would raise KeyboardInterrupt in the middle of the teardown and end the
    process by the signal (exit 130) instead of cleanly. SIGTERM and SIGKILL, the escalation's next steps, still
    end a teardown that hangs."""
    if threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGINT, signal.SIG_IGN)


class Started:
    """A node spinning on its own thread; `stop()` (idempotent) destroys it and closes the session."""

    def __init__(self, node: Any) -> None:
        self.node = node
        self._executor = SingleThreadedExecutor()
        self._executor.add_node(node)
        self._thread = threading.Thread(target=self._spin, name="node-executor", daemon=True)
        self._thread.start()

    def _spin(self) -> None:
        node = self.node
        try:
            while runtime.ok():
                spin_once(self._executor, node)
        except ExternalShutdownException:
            pass

    def stop(self) -> None:
        if self.node is None:
            return
        node, self.node = self.node, None
        runtime.try_shutdown()
        self._thread.join(2.0)
        node.destroy_node()
        from diffctl.bus.session import close_session

        close_session()


def start(make: Callable[[], Any]) -> Started:
    init()
    try:
        node = make()
    except BaseException as e:
        # nothing spins yet: end the client and its session (Zenoh's threads would keep the process alive)
        runtime.try_shutdown()
        from diffctl.bus.session import close_session

        close_session()
        if isinstance(e, BAD_PARAMETER):
            raise ConfigError(str(e)) from None
        raise
    return Started(node)


def _router() -> str:
    from diffctl.bus.session import router_endpoint

    return router_endpoint()


def _watch_router(node: Any, lost: threading.Event) -> None:
    """A node whose router went away (the launch ended without signalling it) ends itself within 1.5 s."""
    if os.environ.get("ZENOH_SESSION_CONFIG_URI"):
        return  # a user's own topology: there may be no router to lose

    def watch() -> None:
        session = node.bus_node.session
        since: float | None = None
        while runtime.ok():
            time.sleep(0.25)
            try:
                present = bool(session.info.routers_zid())
            except Exception:
                return  # the session closed: the process is ending anyway
            if present:
                since = None
            elif since is None:
                since = time.monotonic()
            elif time.monotonic() - since > 1.0:
                lost.set()
                runtime.try_shutdown()
                return

    threading.Thread(target=watch, name="router-watch", daemon=True).start()

