"""rclpy.lifecycle's LifecycleNodeMixin and LifecycleNode: the state machine driven by trigger_*() calls and
the ~/change_state service, callbacks run on entering transition states (the previous state as argument),
~/get_state, ~/get_available_states, ~/get_available_transitions, ~/get_transition_graph and
~/transition_event (lifecycle_msgs), as rcl_lifecycle serves and publishes them in Jazzy."""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import Any, NamedTuple

from diffctl.client.exceptions import RCLError
from diffctl.client.lifecycle import state_machine as sm
from diffctl.client.lifecycle.managed_entity import LifecyclePublisher, ManagedEntity, TransitionCallbackReturn
from diffctl.client.node import Node
from diffctl.client.ros_logging import get_logger

# rclpy's RCLError text for an unregistered transition, as the Jazzy wheels print it.
NOT_REGISTERED = (
    "Failed to trigger lifecycle state machine transition: Transition is not registered., "
    "at /project/src/rcl_lifecycle.c:355"
)


class LifecycleState(NamedTuple):
    label: str
    state_id: int


class LifecycleStateMachine:
    """What rclpy holds as `node._state_machine` (rcl_lifecycle's machine, which packages read): the current
    state as (id, label) and the node's lifecycle services, None while the communication interface is off."""

    def __init__(self, node: LifecycleNodeMixin) -> None:
        self._node = node
        self.service_change_state: Any = None
        self.service_get_state: Any = None
        self.service_get_available_states: Any = None
        self.service_get_available_transitions: Any = None
        self.service_get_transition_graph: Any = None

    @property
    def current_state(self) -> tuple[int, str]:
        state = self._node._lifecycle_state
        return state, sm.STATES[state]


class LifecycleNodeMixin(ManagedEntity):
    """Shared by LifecycleNode; expects to be mixed into a Node (it uses the node's entities)."""

    def __init__(self, *, enable_communication_interface: bool = True, callback_group: Any = None) -> None:
        import lifecycle_msgs.msg
        import lifecycle_msgs.srv

        from diffctl.client.qos import qos_profile_services_default

        if not isinstance(enable_communication_interface, bool):  # rclpy's binding takes a bool only
            raise TypeError("enable_communication_interface must be a bool, "
                            f"not {type(enable_communication_interface).__name__}")
        self._lifecycle_lock = threading.RLock()
        self._lifecycle_state = sm.UNCONFIGURED
        self._managed_entities: set[ManagedEntity] = set()
        self._callbacks: dict[int, Callable[[LifecycleState], TransitionCallbackReturn]] = {
            state: getattr(self, name) for state, name in sm.CALLBACK_OF_STATE.items()
        }
        self._transition_event_pub = None
        self._state_machine = LifecycleStateMachine(self)
        if not enable_communication_interface:
            return
        group = callback_group if callback_group is not None else self.default_callback_group
        self._transition_event_pub = self.create_publisher(
            lifecycle_msgs.msg.TransitionEvent, "~/transition_event", 10
        )
        srv = lifecycle_msgs.srv
        for srv_type, name, handler in (
            (srv.ChangeState, "~/change_state", self.__on_change_state),
            (srv.GetState, "~/get_state", self.__on_get_state),
            (srv.GetAvailableStates, "~/get_available_states", self.__on_get_available_states),
            (srv.GetAvailableTransitions, "~/get_available_transitions", self.__on_get_available_transitions),
            (srv.GetAvailableTransitions, "~/get_transition_graph", self.__on_get_transition_graph),
        ):
            service = self.create_service(srv_type, name, handler, qos_profile=qos_profile_services_default,
                                          callback_group=group)
            setattr(self._state_machine, f"service_{name[2:]}", service)

    # --- the user's API -------------------------------------------------------------------------------
    def trigger_configure(self) -> TransitionCallbackReturn:
        return self.__change_state(1)

    def trigger_cleanup(self) -> TransitionCallbackReturn:
        return self.__change_state(2)

    def trigger_activate(self) -> TransitionCallbackReturn:
        return self.__change_state(3)

    def trigger_deactivate(self) -> TransitionCallbackReturn:
        return self.__change_state(4)

    def trigger_shutdown(self) -> TransitionCallbackReturn:
        shutdown = {sm.UNCONFIGURED: 5, sm.INACTIVE: 6, sm.ACTIVE: 7}.get(self._lifecycle_state)
        if shutdown is None:
            raise RCLError("Shutdown transtion not possible")  # sic, rclpy 7.1.6's words
        return self.__change_state(shutdown)

    def add_managed_entity(self, entity: ManagedEntity) -> None:
        self._managed_entities.add(entity)

    def _each_entity(self, method: str, state: Any) -> TransitionCallbackReturn:
        for entity in list(self._managed_entities):
            ret = getattr(entity, method)(state)
            if ret != TransitionCallbackReturn.SUCCESS:
                return ret
        return TransitionCallbackReturn.SUCCESS

    def on_configure(self, state: Any) -> TransitionCallbackReturn:
        return self._each_entity("on_configure", state)

    def on_cleanup(self, state: Any) -> TransitionCallbackReturn:
        return self._each_entity("on_cleanup", state)

    def on_shutdown(self, state: Any) -> TransitionCallbackReturn:
        return self._each_entity("on_shutdown", state)

    def on_activate(self, state: Any) -> TransitionCallbackReturn:
        return self._each_entity("on_activate", state)

    def on_deactivate(self, state: Any) -> TransitionCallbackReturn:
        return self._each_entity("on_deactivate", state)

    def on_error(self, state: Any) -> TransitionCallbackReturn:
        return self._each_entity("on_error", state)

    def create_lifecycle_publisher(self, *args: Any, **kwargs: Any) -> Any:
        if "publisher_class" in kwargs:
            raise TypeError("create_publisher() got an unexpected keyword argument 'publisher_class'")
        pub = self.create_publisher(*args, **kwargs, publisher_class=LifecyclePublisher)
        self._managed_entities.add(pub)
        return pub

    def destroy_lifecycle_publisher(self, publisher: Any) -> bool:
        self._managed_entities.discard(publisher)
        return self.destroy_publisher(publisher)

    # --- the machine ------------------------------------------------------------------------------------
    def _current(self) -> LifecycleState:
        return LifecycleState(label=sm.STATES[self._lifecycle_state], state_id=self._lifecycle_state)

    def _take(self, transition: sm.Transition) -> None:
        self._lifecycle_state = transition.goal
        if self._transition_event_pub is not None:
            import lifecycle_msgs.msg as lm

            # Jazzy's rcl_lifecycle leaves the event's timestamp and transition zero.
            self._transition_event_pub.publish(lm.TransitionEvent(
                start_state=lm.State(id=transition.start, label=sm.STATES[transition.start]),
                goal_state=lm.State(id=transition.goal, label=sm.STATES[transition.goal]),
            ))

    def _trigger(self, find: Callable[[int], sm.Transition]) -> None:
        try:
            transition = find(self._lifecycle_state)
        except sm.TransitionNotRegistered as e:
            _warn_rcl_lifecycle(str(e))
            raise RCLError(NOT_REGISTERED) from None
        self._take(transition)

    def _run_callback(self, previous: LifecycleState) -> TransitionCallbackReturn:
        callback = self._callbacks.get(self._lifecycle_state)
        if callback is None:
            return TransitionCallbackReturn.SUCCESS
        try:
            return callback(previous)
        except Exception:  # rclpy turns any exception into ERROR
            return TransitionCallbackReturn.ERROR

    def __change_state(self, transition_id: int) -> TransitionCallbackReturn:
        with self._lifecycle_lock:
            initial = self._current()
            self._trigger(lambda s: sm.by_id(s, transition_id))
            ret = self._run_callback(initial)
            self._trigger(lambda s: sm.by_label(s, ret.to_label()))
            if ret == TransitionCallbackReturn.ERROR:
                error_ret = self._run_callback(initial)
                self._trigger(lambda s: sm.by_label(s, error_ret.to_label()))
            return ret

    # --- services ----------------------------------------------------------------------------------------
    def __on_change_state(self, req: Any, resp: Any) -> Any:
        transition_id = req.transition.id
        if req.transition.label:
            try:
                transition_id = sm.by_label(self._lifecycle_state, req.transition.label).id
            except sm.TransitionNotRegistered as e:
                _warn_rcl_lifecycle(str(e))
                resp.success = False
                return resp
        resp.success = self.__change_state(transition_id) == TransitionCallbackReturn.SUCCESS
        return resp

    def __on_get_state(self, req: Any, resp: Any) -> Any:
        resp.current_state.id = self._lifecycle_state
        resp.current_state.label = sm.STATES[self._lifecycle_state]
        return resp

    def __on_get_available_states(self, req: Any, resp: Any) -> Any:
        import lifecycle_msgs.msg as lm

        resp.available_states = [lm.State(id=i, label=label) for i, label in sm.STATES.items()]
        return resp

    @staticmethod
    def _descriptions(transitions: list[sm.Transition]) -> list[Any]:
        import lifecycle_msgs.msg as lm

        return [
            lm.TransitionDescription(
                transition=lm.Transition(id=t.id, label=t.label),
                start_state=lm.State(id=t.start, label=sm.STATES[t.start]),
                goal_state=lm.State(id=t.goal, label=sm.STATES[t.goal]),
            )
            for t in transitions
        ]

    def __on_get_available_transitions(self, req: Any, resp: Any) -> Any:
        resp.available_transitions = self._descriptions(sm.valid_transitions(self._lifecycle_state))
        return resp

    def __on_get_transition_graph(self, req: Any, resp: Any) -> Any:
        resp.available_transitions = self._descriptions(list(sm.TRANSITIONS))
        return resp


def _warn_rcl_lifecycle(text: str) -> None:
    # rcl_lifecycle's own RCUTILS_LOG_WARN_NAMED line (logger "rcl_lifecycle"), before rclpy raises.
    get_logger("rcl_lifecycle").warning(text)


class LifecycleNode(LifecycleNodeMixin, Node):
    """A ROS 2 managed node: Node with LifecycleNodeMixin's methods."""

    def __init__(self, node_name: str, *, enable_communication_interface: bool = True, **kwargs: Any) -> None:
        Node.__init__(self, node_name, **kwargs)
        LifecycleNodeMixin.__init__(self, enable_communication_interface=enable_communication_interface)
