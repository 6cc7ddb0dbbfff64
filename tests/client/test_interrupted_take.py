"""A Ctrl-C (KeyboardInterrupt) that lands while an executor takes a reply or a sample leaves that entity served
afterwards: rclpy's takes are C, so an interrupt cannot land inside them; here they are Python, and an entity
left marked as taken (with its callback group held) never had a reply or sample handled again."""

from __future__ import annotations

import pytest

from diffctl.client.context import Context
from diffctl.client.executors import SingleThreadedExecutor
from diffctl.client.interfaces import cls
from diffctl.client.node import Node
from tests.probe import spinning

TRIGGER = "std_srvs/srv/Trigger"


def test_a_client_whose_take_was_interrupted_gets_its_next_reply(router: str) -> None:
    context = Context()
    context.init(args=[])
    node = Node("interrupted_client", context=context)
    executor = SingleThreadedExecutor(context=context)
    executor.add_node(node)
    try:
        with spinning("trigger_server") as server:
            server.create_service(cls(TRIGGER), "/trigger", lambda req, resp: setattr(resp, "success", True) or resp)
            cli = node.create_client(cls(TRIGGER), "/trigger")
            assert cli.wait_for_service(timeout_sec=30.0)
            take = cli._take
            interrupts = [KeyboardInterrupt()]

            def interrupted_take(*args):
                if interrupts:
                    raise interrupts.pop()  # as a SIGINT arriving inside the take would
                return take(*args)

            cli._take = interrupted_take
            first = cli.call_async(cls(TRIGGER).Request())
            with pytest.raises(KeyboardInterrupt):
                executor.spin_until_future_complete(first, timeout_sec=30.0)
            assert not interrupts and not first.done()  # that reply is lost, as one taken in rclpy would be
            second = cli.call_async(cls(TRIGGER).Request())
            executor.spin_until_future_complete(second, timeout_sec=30.0)
            assert second.done() and second.result().success
    finally:
        executor.shutdown()
        node.destroy_node()
        context.try_shutdown()
