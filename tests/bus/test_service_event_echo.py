"""`diffctl topic echo /<srv>/_service_event` of a node using rclpy's configure_introspection, and the .msg
text a service-typed description turns into (no trailing slash after `pkg/srv/X_Request`)."""

from __future__ import annotations

import sys
import textwrap

from rosbags.typesys import get_types_from_msg

from diffctl.interfaces import types
from diffctl.interfaces.type_description import describe, ros2msg_text

SERVER = textwrap.dedent("""
    import rclpy
    from rclpy.node import Node
    from rclpy.qos import qos_profile_system_default
    from rclpy.service_introspection import ServiceIntrospectionState
    from example_interfaces.srv import AddTwoInts

    def add(req, resp):
        resp.sum = req.a + req.b
        return resp

    rclpy.init()
    n = Node('adder')
    srv = n.create_service(AddTwoInts, 'add_two_ints', add)
    srv.configure_introspection(n.get_clock(), qos_profile_system_default, ServiceIntrospectionState.CONTENTS)
    cli = n.create_client(AddTwoInts, 'add_two_ints')
    n.create_timer(0.2, lambda: cli.call_async(AddTwoInts.Request(a=2, b=3)))
    try:
        rclpy.spin(n)
    except KeyboardInterrupt:
        pass
""")


def test_service_typed_description_is_parseable_msg_text() -> None:
    event = types.check("example_interfaces/srv/AddTwoInts_Event")
    text = ros2msg_text(describe(event))
    assert "AddTwoInts_Request/" not in text and "AddTwoInts_Response/" not in text
    assert "example_interfaces/srv/AddTwoInts_Request[<=1] request" in text
    found = get_types_from_msg(text, "example_interfaces/srv/AddTwoInts_Event")
    assert any(k.endswith("AddTwoInts_Request") for k in found)


def test_service_event_types_are_known_to_the_bus() -> None:
    assert types.exists("example_interfaces/srv/AddTwoInts_Event")
    assert types.check("example_interfaces/srv/AddTwoInts_Event") == "example_interfaces/srv/AddTwoInts_Event"


def test_topic_echo_shows_service_events(router: str, procs) -> None:
    procs.start([sys.executable, "-c", SERVER])
    echo = procs.diffctl("topic", "echo", "/add_two_ints/_service_event", "--once")
    out, _ = echo.communicate(timeout=30)
    assert echo.returncode == 0, out
    assert "event_type:" in out and "sequence_number:" in out
    assert ("a: 2" in out and "b: 3" in out) or "sum: 5" in out


def test_service_event_learnt_from_a_description_keeps_service_names() -> None:
    """A `<srv>_Event` of a package this process has no definition of is learnt from the description's text,
    under the bus's names (`pkg/srv/X_Request`, not rosbags' `pkg/srv/msg/X_Request`), and decodes."""
    from diffctl.bag.msgdefs import register_schema

    text = ros2msg_text(describe(types.check("example_interfaces/srv/AddTwoInts_Event")))
    text = text.replace("example_interfaces/", "exit_clean_unknown_pkg/")
    event = "exit_clean_unknown_pkg/srv/AddTwoInts_Event"
    assert not types.exists(event)
    register_schema(event, "ros2msg", text, "test")
    assert types.exists(event) and types.exists("exit_clean_unknown_pkg/srv/AddTwoInts_Request")
    known = types.new("example_interfaces/srv/AddTwoInts_Event",
                      {"request": [{"a": 2, "b": 3}], "info": {"sequence_number": 7}})
    learnt = types.deserialize(types.serialize(known, "example_interfaces/srv/AddTwoInts_Event"), event)
    assert learnt.info.sequence_number == 7 and learnt.request[0].a == 2 and learnt.request[0].b == 3
