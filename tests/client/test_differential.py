"""The same small programs under the real rclpy (Jazzy wheels, Fast DDS on loopback) and under diffctl's
client library must agree on everything a user observes: parameter API results and exceptions, executor
and callback-group ordering, coroutine callbacks and futures, timers, services and clients, QoS (the
transient-local late joiner, incompatible QoS reported in rclpy's words)."""

from __future__ import annotations

from tests.client.differential import assert_same, run_oracle, run_ours


def test_parameters_agree(router: str) -> None:
    assert_same(run_oracle("params_api.py"), run_ours("params_api.py", router))


def test_executors_and_callback_groups_agree(router: str) -> None:
    assert_same(run_oracle("executors_order.py"), run_ours("executors_order.py", router))


def test_services_and_timers_agree(router: str) -> None:
    assert_same(run_oracle("services_timers.py"), run_ours("services_timers.py", router))


def test_qos_agrees(router: str) -> None:
    oracle, ours = run_oracle("qos_events.py"), run_ours("qos_events.py", router)
    assert_same(oracle, ours)
    warnings = sorted(set(line for line in oracle.log_lines() if line.startswith("[WARN]")))
    assert warnings, oracle.stderr
    assert sorted(set(line for line in ours.log_lines() if line.startswith("[WARN]"))) == warnings


def test_topics_graph_logging_agree(router: str) -> None:
    assert_same(run_oracle("topics_misc.py"), run_ours("topics_misc.py", router))


def test_sim_time_agrees(router: str) -> None:
    assert_same(run_oracle("sim_time.py"), run_ours("sim_time.py", router))


def test_ros_args_agree(router: str) -> None:
    assert_same(run_oracle("ros_args.py"), run_ours("ros_args.py", router))


def test_parameter_events_and_logger_services_agree(router: str) -> None:
    assert_same(run_oracle("param_events.py"), run_ours("param_events.py", router))
