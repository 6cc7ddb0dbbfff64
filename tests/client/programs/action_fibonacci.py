"""Fibonacci action server and client in one process (as ros2/examples' minimal_action_server and
minimal_action_client): goal, feedback, result, rejection, cancel, a cancel of a finished goal, an unknown
goal's result. Prints what a user observes; the differential test runs it on the real rclpy and on diffctl."""

import threading
import time
import uuid

import rclpy
from action_msgs.msg import GoalStatus, GoalStatusArray
from action_msgs.srv import CancelGoal
from rclpy.action import ActionClient, ActionServer, CancelResponse, GoalResponse
from rclpy.callback_groups import ReentrantCallbackGroup
from rclpy.executors import MultiThreadedExecutor
from rclpy.node import Node
from rclpy.qos import qos_profile_action_status_default
from unique_identifier_msgs.msg import UUID

try:
    from example_interfaces.action import Fibonacci
except ImportError:  # the real ROS wheels ship the same action in test_msgs
    from test_msgs.action import Fibonacci


class Server(Node):
    def __init__(self):
        super().__init__("fibonacci_server")
        self.server = ActionServer(
            self, Fibonacci, "fibonacci", self.execute,
            goal_callback=self.on_goal, cancel_callback=self.on_cancel,
            callback_group=ReentrantCallbackGroup())

    def on_goal(self, goal):
        return GoalResponse.REJECT if goal.order > 40 else GoalResponse.ACCEPT

    def on_cancel(self, goal_handle):
        return CancelResponse.ACCEPT

    def execute(self, goal_handle):
        feedback = Fibonacci.Feedback()
        feedback.sequence = [0, 1]
        for i in range(1, goal_handle.request.order):
            if goal_handle.is_cancel_requested:
                goal_handle.canceled()
                result = Fibonacci.Result()
                result.sequence = feedback.sequence
                return result
            feedback.sequence.append(feedback.sequence[i] + feedback.sequence[i - 1])
            goal_handle.publish_feedback(feedback)
            time.sleep(0.05 if goal_handle.request.order < 10 else 0.2)
        goal_handle.succeed()
        result = Fibonacci.Result()
        result.sequence = feedback.sequence
        return result


def wait(fut, timeout=10.0):
    end = time.time() + timeout
    while not fut.done() and time.time() < end:
        time.sleep(0.01)
    assert fut.done(), "timed out"
    return fut.result()


def main():
    rclpy.init()
    server, client_node = Server(), Node("fibonacci_client")
    statuses = {}
    client_node.create_subscription(
        GoalStatusArray, "/fibonacci/_action/status",
        lambda m: statuses.update({bytes(s.goal_info.goal_id.uuid): s.status for s in m.status_list}),
        qos_profile_action_status_default)
    client = ActionClient(client_node, Fibonacci, "fibonacci")
    executor = MultiThreadedExecutor(num_threads=4)
    executor.add_node(server)
    executor.add_node(client_node)
    spinner = threading.Thread(target=executor.spin, daemon=True)
    spinner.start()

    print("server ready", client.wait_for_server(timeout_sec=10.0), client.server_is_ready())
    for name, entities in (("client", client.get_num_entities()), ("server", server.server.get_num_entities())):
        print(name, "entities", entities.num_subscriptions, entities.num_guard_conditions, entities.num_timers,
              entities.num_clients, entities.num_services, entities.num_events)
    for wrong in ("a string", Fibonacci.Result()):  # a goal must be the action's Goal, not any message
        for send in (client.send_goal_async, client.send_goal):
            try:
                send(wrong)
                print(send.__name__, "took", type(wrong).__name__)
            except TypeError as e:
                print(send.__name__, "refused", type(wrong).__name__, repr(e))
    feedback = []
    handle = wait(client.send_goal_async(Fibonacci.Goal(order=5), feedback_callback=lambda m: feedback.append(
        (type(m).__name__.endswith("FeedbackMessage"), list(m.feedback.sequence)))))
    print("accepted", handle.accepted, type(handle).__name__)
    result = wait(handle.get_result_async())
    print("result", result.status, list(result.result.sequence), type(result).__name__)
    end = time.time() + 5  # feedback and result travel separately: the last feedback may trail the result
    while len(feedback) < 4 and time.time() < end:
        time.sleep(0.01)
    print("feedback", feedback)
    print("status after result", handle.status)

    rejected = wait(client.send_goal_async(Fibonacci.Goal(order=50)))
    print("rejected", rejected.accepted, rejected.status)

    slow_feedback = []
    slow = wait(client.send_goal_async(Fibonacci.Goal(order=20), feedback_callback=slow_feedback.append))
    end = time.time() + 10
    while not slow_feedback and time.time() < end:
        time.sleep(0.01)
    cancel = wait(slow.cancel_goal_async())
    print("cancel", cancel.return_code, len(cancel.goals_canceling),
          bytes(cancel.goals_canceling[0].goal_id.uuid) == bytes(slow.goal_id.uuid), type(cancel).__name__)
    slow_result = wait(slow.get_result_async())
    print("canceled result", slow_result.status, len(slow_result.result.sequence) < 20)

    again = wait(handle.cancel_goal_async())
    print("cancel finished goal", again.return_code, len(again.goals_canceling))

    raw_cancel = client_node.create_client(CancelGoal, "/fibonacci/_action/cancel_goal")
    everything = CancelGoal.Request()
    print("cancel all idle", wait(raw_cancel.call_async(everything)).return_code)
    unknown = CancelGoal.Request()
    unknown.goal_info.goal_id = UUID(uuid=list(uuid.uuid4().bytes))
    print("cancel unknown", wait(raw_cancel.call_async(unknown)).return_code)
    raw_result = client_node.create_client(Fibonacci.Impl.GetResultService, "/fibonacci/_action/get_result")
    request = Fibonacci.Impl.GetResultService.Request()
    request.goal_id = UUID(uuid=list(uuid.uuid4().bytes))
    print("unknown result", wait(raw_result.call_async(request)).status)

    # Results are kept result_timeout seconds after the goal ends, then the goal is forgotten.
    short_statuses = []
    ActionServer(server, Fibonacci, "fibonacci_short", lambda gh: (gh.succeed(), Fibonacci.Result())[1],
                 result_timeout=1)
    client_node.create_subscription(GoalStatusArray, "/fibonacci_short/_action/status",
                                    lambda m: short_statuses.append([s.status for s in m.status_list]),
                                    qos_profile_action_status_default)
    short = ActionClient(client_node, Fibonacci, "fibonacci_short")
    short.wait_for_server(timeout_sec=10.0)
    short_handle = wait(short.send_goal_async(Fibonacci.Goal(order=2)))
    print("short result", wait(short_handle.get_result_async()).status)
    time.sleep(2.5)
    short_raw = client_node.create_client(Fibonacci.Impl.GetResultService, "/fibonacci_short/_action/get_result")
    request = Fibonacci.Impl.GetResultService.Request()
    request.goal_id = short_handle.goal_id
    print("expired result", wait(short_raw.call_async(request)).status, short_statuses[-1])

    end = time.time() + 5
    while time.time() < end and (statuses.get(bytes(handle.goal_id.uuid)) != GoalStatus.STATUS_SUCCEEDED
                                 or statuses.get(bytes(slow.goal_id.uuid)) != GoalStatus.STATUS_CANCELED):
        time.sleep(0.02)
    print("status topic", statuses.get(bytes(handle.goal_id.uuid)), statuses.get(bytes(slow.goal_id.uuid)),
          bytes(rejected.goal_id.uuid) in statuses)
    # rclpy's orderly teardown: stop and join the spinning thread, destroy the nodes, then shut down (the real
    # rclpy aborts at exit, "terminate called without an active exception", when its threads outlive this).
    executor.shutdown()
    spinner.join(timeout=10.0)
    server.destroy_node()
    client_node.destroy_node()
    rclpy.shutdown()
    feedback_after_shutdown()


def feedback_after_shutdown():
    """An execute callback still running when the context goes (Ctrl-C mid-goal): its feedback is refused
    with rcl_action's error, and the server's own lines come from its `action_server` child logger."""
    rclpy.init()
    node = Node("late_server")
    started, go = threading.Event(), threading.Event()

    def execute(goal_handle):
        started.set()
        go.wait(10.0)
        try:
            goal_handle.publish_feedback(Fibonacci.Feedback())
        except Exception as e:  # the error is the observation
            print("feedback after shutdown", type(e).__module__, type(e).__name__, e)
        raise ValueError("gave up")

    ActionServer(node, Fibonacci, "late", execute, callback_group=ReentrantCallbackGroup())
    client = ActionClient(node, Fibonacci, "late")
    executor = MultiThreadedExecutor(num_threads=2)
    executor.add_node(node)
    spinner = threading.Thread(target=executor.spin, daemon=True)
    spinner.start()
    client.wait_for_server(timeout_sec=10.0)
    client.send_goal_async(Fibonacci.Goal(order=3))
    print("late goal started", started.wait(10.0))
    rclpy.shutdown()
    spinner.join(timeout=10.0)
    try:
        client.wait_for_server(timeout_sec=0.1)
    except Exception as e:  # the error is the observation
        print("wait_for_server after shutdown", type(e).__name__, e)
    go.set()
    executor.shutdown()
    node.destroy_node()


if __name__ == "__main__":
    main()
