"""The same small programs under the real rclpy (Jazzy wheels, Fast DDS on loopback) and under diffctl's
client library must agree on everything a user observes: parameter API results and exceptions, executor
and callback-group ordering, coroutine callbacks and futures, timers, services and clients, QoS (the
transient-local late joiner, incompatible QoS reported in rclpy's words)."""

from __future__ import annotations

from tests.client.differential import assert_same, run_both


def test_parameters_agree(router: str) -> None:
    assert_same(*run_both("params_api.py", router))


def test_executors_and_callback_groups_agree(router: str) -> None:
    assert_same(*run_both("executors_order.py", router))


def test_services_and_timers_agree(router: str) -> None:
    assert_same(*run_both("services_timers.py", router))


def test_qos_agrees(router: str) -> None:
    oracle, ours = run_both("qos_events.py", router)
    assert_same(oracle, ours)
    warnings = sorted(set(line for line in oracle.log_lines() if line.startswith("[WARN]")))
    assert warnings, oracle.stderr
    assert sorted(set(line for line in ours.log_lines() if line.startswith("[WARN]"))) == warnings


def test_topics_graph_logging_agree(router: str) -> None:
    assert_same(*run_both("topics_misc.py", router))


def test_sim_time_agrees(router: str) -> None:
    assert_same(*run_both("sim_time.py", router))


def test_ros_args_agree(router: str) -> None:
    assert_same(*run_both("ros_args.py", router))


def test_parameter_events_and_logger_services_agree(router: str) -> None:
    assert_same(*run_both("param_events.py", router))


def test_parameter_services_agree(router: str) -> None:
    """Another node's parameter services through AsyncParameterClient: the same answers as rclpy's."""
    assert_same(*run_both("param_client.py", router))


def test_logging_switches_agree(router: str) -> None:
    oracle, ours = run_both("logging_switches.py", router)
    assert_same(oracle, ours)
    assert ours.log_lines() == oracle.log_lines()


def test_values_agree(router: str) -> None:
    """QoS profiles as printed, the compatibility check's verdict and words for every policy pairing, time and
    parameter values, logging severities."""
    assert_same(*run_both("values.py", router))


def test_node_api_details_agree(router: str) -> None:
    assert_same(*run_both("node_api.py", router))


def test_name_validation_agrees(router: str) -> None:
    assert_same(*run_both("names_graph.py", router))
