"""rclpy.node.Node: the one node of diffctl, users' and its own components' alike — liveliness token, parameter
services and events, /rosout, type descriptions, use_sim_time — with rclpy's API and its executor model.

Names, remaps, parameter overrides and the node's name and namespace come from --ros-args through
diffctl.ros_args (global arguments first, then `cli_args`, then `parameter_overrides=`).
"""

from __future__ import annotations

import struct
import sys
import threading
import time
from collections.abc import Callable, Iterator
from typing import Any

from diffctl import ros_args
from diffctl.bus import wire
from diffctl.bus.participant import Participant
from diffctl.bus.session import closing
from diffctl.client import qos as _qos
from diffctl.client import ros_logging, waiting
from diffctl.client.callback_groups import CallbackGroup, MutuallyExclusiveCallbackGroup, ReentrantCallbackGroup
from diffctl.client.client import Client
from diffctl.client.clock import Clock, ROSClock
from diffctl.client.context import Context, get_default_context
from diffctl.client.destroyable import handle_of
from diffctl.client.event_handler import PublisherEventCallbacks, SubscriptionEventCallbacks
from diffctl.client.exceptions import (
    NodeNameNonExistentError,
    NotInitializedException,
    RCLError,
    RCLInvalidROSArgsError,
    UnknownROSArgsError,
)
from diffctl.client.guard_condition import GuardCondition
from diffctl.client.interfaces import cls, serialize, type_name
from diffctl.client.names import (
    expand_topic_name,
    namespace_problem,
    node_name_problem,
    normalize_namespace,
    resolve_name,
    rmw_result_code,
    validate_full_topic_name,
    validate_namespace,
    validate_node_name,
    validate_topic_name,
)
from diffctl.client.node_parameters import NodeParameters
from diffctl.client.parameter import Parameter, from_python_value
from diffctl.client.publisher import Publisher
from diffctl.client.qos_overriding_options import QoSOverridingOptions, declare_qos_parameters
from diffctl.client.ros_logging import RcutilsLogger, get_logger
from diffctl.client.ros_time import Time
from diffctl.client.rosout import Rosout
from diffctl.client.service import Service
from diffctl.client.subscription import Subscription
from diffctl.client.timer import Rate, Timer
from diffctl.client.topic_endpoint_info import TopicEndpointInfo, TopicEndpointTypeEnum  # noqa: F401 (rclpy.node has it)
from diffctl.client.type_support import check_is_valid_msg_type, check_is_valid_srv_type
from diffctl.client.waitable import Waitable
from diffctl.errors import ConfigError, NoRouterError

CLOCK_TOPIC = "/clock"
USE_SIM_TIME_NAME = "use_sim_time"
# rmw_qos_profile_parameter_events: reliable, volatile, keep_last 1000
PARAMETER_EVENTS_QOS = wire.QoS(depth=1000)
# What rclcpp lets a user override on /parameter_events and on the time source's /clock subscription
_ALL_OVERRIDES = QoSOverridingOptions([_qos.QoSPolicyKind.DEPTH, _qos.QoSPolicyKind.DURABILITY,
                                       _qos.QoSPolicyKind.HISTORY, _qos.QoSPolicyKind.RELIABILITY])


_CLOCK_STAMP = struct.Struct("<iI")
# rcl's words for a timer or guard condition made in a context that was shut down
_CONTEXT_GONE = ("the given context is not valid, either rcl_init() was not called or rcl_shutdown() was called., "
                 "at /project/src/rcl/guard_condition.c:67")


class TimeSource:
    """use_sim_time: the node's ROS clocks follow /clock (best effort, depth 1) while it is true.

    An rclpy node takes /clock as rclpy does, through a subscription of its own that its executor serves: its
    time moves only while an executor runs its callbacks, never during one of them in a single-threaded
    executor, and stays 0 until the node is in one. An rclcpp-flavoured node follows at once on Zenoh's thread,
    as rclcpp's clock thread does.
    """

    def __init__(self, *, node: Node | None = None) -> None:
        self._node: Node | None = None
        self._clocks: list[ROSClock] = []
        self._active = False
        self._clock_sub: Any = None
        self._last_ns = 0
        # Held while a /clock sample is applied and while the subscription is let go: a sample being applied on
        # another thread must not move the clocks after use_sim_time went false or the node was detached (a
        # hosting simulator's override was overwritten by a /clock tick in flight).
        self._following = threading.RLock()
        self._follows = False
        if node is not None:
            self.attach_node(node)

    def attach_node(self, node: Node) -> None:
        """Follow `node`'s use_sim_time (declared false when it is not yet) and, while it is true, its /clock.
        A node attached before is detached first."""
        if not isinstance(node, Node):
            raise TypeError("Node must be of type rclpy.node.Node")
        if self._node is not None:
            self.detach_node()
        self._node = node
        if not node.has_parameter(USE_SIM_TIME_NAME):
            node.declare_parameter(USE_SIM_TIME_NAME, False)
        p = node.get_parameter(USE_SIM_TIME_NAME)
        if p.type_ == Parameter.Type.BOOL:
            self.ros_time_is_active = p.value
        elif p.type_ != Parameter.Type.NOT_SET:
            node.get_logger().error(f"Invalid type for parameter '{USE_SIM_TIME_NAME}' {p.type_!r} should be bool")
        if self._active and self._clock_sub is None:  # already following time: the new node's /clock now
            self._follow(node)
        node.add_on_set_parameters_callback(self._on_parameters)

    def _get_node(self) -> Node | None:
        return self._node

    @property
    def ros_time_is_active(self) -> bool:
        return self._active

    @ros_time_is_active.setter
    def ros_time_is_active(self, enabled: bool) -> None:
        if enabled == self._active:
            return
        self._active = enabled
        for c in self._clocks:
            c._set_ros_time_is_active(enabled)
        node = self._node
        if node is None:  # detached: whoever detached it sets the time (set_ros_time_override)
            return
        if enabled and self._clock_sub is None:
            self._follow(node)
        elif not enabled and self._clock_sub is not None:
            self._stop_following(node)

    def _follow(self, node: Node) -> None:
        qos = _qos.QoSProfile(depth=1, reliability=_qos.ReliabilityPolicy.BEST_EFFORT)
        self._follows = True
        if node._rclcpp:
            declare_qos_parameters("subscription", node, CLOCK_TOPIC, qos, _ALL_OVERRIDES, rclcpp=True)
            self._clock_sub = node._bus.create_subscription(CLOCK_TOPIC, "rosgraph_msgs/msg/Clock", self._on_clock,
                                                            raw=True, qos=wire.QoS(reliable=False, depth=1))
        else:
            self._clock_sub = node.create_subscription(cls("rosgraph_msgs/msg/Clock"), CLOCK_TOPIC, self._on_clock,
                                                       qos, raw=True)

    def clock_callback(self, msg: Any) -> None:
        """rclpy's: take the time of a rosgraph_msgs/msg/Clock message for the attached clocks."""
        with self._following:
            self.set_time_ns(Time.from_msg(msg.clock).nanoseconds)

    def _on_clock(self, data: bytes) -> None:
        # builtin_interfaces/Time right after the little-endian CDR header: sec (int32), nanosec (uint32)
        valid = len(data) >= 12 and data[:2] == b"\x00\x01"
        if valid:
            sec, nanosec = _CLOCK_STAMP.unpack_from(data, 4)
            valid = sec >= 0 and nanosec < 1_000_000_000
        with self._following:
            if not self._follows:
                return
            if not valid:  # a time no clock can hold: dropped, the node's clock keeps its time
                if self._node is not None:
                    self._node._bus.throttled("clock", f"dropped a malformed sample on {CLOCK_TOPIC}")
                return
            self.set_time_ns(sec * 1_000_000_000 + nanosec)

    def _stop_following(self, node: Node) -> None:
        with self._following:
            self._follows = False
        sub, self._clock_sub = self._clock_sub, None
        if node._rclcpp:
            node._bus.destroy(sub)
        else:
            node.destroy_subscription(sub)

    def set_time_ns(self, ns: int) -> None:
        """The ROS time of this node's clocks while use_sim_time holds (from /clock, or from a simulator
        hosting the node, which needs no /clock round trip)."""
        self._last_ns = ns
        for c in self._clocks:
            c._set_override_ns(ns)

    def detach_node(self) -> None:
        """rclpy's: stop following the node's /clock and use_sim_time; the clocks keep their state, and their
        time comes from `set_ros_time_override` from now on."""
        node, self._node = self._node, None
        if node is None:
            return
        if self._clock_sub is not None:
            self._stop_following(node)
        node.remove_on_set_parameters_callback(self._on_parameters)

    def attach_clock(self, clock: ROSClock) -> None:
        if not isinstance(clock, ROSClock):
            raise ValueError("Only clocks with type ROS_TIME can be attached.")
        clock._set_override_ns(self._last_ns)
        clock._set_ros_time_is_active(self._active)
        self._clocks.append(clock)

    def _on_parameters(self, parameter_list: list[Parameter]) -> Any:
        ok, reason = True, ""
        for p in parameter_list:
            if p.name == "use_sim_time":
                if p.type_ == Parameter.Type.BOOL:
                    self.ros_time_is_active = p.value
                else:
                    ok, reason = False, "use_sim_time parameter set to something besides a bool"
                    if self._node is not None:
                        self._node.get_logger().error(reason)
                break
        return cls("rcl_interfaces/msg/SetParametersResult")(successful=ok, reason=reason)


class Node:
    PARAM_REL_TOL = 1e-6

    def __init__(self, node_name: str, *, context: Context | None = None, cli_args: list[str] | None = None,
                 namespace: str | None = None, use_global_arguments: bool = True, enable_rosout: bool = True,
                 start_parameter_services: bool = True, parameter_overrides: list[Parameter] | None = None,
                 allow_undeclared_parameters: bool = False,
                 automatically_declare_parameters_from_overrides: bool = False,
                 enable_logger_service: bool = False, client_library: str = "rclpy",
                 start_parameter_event_publisher: bool = True) -> None:
        """`client_library="rclcpp"` (diffctl's own addition) makes the node declare what an rclcpp node
        declares — the read-only QoS overrides of /parameter_events (and of /clock with use_sim_time), rclcpp's
        descriptions — so a diffctl component ROS writes in C++ lists the parameters the real one lists.
        `start_parameter_event_publisher=False` (rclcpp's NodeOptions, as rosbag2's recorder sets it): no
        /parameter_events publisher, so neither its events nor, for rclcpp, its QoS override parameters."""
        self._rclcpp = client_library == "rclcpp"
        self._context = get_default_context() if context is None else context
        self._publishers: list[Publisher] = []
        self._subscriptions: list[Subscription] = []
        self._clients: list[Client] = []
        self._services: list[Service] = []
        self._timers: list[Timer] = []
        self._guards: list[GuardCondition] = []
        self._waitables: list[Any] = []
        # those whose add_to_wait_set does something: the executor calls it before each wait
        self._joining_waitables: list[Any] = []
        self._default_callback_group = MutuallyExclusiveCallbackGroup()
        self._rate_group = ReentrantCallbackGroup()
        self._executor_ref: Any = None
        self._destroyed = False
        if not self._context.ok():
            raise NotInitializedException("cannot create node")
        if node_name is None:  # pybind11 hands None to rcl as a null pointer
            raise RCLError("error creating node: name argument is null, at /project/src/rcl/node.c:129")
        if not isinstance(node_name, str) or not isinstance(namespace, (str, type(None))):
            raise TypeError("__init__(): incompatible constructor arguments: the node name and namespace must be str, "
                            f"not {type(node_name).__name__} and {type(namespace).__name__}")
        validate_node_name(node_name)
        namespace = normalize_namespace(namespace)
        validate_namespace(namespace)

        # The process's arguments are global, cli_args the node's own (local: they win), as rcl has them; the
        # namespace takes part in matching parameter-file keys (/ns/name, /**/name).
        glob = ros_args.split_argv(self._context.args)[1] if use_global_arguments else []
        local = ros_args.split_argv(list(cli_args))[1] if cli_args else []
        try:
            ra = ros_args.parse(glob, node_name, namespace, local_argv=local)
        except ros_args.UnknownRosArgsError as e:
            raise UnknownROSArgsError(str(e.unknown)) from None
        except ConfigError as e:
            raise RCLInvalidROSArgsError(f"Failed to parse ROS arguments: {e}") from None
        name = ra.node_name or node_name
        if ra.namespace:
            namespace = normalize_namespace(ra.namespace)
        validate_node_name(name)
        validate_namespace(namespace)
        overrides = {k: from_python_value(k, v) for k, v in ra.params.items()}
        if parameter_overrides is not None:
            overrides.update({p.name: p for p in parameter_overrides})
        self._parameter_overrides = overrides
        self._logger_name = (f"{namespace.strip('/')}/{name}" if namespace != "/" else name).replace("/", ".")
        self._logger = get_logger(self._logger_name)
        try:
            self._bus = Participant(name, namespace, self._logger)
        except NoRouterError as e:
            print(f"error: {e}", file=sys.stderr)
            raise SystemExit(2) from None
        self._remaps: dict[str, str] = {}
        for k, v in ra.remaps.items():  # rcl: the first rule matching a name wins
            try:
                self._remaps.setdefault(self._expand(k), self._expand(v))
            except Exception:
                continue  # a rule for a name this node cannot have
        self._params = NodeParameters(overrides=overrides, allow_undeclared=allow_undeclared_parameters,
                                      rclcpp=self._rclcpp)
        self._parameter_events = None
        if start_parameter_event_publisher:
            self._parameter_events = self._bus.create_publisher(
                "/parameter_events", "rcl_interfaces/msg/ParameterEvent", qos=PARAMETER_EVENTS_QOS)
            # Listed in `publishers` as rclpy lists its own; events go out raw from the bus publisher. No
            # default QoS event handlers: they would watch the graph on behalf of every node in the process.
            self._parameter_events.client_node = self
            self._publishers.append(Publisher(
                self._parameter_events, cls("rcl_interfaces/msg/ParameterEvent"), "/parameter_events",
                _qos.qos_profile_parameter_events, callback_group=self._default_callback_group,
                event_callbacks=PublisherEventCallbacks(use_default_callbacks=False)))
            self._params.on_event = self._publish_parameter_event
        self._rosout = (Rosout(self._bus, self._logger_name, self._context)
                        if enable_rosout and ros_logging.rosout_enabled else None)
        if automatically_declare_parameters_from_overrides:
            desc = cls("rcl_interfaces/msg/ParameterDescriptor")
            self.declare_parameters("", [(n, p.value, desc()) for n, p in overrides.items()], ignore_override=True)
        if start_parameter_services:
            from diffctl.client.parameter_service import ParameterService

            self._parameter_service = ParameterService(self)
        self._clock = ROSClock()
        self._time_source = TimeSource(node=self)
        self._time_source.attach_clock(self._clock)
        from diffctl.client.type_description_service import TypeDescriptionService

        self._type_description_service = TypeDescriptionService(self)
        if self._rclcpp and self._parameter_events is not None:
            declare_qos_parameters("publisher", self, "/parameter_events",
                                   _qos.QoSProfile(depth=1000), _ALL_OVERRIDES, rclcpp=True)
        if enable_logger_service:
            from diffctl.client.logging_service import LoggingService

            self._logger_service = LoggingService(self)
        self._context.track_node(self)

    def _publish_parameter_event(self, new: list[Parameter], changed: list[Parameter],
                                 deleted: list[Parameter]) -> None:
        pub = self._parameter_events
        if pub is None or closing() or pub.closed:
            return  # the process is ending: nobody will see the event, and a warning would only alarm
        clock = getattr(self, "_clock", None)
        event = cls("rcl_interfaces/msg/ParameterEvent")(
            stamp=clock.now().to_msg() if clock is not None else Time(nanoseconds=time.time_ns()).to_msg(),
            node=self.get_fully_qualified_name(), new_parameters=[p.to_parameter_msg() for p in new],
            changed_parameters=[p.to_parameter_msg() for p in changed],
            deleted_parameters=[p.to_parameter_msg() for p in deleted])
        try:
            pub.publish_raw(serialize(event))
        except Exception as e:  # a closed session at shutdown must not fail the set that caused the event
            if not closing():
                self._bus.throttled("parameter_events",
                                    f"could not publish /parameter_events: {type(e).__name__}: {e}")

    # ------------------------------------------------------------------ identity
    @property
    def publishers(self) -> Iterator[Publisher]:
        yield from self._publishers

    @property
    def subscriptions(self) -> Iterator[Subscription]:
        yield from self._subscriptions

    @property
    def clients(self) -> Iterator[Client]:
        yield from self._clients

    @property
    def services(self) -> Iterator[Service]:
        yield from self._services

    @property
    def timers(self) -> Iterator[Timer]:
        yield from self._timers

    @property
    def guards(self) -> Iterator[GuardCondition]:
        yield from self._guards

    @property
    def waitables(self) -> Iterator[Any]:
        yield from self._waitables

    @property
    def executor(self) -> Any:
        return self._executor_ref() if self._executor_ref is not None else None

    @executor.setter
    def executor(self, new_executor: Any) -> None:
        import weakref

        current = self.executor
        if current is new_executor:
            return
        if current is not None:
            current.remove_node(self)
        if new_executor is None:
            self._executor_ref = None
        else:
            # Executor.add_node sets this property while it adds the node (then add_node answers False).
            new_executor.add_node(self)
            self._executor_ref = weakref.ref(new_executor)

    def _wake_executor(self) -> None:
        waiting.notify()

    @property
    def context(self) -> Context:
        return self._context

    @property
    def default_callback_group(self) -> CallbackGroup:
        return self._default_callback_group

    def __enter__(self) -> Node:
        return self

    def __exit__(self, *exc: Any) -> None:
        self.destroy_node()

    def _refuse_handle(self, value: Any) -> None:
        raise AttributeError("handle cannot be modified after node creation")

    # `with node.handle:` raises InvalidHandle once the node is destroyed; the handle is the node's for good
    handle = property(handle_of, _refuse_handle)

    @property
    def bus_node(self) -> Participant:
        """This node on the wire (diffctl.bus.participant): its session, graph and raw endpoints."""
        return self._bus

    def get_name(self) -> str:
        return self._bus.name

    def get_namespace(self) -> str:
        return self._bus.namespace

    def get_fully_qualified_name(self) -> str:
        return self._bus.fqn

    def get_clock(self) -> Clock:
        return self._clock

    def get_logger(self) -> RcutilsLogger:
        return self._logger

    # ------------------------------------------------------------------ rclcpp's accessors (diffctl's additions)
    def get_parameter_overrides(self) -> dict[str, Parameter]:
        """rclcpp's `get_node_parameters_interface()->get_parameter_overrides()`: the values this node was
        started with (the parameter files' and -p rules' matching it, then `parameter_overrides=`), by name,
        declared or not."""
        return dict(self._parameter_overrides)

    def get_node_time_source_interface(self) -> TimeSource:
        """rclcpp's accessor of the node's time source, an rclpy TimeSource: `detach_node()` leaves /clock and
        use_sim_time to whoever then drives the node's clock (`set_ros_time_override`), as a simulator hosting
        the node does."""
        return self._time_source

    # ------------------------------------------------------------------ parameters
    def declare_parameter(self, name: str, value: Any = None, descriptor: Any = None,
                          ignore_override: bool = False) -> Parameter:
        if value is None and descriptor is None:
            args: tuple = (name,)
        else:
            args = (name, value, cls("rcl_interfaces/msg/ParameterDescriptor")() if descriptor is None else descriptor)
        return self.declare_parameters("", [args], ignore_override)[0]

    def declare_parameters(self, namespace: str, parameters: list[tuple], ignore_override: bool = False
                           ) -> list[Parameter]:
        return self._params.declare_parameters(namespace, parameters, ignore_override)

    def undeclare_parameter(self, name: str) -> None:
        self._params.undeclare_parameter(name)

    def has_parameter(self, name: str) -> bool:
        return name in self._params.parameters

    def get_parameter_types(self, names: list[str]) -> list[Any]:
        if not all(isinstance(n, str) for n in names):
            raise TypeError("All names must be instances of type str")
        return [self.get_parameter_type(n) for n in names]

    def get_parameter_type(self, name: str) -> Any:
        return self._params.get_parameter_type(name)

    def get_parameters(self, names: list[str]) -> list[Parameter]:
        if not all(isinstance(n, str) for n in names):
            raise TypeError("All names must be instances of type str")
        return [self.get_parameter(n) for n in names]

    def get_parameter(self, name: str) -> Parameter:
        return self._params.get_parameter(name)

    def get_parameter_or(self, name: str, alternative_value: Parameter | None = None) -> Parameter:
        return self._params.get_parameter_or(name, alternative_value)

    def get_parameters_by_prefix(self, prefix: str) -> dict[str, Parameter]:
        return self._params.get_parameters_by_prefix(prefix)

    def set_parameters(self, parameter_list: list[Parameter]) -> list[Any]:
        return self._params.set_parameters(parameter_list)

    def set_parameters_atomically(self, parameter_list: list[Parameter]) -> Any:
        return self._params.set_parameters_atomically(parameter_list)

    def list_parameters(self, prefixes: list[str], depth: int) -> Any:
        return self._params.list_parameters(prefixes, depth)

    def describe_parameter(self, name: str) -> Any:
        return self._params.describe_parameter(name)

    def describe_parameters(self, names: list[str]) -> list[Any]:
        return [self.describe_parameter(n) for n in names]

    def set_descriptor(self, name: str, descriptor: Any, alternative_value: Any = None) -> Any:
        return self._params.set_descriptor(name, descriptor, alternative_value)

    def add_pre_set_parameters_callback(self, callback: Callable[[list[Parameter]], list[Parameter]]) -> None:
        self._params.pre_set.insert(0, callback)

    def add_on_set_parameters_callback(self, callback: Callable[[list[Parameter]], Any]) -> None:
        if not callable(callback):
            raise TypeError("Callback must be callable, got {}", type(callback))
        self._params.on_set.insert(0, callback)

    def add_post_set_parameters_callback(self, callback: Callable[[list[Parameter]], None]) -> None:
        if not callable(callback):
            raise TypeError("Callback must be callable, got {}", type(callback))
        self._params.post_set.insert(0, callback)

    def remove_pre_set_parameters_callback(self, callback: Callable[..., Any]) -> None:
        self._params.pre_set.remove(callback)

    def remove_on_set_parameters_callback(self, callback: Callable[..., Any]) -> None:
        self._params.on_set.remove(callback)

    def remove_post_set_parameters_callback(self, callback: Callable[..., Any]) -> None:
        self._params.post_set.remove(callback)

    # rclpy's own lists under rclpy's names: community code counts them (`len(node._on_set_parameters_callbacks)`)
    # before it adds one
    @property
    def _pre_set_parameters_callbacks(self) -> list[Callable[[list[Parameter]], list[Parameter]]]:
        return self._params.pre_set

    @property
    def _on_set_parameters_callbacks(self) -> list[Callable[[list[Parameter]], Any]]:
        return self._params.on_set

    @property
    def _post_set_parameters_callbacks(self) -> list[Callable[[list[Parameter]], None]]:
        return self._params.post_set

    # ------------------------------------------------------------------ names
    def _validate_topic_or_service_name(self, name: str, *, is_service: bool = False) -> None:
        validate_node_name(self.get_name())
        validate_namespace(self.get_namespace())
        validate_topic_name(name, is_service=is_service)
        validate_full_topic_name(expand_topic_name(name, self.get_name(), self.get_namespace()),
                                 is_service=is_service)

    def resolve_topic_name(self, topic: str, *, only_expand: bool = False) -> str:
        return resolve_name(topic, self.get_name(), self.get_namespace(), self._remaps, only_expand=only_expand)

    def resolve_service_name(self, service: str, *, only_expand: bool = False) -> str:
        return resolve_name(service, self.get_name(), self.get_namespace(), self._remaps, only_expand=only_expand)

    def _resolve_for_entity(self, name: str, *, is_service: bool) -> str:
        """The name an endpoint gets; a bad one raises rclpy's Invalid{Topic,Service}NameException naming the
        user's name and the offending character, as rclpy's create_* do after rcl refused it."""
        try:
            return resolve_name(name, self.get_name(), self.get_namespace(), self._remaps)
        except RCLError:
            self._validate_topic_or_service_name(name, is_service=is_service)
            raise  # a remap rule made it invalid: rcl's own words

    def _check_context(self, what: str) -> None:
        """rcl refuses to make or query anything through a node whose context was shut down."""
        if not self._context._ok:
            raise RCLError(f"{what}: rcl node's context is invalid, at /project/src/rcl/node.c:404")

    # ------------------------------------------------------------------ entities
    def add_waitable(self, waitable: Any) -> None:
        self._waitables.append(waitable)
        if getattr(type(waitable), "add_to_wait_set", Waitable.add_to_wait_set) is not Waitable.add_to_wait_set:
            self._joining_waitables.append(waitable)
        self._wake_executor()

    def remove_waitable(self, waitable: Any) -> None:
        if waitable in self._waitables:
            self._waitables.remove(waitable)
            if waitable in self._joining_waitables:
                self._joining_waitables.remove(waitable)
            self._wake_executor()

    def create_publisher(self, msg_type: Any, topic: str, qos_profile: Any, *,
                         callback_group: CallbackGroup | None = None, event_callbacks: Any = None,
                         qos_overriding_options: Any = None, publisher_class: type = Publisher) -> Publisher:
        qos_profile = _qos.as_profile(qos_profile)
        callback_group = callback_group or self.default_callback_group
        full = self._resolve_for_entity(topic, is_service=False)
        if qos_overriding_options is not None:
            declare_qos_parameters("publisher", self, full, qos_profile, qos_overriding_options, rclcpp=self._rclcpp)
        check_is_valid_msg_type(msg_type)
        typename = type_name(msg_type)
        self._check_context("Failed to create publisher")
        bus_pub = self._bus.create_publisher(full, typename, qos=_qos.to_wire(qos_profile))
        bus_pub.client_node = self
        pub = publisher_class(bus_pub, msg_type, topic, qos_profile,
                              event_callbacks=event_callbacks or PublisherEventCallbacks(),
                              callback_group=callback_group)
        self._publishers.append(pub)
        self._wake_executor()
        for h in pub.event_handlers:
            self.add_waitable(h)
        return pub

    def create_subscription(self, msg_type: Any, topic: str, callback: Callable[..., Any], qos_profile: Any, *,
                            callback_group: CallbackGroup | None = None, event_callbacks: Any = None,
                            qos_overriding_options: Any = None, raw: bool = False) -> Subscription:
        qos_profile = _qos.as_profile(qos_profile)
        callback_group = callback_group or self.default_callback_group
        full = self._resolve_for_entity(topic, is_service=False)
        if qos_overriding_options is not None:
            declare_qos_parameters("subscription", self, full, qos_profile, qos_overriding_options,
                                   rclcpp=self._rclcpp)
        check_is_valid_msg_type(msg_type)
        typename = type_name(msg_type)
        self._check_context("Failed to create subscription")
        sub = Subscription(self, msg_type, topic, callback, callback_group, qos_profile, raw,
                           event_callbacks=event_callbacks or SubscriptionEventCallbacks())
        bus_sub = self._bus.create_subscription(full, typename, sub._on_sample, raw=True, samples=True,
                                                qos=_qos.to_wire(qos_profile))
        sub._attach(bus_sub)
        callback_group.add_entity(sub)
        self._subscriptions.append(sub)
        self._wake_executor()
        for h in sub.event_handlers:
            self.add_waitable(h)
        return sub

    def create_client(self, srv_type: Any, srv_name: str, *, qos_profile: Any = None,
                      callback_group: CallbackGroup | None = None) -> Client:
        qos_profile = _qos.qos_profile_services_default if qos_profile is None else qos_profile
        callback_group = callback_group or self.default_callback_group
        check_is_valid_srv_type(srv_type)
        srv_type_name = type_name(srv_type)
        self._check_context("failed to create client")
        full = self._resolve_for_entity(srv_name, is_service=True)
        client = Client(self, srv_type, srv_name, qos_profile, callback_group)
        client._bus = self._bus.create_client(full, srv_type_name, qos=_qos.to_wire(qos_profile))
        callback_group.add_entity(client)
        self._clients.append(client)
        self._wake_executor()
        return client

    def create_service(self, srv_type: Any, srv_name: str, callback: Callable[[Any, Any], Any], *,
                       qos_profile: Any = None, callback_group: CallbackGroup | None = None) -> Service:
        qos_profile = _qos.qos_profile_services_default if qos_profile is None else qos_profile
        callback_group = callback_group or self.default_callback_group
        check_is_valid_srv_type(srv_type)
        srv_type_name = type_name(srv_type)
        self._check_context("failed to create service")
        full = self._resolve_for_entity(srv_name, is_service=True)
        service = Service(self, srv_type, srv_name, callback, callback_group, qos_profile)
        service._bus = self._bus.create_service(full, srv_type_name, service._on_query,
                                                qos=_qos.to_wire(qos_profile), raw=True)
        callback_group.add_entity(service)
        self._services.append(service)
        self._wake_executor()
        return service

    def _create_builtin_service(self, srv_type_name: str, srv_name: str, callback: Callable[[Any, Any], Any], *,
                                qos_profile: Any) -> Service:
        """A service every node has (parameters, type description): made by type name, its generated classes
        only on its first request, so a node's start does not generate seven service types nobody may call."""
        full = self._resolve_for_entity(srv_name, is_service=True)
        group = self.default_callback_group
        service = Service(self, srv_type_name, srv_name, callback, group, qos_profile)
        service._bus = self._bus.create_service(full, srv_type_name, service._on_query,
                                                qos=_qos.to_wire(qos_profile), raw=True)
        group.add_entity(service)
        self._services.append(service)
        self._wake_executor()
        return service

    def create_timer(self, timer_period_sec: float, callback: Callable[[], Any] | None,
                     callback_group: CallbackGroup | None = None, clock: Clock | None = None,
                     autostart: bool = True) -> Timer:
        period_ns = int(float(timer_period_sec) * 1_000_000_000)
        if not self._context._ok:
            raise RCLError(f"failed to create timer: {_CONTEXT_GONE}")
        if period_ns < 0:
            raise RCLError("failed to create timer: timer period must be non-negative, at /project/src/rcl/timer.c:157")
        callback_group = callback_group or self.default_callback_group
        timer = Timer(callback, callback_group, period_ns, clock or self._clock, context=self.context,
                      autostart=autostart)
        timer._node = self
        callback_group.add_entity(timer)
        self._timers.append(timer)
        self._wake_executor()
        return timer

    def create_guard_condition(self, callback: Callable[[], Any],
                               callback_group: CallbackGroup | None = None) -> GuardCondition:
        if not self._context._ok:
            raise RCLError(f"failed to create guard_condition: {_CONTEXT_GONE}")
        callback_group = callback_group or self.default_callback_group
        guard = GuardCondition(callback, callback_group, context=self.context)
        guard._node = self
        callback_group.add_entity(guard)
        self._guards.append(guard)
        self._wake_executor()
        return guard

    def create_rate(self, frequency: float, clock: Clock | None = None) -> Rate:
        if frequency <= 0:
            raise ValueError("frequency must be > 0")
        timer = self.create_timer(1.0 / frequency, None, self._rate_group, clock)
        return Rate(timer, context=self.context)

    def _destroy_entity(self, entity: Any, table: list[Any]) -> bool:
        if entity not in table:
            return False
        table.remove(entity)
        entity._destroy()
        self._wake_executor()
        return True

    def destroy_publisher(self, publisher: Publisher) -> bool:
        if publisher not in self._publishers:
            return False
        for h in publisher.event_handlers:
            self.remove_waitable(h)
        return self._destroy_entity(publisher, self._publishers)

    def destroy_subscription(self, subscription: Subscription) -> bool:
        if subscription not in self._subscriptions:
            return False
        for h in subscription.event_handlers:
            self.remove_waitable(h)
        return self._destroy_entity(subscription, self._subscriptions)

    def destroy_client(self, client: Client) -> bool:
        return self._destroy_entity(client, self._clients)

    def destroy_service(self, service: Service) -> bool:
        return self._destroy_entity(service, self._services)

    def destroy_timer(self, timer: Timer) -> bool:
        return self._destroy_entity(timer, self._timers)

    def destroy_guard_condition(self, guard: GuardCondition) -> bool:
        if guard not in self._guards:
            return False
        self._guards.remove(guard)
        guard._destroyed = True
        return True

    def destroy_rate(self, rate: Rate) -> bool:
        ok = self.destroy_timer(rate._timer)
        rate.destroy()
        return ok

    def destroy_node(self) -> None:
        if self._destroyed:
            return
        for table, fn in ((self._publishers, self.destroy_publisher), (self._subscriptions, self.destroy_subscription),
                          (self._clients, self.destroy_client), (self._services, self.destroy_service),
                          (self._timers, self.destroy_timer), (self._guards, self.destroy_guard_condition)):
            while table:
                fn(table[0])
        self._destroyed = True
        if self._rosout is not None:
            self._rosout.close()
        self._bus.close()
        self._context.untrack_node(self)
        self._wake_executor()

    # ------------------------------------------------------------------ graph
    @property
    def _graph(self) -> Any:
        return self._bus.graph

    def _expand(self, name: str) -> str:
        return expand_topic_name(name, self.get_name(), self.get_namespace())

    def _by_node(self, node_name: str, node_namespace: str, kinds: tuple[str, ...]) -> list[tuple[str, list[str]]]:
        ns = normalize_namespace(node_namespace)
        out: dict[str, set[str]] = {}
        for e in self._graph.entities():
            if e.kind in kinds and e.node == node_name and normalize_namespace(e.namespace) == ns:
                out.setdefault(e.topic, set()).add(e.type)
        return [(k, sorted(v)) for k, v in sorted(out.items())]

    def _check_node_exists(self, node_name: str, node_namespace: str, what: str) -> None:
        self._check_context(f"failed to get {what} names and types")
        ns = node_namespace or "/"
        # rcl checks the namespace, then the name, before asking the graph
        for problem, line in ((namespace_problem(ns), 57), (node_name_problem(node_name), 69)):
            if problem is not None:
                raise RCLError(f"failed to get {what} names and types: {problem[0]}, "
                               f"result: {rmw_result_code(problem[0])}, at /project/src/rcl/graph.c:{line}")
        if (node_name, ns) not in self.get_node_names_and_namespaces():
            raise NodeNameNonExistentError(f"cannot get {what} names and types for nonexistent node: error not set")

    def get_publisher_names_and_types_by_node(self, node_name: str, node_namespace: str,
                                              no_demangle: bool = False) -> list[tuple[str, list[str]]]:
        self._check_node_exists(node_name, node_namespace, "publisher")
        return self._by_node(node_name, node_namespace, (wire.KIND_PUB,))

    def get_subscriber_names_and_types_by_node(self, node_name: str, node_namespace: str,
                                               no_demangle: bool = False) -> list[tuple[str, list[str]]]:
        self._check_node_exists(node_name, node_namespace, "subscriber")
        return self._by_node(node_name, node_namespace, (wire.KIND_SUB,))

    def get_service_names_and_types_by_node(self, node_name: str, node_namespace: str
                                            ) -> list[tuple[str, list[str]]]:
        self._check_node_exists(node_name, node_namespace, "service")
        return self._by_node(node_name, node_namespace, (wire.KIND_SERVICE,))

    def get_client_names_and_types_by_node(self, node_name: str, node_namespace: str
                                           ) -> list[tuple[str, list[str]]]:
        self._check_node_exists(node_name, node_namespace, "client")
        return self._by_node(node_name, node_namespace, (wire.KIND_CLIENT,))

    def get_topic_names_and_types(self, no_demangle: bool = False) -> list[tuple[str, list[str]]]:
        self._check_context("failed to get topic names and types")
        return list(self._graph.topics().items())

    def get_service_names_and_types(self) -> list[tuple[str, list[str]]]:
        self._check_context("failed to get service names and types")
        return list(self._graph.services().items())

    def get_node_names_and_namespaces(self) -> list[tuple[str, str]]:
        self._check_context("Failed to get node names")
        seen: list[tuple[str, str]] = []
        for e in self._graph.entities(wire.KIND_NODE):
            item = (e.node, normalize_namespace(e.namespace))
            if item not in seen:
                seen.append(item)
        return seen

    def get_node_names_and_namespaces_with_enclaves(self) -> list[tuple[str, str, str]]:
        return [(n, ns, "/") for n, ns in self.get_node_names_and_namespaces()]

    def get_node_names(self) -> list[str]:
        return [n for n, _ in self.get_node_names_and_namespaces()]

    def get_fully_qualified_node_names(self) -> list[str]:
        return [f"{ns.rstrip('/')}/{n}" for n, ns in self.get_node_names_and_namespaces()]

    def _graph_name(self, name: str, what: str, *, is_service: bool = False) -> str:
        """A name a graph query asks about: expanded (not remapped) and checked as rclpy's queries do."""
        full = self._expand(name)
        validate_full_topic_name(full, is_service=is_service)
        self._check_context(what)
        return full

    def count_publishers(self, topic_name: str) -> int:
        return len(self._graph.publishers(self._graph_name(topic_name, "Error in rcl_count_publishers")))

    def count_subscribers(self, topic_name: str) -> int:
        return len(self._graph.subscribers(self._graph_name(topic_name, "Error in rcl_count_subscribers")))

    def count_clients(self, service_name: str) -> int:
        name = self._graph_name(service_name, "Error in rcl_count_clients", is_service=True)
        return sum(1 for e in self._graph.entities(wire.KIND_CLIENT) if e.topic == name)

    def count_services(self, service_name: str) -> int:
        return len(self._graph.servers(self._graph_name(service_name, "Error in rcl_count_services",
                                                        is_service=True)))

    def _info_by_topic(self, topic_name: str, no_mangle: bool, kind: str) -> list[TopicEndpointInfo]:
        what = "publishers" if kind == wire.KIND_PUB else "subscriptions"
        if no_mangle:
            name = topic_name
            self._check_context(f"Failed to get information by topic for {what}")
        else:
            name = self._graph_name(topic_name, f"Failed to get information by topic for {what}")
            name = self._remaps.get(name, name)
        ents = self._graph.publishers(name) if kind == wire.KIND_PUB else self._graph.subscribers(name)
        return [TopicEndpointInfo.from_entity(e) for e in ents]

    def get_publishers_info_by_topic(self, topic_name: str, no_mangle: bool = False) -> list[TopicEndpointInfo]:
        return self._info_by_topic(topic_name, no_mangle, wire.KIND_PUB)

    def get_subscriptions_info_by_topic(self, topic_name: str, no_mangle: bool = False) -> list[TopicEndpointInfo]:
        return self._info_by_topic(topic_name, no_mangle, wire.KIND_SUB)

    def wait_for_node(self, fully_qualified_node_name: str, timeout: float) -> bool:
        name = fully_qualified_node_name if fully_qualified_node_name.startswith("/") \
            else "/" + fully_qualified_node_name
        return self._graph.wait_for(lambda: name in self.get_fully_qualified_node_names(), timeout)


# rclpy's node module imports rcl_interfaces' messages when it is imported; so does this one, so that a node's
# start does not generate the classes every node needs (its parameter descriptors and set results).
cls("rcl_interfaces/msg/ParameterDescriptor")
cls("rcl_interfaces/msg/SetParametersResult")
