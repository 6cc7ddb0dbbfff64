"""tf2_ros.buffer_client.BufferClient against a LookupTransform action server (tf2's BufferServer is C++;
the server here answers from a tf2_ros Buffer as it does, with TF2Error codes), over a real Zenoh router."""

from __future__ import annotations

import threading

import pytest


@pytest.mark.usefixtures("router")
def test_buffer_client_lookups_and_errors() -> None:
    import rclpy
    from geometry_msgs.msg import TransformStamped
    from rclpy.action import ActionServer
    from rclpy.duration import Duration
    from rclpy.executors import MultiThreadedExecutor
    from rclpy.time import Time
    from tf2_msgs.action import LookupTransform
    from tf2_msgs.msg import TF2Error
    from tf2_ros import Buffer, LookupException, TimeoutException
    from tf2_ros.buffer_client import BufferClient

    rclpy.init()
    try:
        server_node = rclpy.create_node("tf2_buffer_server")
        buffer = Buffer()
        t = TransformStamped()
        t.header.frame_id, t.child_frame_id = "map", "odom"
        t.transform.translation.x = 1.5
        t.transform.rotation.w = 1.0
        buffer.set_transform_static(t, "test")

        def execute(goal_handle):
            g, result = goal_handle.request, LookupTransform.Result()
            try:
                result.transform = buffer.lookup_transform(g.target_frame, g.source_frame, Time.from_msg(g.source_time))
            except LookupException as e:
                result.error = TF2Error(error=TF2Error.LOOKUP_ERROR, error_string=str(e))
            goal_handle.succeed()
            return result

        ActionServer(server_node, LookupTransform, "tf2_buffer_server", execute)
        client_node = rclpy.create_node("buffer_client_user")
        missing = BufferClient(client_node, "no_such_server")
        client = BufferClient(client_node, "tf2_buffer_server", timeout_padding=Duration(seconds=5.0))
        executor = MultiThreadedExecutor()
        executor.add_node(server_node)
        executor.add_node(client_node)
        spinner = threading.Thread(target=executor.spin, daemon=True)
        spinner.start()
        assert client.action_client.wait_for_server(timeout_sec=10.0)

        found = client.lookup_transform("map", "odom", Time())
        assert (found.header.frame_id, found.child_frame_id, found.transform.translation.x) == ("map", "odom", 1.5)
        assert client.can_transform("map", "odom", Time())
        with pytest.raises(LookupException, match="nowhere"):
            client.lookup_transform("map", "nowhere", Time())
        assert not client.can_transform("map", "nowhere", Time())
        with pytest.raises(TimeoutException, match="BufferServer is not ready"):
            missing.lookup_transform("map", "odom", Time())
        with pytest.raises(TypeError, match=r"rclpy\.time\.Time"):
            client.lookup_transform("map", "odom", 0)
        executor.shutdown()
        spinner.join(5)
    finally:
        rclpy.try_shutdown()
