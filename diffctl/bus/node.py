"""A ROS-like node on Zenoh: names, parameters, endpoints, clock, timers, logging, graph, spin.

All nodes of one process share its peer session and a per-session context (entity ids for liveliness
tokens, the graph cache, a small executor for service handlers, type-mismatch reporting).
"""

from __future__ import annotations

import os
import signal
import threading
import time
from collections.abc import Callable
from typing import Any

import zenoh

from diffctl import ros_args
from diffctl.bus import wire
from diffctl.bus.clock import Clock, Timer
from diffctl.bus.endpoints import Client, Publisher, Service, Subscription
from diffctl.bus.log import Logger
from diffctl.bus.parameter_services import ParameterServices
from diffctl.bus.parameters import ParameterDescriptor, ParameterStore
from diffctl.bus.participant import Participant
from diffctl.bus.rosout import Rosout
from diffctl.bus.session import router_endpoint
from diffctl.bus.type_description import TypeDescriptionService
from diffctl.errors import ConfigError


def _as_bool(value: Any) -> bool:
    if isinstance(value, str):
        return value.strip().lower() in ("true", "1", "yes", "on")
    return bool(value)


def validate_name(name: str, what: str = "node name") -> str:
    if not name or not all(c.isalnum() or c == "_" for c in name) or name[0].isdigit():
        raise ConfigError(f"invalid {what} {name!r}", hint="use letters, digits and '_', not starting with a digit")
    return name


class Node(Participant):
    def __init__(
        self,
        name: str,
        namespace: str = "/",
        *,
        use_sim_time: bool | None = None,
        remaps: dict[str, str] | None = None,
        params: dict[str, Any] | None = None,
        session: zenoh.Session | None = None,
        allow_undeclared_parameters: bool = True,
        parameter_store: ParameterStore | None = None,
        rosout: bool = True,
        parameter_services: bool = True,
        serve_parameters: bool = True,
    ) -> None:
        """`parameter_store` replaces the default store (the client library's, with rclpy's semantics);
        `rosout` and `parameter_services` False leave those standard endpoints out (rclpy's enable_rosout and
        start_parameter_services). `serve_parameters` False keeps `/parameter_events` but leaves the six
        parameter services to the caller (the client library answers them from its executor, as rclpy)."""
        self.name = validate_name(name)
        self.namespace = "/" + namespace.strip("/") if namespace and namespace != "/" else "/"
        self.params: dict[str, Any] = dict(params or {})
        if "use_sim_time" in self.params:
            # Launch files pass it as text ("true") as often as a bool; ROS reads both.
            self.params["use_sim_time"] = _as_bool(self.params["use_sim_time"])
        self.parameters = parameter_store if parameter_store is not None else ParameterStore(
            self.params, allow_undeclared=allow_undeclared_parameters)
        log = Logger(self.fqn[1:] if self.namespace == "/" else self.fqn[1:].replace("/", "."))
        super().__init__(self.name, self.namespace, log, session=session)
        self._remaps: dict[str, str] = {}
        for k, v in (remaps or {}).items():  # rcl: the first rule matching a name wins
            self._remaps.setdefault(self._expand(k), self._expand(v))
        self._stop = threading.Event()
        # Every ROS node's standard endpoints: /rosout, parameter services and events, type descriptions.
        self._builtin_services: dict[str, Service] = {}
        self._rosout = self._keep(Rosout(self)) if rosout else None
        self._parameter_services = (self._keep(ParameterServices(self, serve=serve_parameters))
                                    if parameter_services else None)
        if self._parameter_services is not None:
            self._builtin_services.update(self._parameter_services.services)
        self.clock = Clock(False)
        # The parameter says what the node was told; the constructor argument may still keep its clock on wall
        # time (a controller runs on its manager's clock, not its own /clock subscription).
        sim_param = self.declare_parameter(
            "use_sim_time", bool(use_sim_time) if use_sim_time is not None else False,
            ParameterDescriptor(type="bool", description="Use /clock instead of the wall clock"),
        )
        self._type_descriptions: TypeDescriptionService | None = None
        if self.declare_parameter("start_type_description_service", True,
                                  ParameterDescriptor(type="bool", read_only=True)):
            self._type_descriptions = self._keep(TypeDescriptionService(self))
            self._builtin_services[self._type_descriptions.service.name] = self._type_descriptions.service
            builtin: list[Any] = [self._type_descriptions.service]
            if self._parameter_services is not None:
                builtin += [*self._parameter_services.services.values(), self._parameter_services.events]
            if self._rosout is not None:
                builtin.append(self._rosout.pub)
            for ep in builtin:
                self._type_descriptions.use(ep.type)
        sim = sim_param if use_sim_time is None else use_sim_time
        self.clock = Clock(_as_bool(sim))
        self._clock_sub: Subscription | None = None
        if self.clock.use_sim_time:
            self._follow_clock(True)
        if use_sim_time is None:
            # As rclcpp's TimeSource: setting use_sim_time at run time switches the node's clock.
            self.parameters.add_listener(self._on_use_sim_time)

    def _follow_clock(self, on: bool) -> None:
        if on and self._clock_sub is None:
            # rclcpp's TimeSource subscribes best-effort, depth 1.
            self._clock_sub = self.create_subscription("/clock", "rosgraph_msgs/msg/Clock", self.clock.on_clock,
                                                       reliable=False, depth=1)
        elif not on and self._clock_sub is not None:
            self._clock_sub.close()
            self._closables.remove(self._clock_sub)
            self._clock_sub = None
        self.clock.use_sim_time = on

    def _on_use_sim_time(self, changes: list[Any]) -> None:
        for c in changes:
            if c.name == "use_sim_time" and c.kind == "changed" and bool(c.value) != self.clock.use_sim_time:
                self._follow_clock(bool(c.value))

    @classmethod
    def from_ros_args(cls, default_name: str, namespace: str = "/", *, defaults: dict[str, Any] | None = None,
                      **kwargs: Any) -> Node:
        """A node named and parameterised by this process's `--ros-args` (defaults first, then the args)."""
        ra = ros_args.current(default_name, namespace)
        params = {**(defaults or {}), **ra.params, **kwargs.pop("params", {})}
        return cls(ra.node_name or default_name, ra.namespace or namespace, remaps=ra.remaps, params=params,
                   **kwargs)

    # ------------------------------------------------------------------ names
    def _expand(self, name: str) -> str:
        if name.startswith("~"):
            return self.fqn + name[1:] if name != "~" else self.fqn
        if name.startswith("/"):
            return name
        return f"{self.namespace.rstrip('/')}/{name}"

    def resolve(self, name: str) -> str:
        """Fully qualified topic or service name, after `~`/namespace expansion and remapping."""
        if not name:
            raise ConfigError("empty topic or service name")
        full = self._expand(name)
        return self._remaps.get(full, full)

    # ------------------------------------------------------------------ parameters
    def declare_parameter(self, name: str, default: Any = None,
                          descriptor: ParameterDescriptor | None = None) -> Any:
        """Declare a parameter: its override (--ros-args, params) if given, else `default`; ConfigError if invalid."""
        return self.parameters.declare(name, default, descriptor)

    def get_parameter(self, name: str) -> Any:
        try:
            return self.parameters.get(name)
        except KeyError:
            raise ConfigError(f"node {self.fqn} has no parameter '{name}'") from None

    def has_parameter(self, name: str) -> bool:
        return self.parameters.has(name)

    def set_parameters(self, values: dict[str, Any]) -> list[str | None]:
        """Set each parameter on its own, as the set_parameters service does: a refusal reason or None each."""
        return self.parameters.set(values)

    def set_parameters_atomically(self, values: dict[str, Any]) -> str | None:
        return self.parameters.set_atomically(values)

    def add_on_set_parameters_callback(self, cb: Callable[[dict[str, Any]], str | None]) -> None:
        """`cb(changes)` runs before a set is applied; returning a reason refuses the whole set."""
        self.parameters.add_on_set_callback(cb)

    # ------------------------------------------------------------------ endpoints
    def _keep(self, obj: Any) -> Any:
        super()._keep(obj)
        td = getattr(self, "_type_descriptions", None)
        if td is not None and isinstance(obj, (Publisher, Subscription, Service, Client)):
            td.use(obj.type)
        return obj

    def create_service(self, name: str, srv_type: str, handler: Callable[[Any], Any], *,
                       qos: wire.QoS | None = None, raw: bool = False) -> Service:
        full = self.resolve(name)
        builtin = self._builtin_services.pop(full, None)
        if builtin is not None:
            # A component serving one of the node's standard services itself (the controller manager's own
            # set_parameters, kept while it moves onto declared parameters) replaces the built-in one.
            builtin.close()
        return self._keep(Service(self, name, srv_type, handler, qos=qos, raw=raw))

    def create_timer(self, period_s: float, callback: Callable[[], None]) -> Timer:
        return self._keep(Timer(self.clock, period_s, callback, self.log.error))

    # ------------------------------------------------------------------ time, graph
    def now_ns(self) -> int:
        return self.clock.now_ns()

    def now(self) -> Any:
        from diffctl.interfaces.types import time_msg

        return time_msg(self.now_ns())

    # ------------------------------------------------------------------ lifetime
    def request_shutdown(self) -> None:
        self._stop.set()

    @property
    def shutting_down(self) -> bool:
        return self._stop.is_set()

    def spin(self, *, watch_router: bool = True) -> None:
        """Block until SIGINT/SIGTERM (or request_shutdown), then close. Exits if the router disappears."""
        if threading.current_thread() is threading.main_thread():
            for sig in (signal.SIGINT, signal.SIGTERM):
                signal.signal(sig, lambda *_: self._stop.set())
        lost_since: float | None = None
        while not self._stop.wait(0.25):
            if not watch_router or os.environ.get("ZENOH_SESSION_CONFIG_URI"):
                continue
            if self.session.info.routers_zid():
                lost_since = None
            elif lost_since is None:
                lost_since = time.monotonic()
            elif time.monotonic() - lost_since > 1.0:
                self.log.error(f"lost the Zenoh router at {router_endpoint()}; shutting down")
                self.close()
                raise SystemExit(1)
        self.close()

    def close(self) -> None:
        self._stop.set()
        super().close()
