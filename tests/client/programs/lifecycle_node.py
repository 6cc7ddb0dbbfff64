"""A managed node driven through its whole state machine, by its own trigger_* calls and by the lifecycle
services (as `ros2 lifecycle set` does), with a LifecyclePublisher that only publishes while active.
Prints what a user observes; the differential test runs it on the real rclpy and on diffctl."""

import threading
import time

import rclpy
from lifecycle_msgs.msg import State, Transition, TransitionEvent
from lifecycle_msgs.srv import ChangeState, GetAvailableStates, GetAvailableTransitions, GetState
from rclpy.executors import MultiThreadedExecutor
from rclpy.lifecycle import LifecycleNode, LifecycleState, TransitionCallbackReturn
from rclpy.node import Node
from std_msgs.msg import String


class Talker(LifecycleNode):
    def __init__(self):
        super().__init__("lc_talker")
        self.fail_next_activate = False
        self.raise_next_configure = False
        self.pub = None

    def on_configure(self, state):
        print("on_configure", state)
        if self.raise_next_configure:
            raise RuntimeError("cannot configure")
        self.pub = self.create_lifecycle_publisher(String, "lifecycle_chatter", 10)
        return TransitionCallbackReturn.SUCCESS

    def on_activate(self, state):
        print("on_activate", state)
        if self.fail_next_activate:
            self.fail_next_activate = False
            return TransitionCallbackReturn.FAILURE
        return super().on_activate(state)

    def on_deactivate(self, state):
        print("on_deactivate", state)
        return super().on_deactivate(state)

    def on_cleanup(self, state):
        print("on_cleanup", state)
        self.destroy_lifecycle_publisher(self.pub)
        self.pub = None
        return TransitionCallbackReturn.SUCCESS

    def on_shutdown(self, state):
        print("on_shutdown", state)
        return TransitionCallbackReturn.SUCCESS

    def on_error(self, state):
        print("on_error", state)
        return TransitionCallbackReturn.FAILURE


def wait(fut, timeout=10.0):
    end = time.time() + timeout
    while not fut.done() and time.time() < end:
        time.sleep(0.01)
    assert fut.done(), "timed out"
    return fut.result()


def settle(seconds=0.3):
    time.sleep(seconds)


def until(condition, timeout=10.0):
    end = time.time() + timeout
    while not condition() and time.time() < end:
        time.sleep(0.01)


def main():
    rclpy.init()
    talker, manager = Talker(), Node("lc_manager")
    events, heard = [], []
    manager.create_subscription(TransitionEvent, "/lc_talker/transition_event", events.append, 10)
    manager.create_subscription(String, "/lifecycle_chatter", lambda m: heard.append(m.data), 10)
    clients = {name: manager.create_client(t, f"/lc_talker/{name}") for name, t in (
        ("change_state", ChangeState), ("get_state", GetState), ("get_available_states", GetAvailableStates),
        ("get_available_transitions", GetAvailableTransitions),
        ("get_transition_graph", GetAvailableTransitions))}
    executor = MultiThreadedExecutor(num_threads=4)
    executor.add_node(talker)
    executor.add_node(manager)
    spinner = threading.Thread(target=executor.spin, daemon=True)
    spinner.start()
    for c in clients.values():
        assert c.wait_for_service(timeout_sec=10.0)

    def state():
        s = wait(clients["get_state"].call_async(GetState.Request())).current_state
        return (s.id, s.label)

    def change(transition_id=0, label=""):
        req = ChangeState.Request(transition=Transition(id=transition_id, label=label))
        return wait(clients["change_state"].call_async(req)).success

    def say(text):
        if talker.pub is not None:
            talker.pub.publish(String(data=text))

    print("initial", state(), LifecycleState(label="x", state_id=9))
    print("states", [(s.id, s.label) for s in wait(
        clients["get_available_states"].call_async(GetAvailableStates.Request())).available_states])
    graph = wait(clients["get_transition_graph"].call_async(GetAvailableTransitions.Request()))
    print("graph", [(t.transition.id, t.transition.label, t.start_state.id, t.goal_state.label)
                    for t in graph.available_transitions])

    print("configure", talker.trigger_configure(), state())
    say("inactive")
    settle()
    print("available", [(t.transition.id, t.transition.label) for t in wait(
        clients["get_available_transitions"].call_async(GetAvailableTransitions.Request())).available_transitions])
    talker.fail_next_activate = True
    print("activate failing", change(Transition.TRANSITION_ACTIVATE), state())
    print("activate by label", change(label="activate"), state())
    say("active 1")
    say("active 2")
    until(lambda: len(heard) >= 2)
    print("deactivate", talker.trigger_deactivate(), state())
    say("inactive again")
    settle()
    print("heard", heard, talker.pub.is_activated)
    try:
        talker.trigger_deactivate()
    except Exception as e:  # what the user sees is the point
        print("invalid", type(e).__name__, isinstance(e, RuntimeError), str(e).split(",")[0])
    print("bad label", change(label="fly"), state())
    print("cleanup", change(Transition.TRANSITION_CLEANUP), state())
    talker.raise_next_configure = True  # an exception is ERROR: on_error runs, and its FAILURE finalizes
    print("configure raising", talker.trigger_configure(), state())
    try:
        talker.trigger_shutdown()
    except Exception as e:  # what the user sees is the point
        print("shutdown when finalized", type(e).__name__, str(e), state())
    until(lambda: len(events) >= 13)
    print("events", [(e.timestamp, e.transition.id, e.start_state.label, e.goal_state.label) for e in events])
    print("state consts", State.PRIMARY_STATE_ACTIVE, Transition.TRANSITION_ON_ERROR_FAILURE,
          int(TransitionCallbackReturn.ERROR))
    # node._state_machine, rcl_lifecycle's machine as packages read it: (id, label), no services when off
    quiet = LifecycleNode("quiet_lifecycle", enable_communication_interface=False)
    quiet.trigger_configure()
    machine = quiet._state_machine
    print("state machine", talker._state_machine.current_state, machine.current_state,
          bool(talker._state_machine.service_get_state), bool(machine.service_change_state),
          bool(machine.service_get_transition_graph))
    quiet.destroy_node()
    try:
        LifecycleNode("typed_lifecycle", enable_communication_interface="yes")
    except TypeError:
        print("non-bool communication interface", "TypeError")
    executor.shutdown()  # the orderly teardown, as in action_fibonacci.py
    spinner.join(timeout=10.0)
    talker.destroy_node()
    manager.destroy_node()
    rclpy.shutdown()


if __name__ == "__main__":
    main()
