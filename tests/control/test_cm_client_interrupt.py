"""An interrupt (the spawner's Ctrl-C/SIGTERM handler) while a controller-manager call waits for its reply ends the
call between two slices of its wait, never inside the executor, and the client's later calls still work (the
spawner -u unloads with them): a KeyboardInterrupt raised inside the executor as a reply was handled lost that
reply and left the spawner waiting out its call timeout, three attempts of 10 s."""

from __future__ import annotations

import threading

import pytest

from diffctl.client.context import Context
from diffctl.client.interfaces import cls
from diffctl.client.node import Node
from diffctl.control.cm_client import ManagerClient
from tests.probe import spinning

LIST = "controller_manager_msgs/srv/ListControllers"


def test_an_interrupt_mid_call_ends_the_call_and_later_calls_are_answered(router: str) -> None:
    held = threading.Event()
    release = threading.Event()
    calls: list[int] = []
    context = Context()
    context.init(args=[])
    node = Node("spawner_probe", context=context)
    cm = ManagerClient(node, call_timeout_s=30.0)

    def handler(request, response):
        calls.append(1)
        if len(calls) == 1:
            cm.interrupt()  # what the spawner's signal handler does, while the first call waits for this reply
            held.set()
            release.wait(30.0)
        return response

    try:
        with spinning("controller_manager") as server:
            server.create_service(cls(LIST), "/controller_manager/list_controllers", handler)
            cm.wait("list_controllers", 30.0)
            with pytest.raises(KeyboardInterrupt):
                cm.list_controllers()
            assert held.is_set() and not release.is_set()  # ended while the manager still held its reply
            release.set()
            cm.interrupt_handled()
            assert cm.list_controllers() == [] and len(calls) == 2
            with pytest.raises(KeyboardInterrupt):  # outside a call (or a second time): at once
                cm.interrupt()
    finally:
        release.set()
        cm.close()
        node.destroy_node()
        context.try_shutdown()
