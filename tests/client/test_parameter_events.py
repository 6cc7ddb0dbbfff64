"""A node's /parameter_events leave before the declare or set that caused them returns, as rcl publishes them:
a subscription made afterwards never hears them (published by the declaring thread, not handed to another that
a loaded machine may run late)."""

from __future__ import annotations

import time
from typing import Any

import pytest


@pytest.mark.usefixtures("router")
def test_events_of_a_nodes_start_are_not_heard_by_a_later_subscription() -> None:
    from diffctl.client import runtime
    from diffctl.client.executors import SingleThreadedExecutor
    from diffctl.client.interfaces import cls
    from diffctl.client.node import Node
    from diffctl.client.parameter import Parameter
    from diffctl.client.qos import qos_profile_parameter_events
    from diffctl.client.signals import SignalHandlerOptions

    runtime.init(args=["test_parameter_events"], signal_handler_options=SignalHandlerOptions.NO)

    watched = Node("watched_start")  # declares use_sim_time and start_type_description_service
    watcher = Node("watcher_after")
    heard: list[Any] = []
    watcher.create_subscription(cls("rcl_interfaces/msg/ParameterEvent"), "/parameter_events",
                                lambda e: heard.append((e.node, [p.name for p in e.new_parameters],
                                                        [p.name for p in e.changed_parameters])),
                                qos_profile_parameter_events)
    ex = SingleThreadedExecutor()
    ex.add_node(watcher)
    try:
        deadline = time.monotonic() + 30.0
        while watcher.count_publishers("/parameter_events") < 2:
            assert time.monotonic() < deadline, "the nodes' /parameter_events publishers never matched"
            ex.spin_once(timeout_sec=0.05)
        watched.set_parameters([Parameter("use_sim_time", value=True)])  # heard: made after the subscription
        while not heard:
            assert time.monotonic() < deadline, "the set's event never arrived"
            ex.spin_once(timeout_sec=0.05)
        end = time.monotonic() + 0.5
        while time.monotonic() < end:
            ex.spin_once(timeout_sec=0.05)
        assert heard == [("/watched_start", [], ["use_sim_time"])]
    finally:
        ex.shutdown()
        watched.destroy_node()
        watcher.destroy_node()
        runtime.try_shutdown()
