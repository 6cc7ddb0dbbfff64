"""tf2_ros over the client library and a real Zenoh router: broadcasters and a listener in separate nodes,
a late listener still gets /tf_static (transient local, all frames in one message), lookups with a timeout,
wait_for_transform_async, and tf2's exceptions through tf2_ros."""

from __future__ import annotations

import threading
import time

import pytest


def transform(parent: str, child: str, stamp, x: float):
    from geometry_msgs.msg import TransformStamped

    t = TransformStamped()
    t.header.stamp = stamp
    t.header.frame_id, t.child_frame_id = parent, child
    t.transform.translation.x = x
    t.transform.rotation.w = 1.0
    return t


@pytest.mark.usefixtures("router")
def test_broadcasters_listener_and_lookups() -> None:
    import rclpy
    from rclpy.duration import Duration
    from rclpy.executors import MultiThreadedExecutor
    from rclpy.time import Time
    from tf2_ros import (
        Buffer,
        ExtrapolationException,
        LookupException,
        StaticTransformBroadcaster,
        TransformBroadcaster,
        TransformException,
        TransformListener,
    )

    rclpy.init()
    try:
        talker = rclpy.create_node("tf_talker")
        static = StaticTransformBroadcaster(talker)
        static.sendTransform(transform("world", "base", talker.get_clock().now().to_msg(), 1.0))
        static.sendTransform([transform("base", "laser", talker.get_clock().now().to_msg(), 0.25)])
        dynamic = TransformBroadcaster(talker)

        listener_node = rclpy.create_node("tf_listener")  # created after the static frames were sent
        buffer = Buffer(node=listener_node)
        TransformListener(buffer, listener_node)
        executor = MultiThreadedExecutor(num_threads=2)
        executor.add_node(talker)
        executor.add_node(listener_node)
        spinner = threading.Thread(target=executor.spin, daemon=True)
        spinner.start()

        future = buffer.wait_for_transform_async("world", "carrot", Time())
        assert not future.done()
        t = buffer.lookup_transform("world", "laser", Time(), timeout=Duration(seconds=5.0))
        assert (t.header.frame_id, t.child_frame_id, t.transform.translation.x) == ("world", "laser", 1.25)

        with pytest.raises(LookupException) as e:
            buffer.lookup_transform("world", "carrot", Time())
        assert str(e.value) == '"carrot" passed to lookupTransform argument source_frame does not exist. '
        started = time.monotonic()
        assert not buffer.can_transform("world", "carrot", Time(), timeout=Duration(seconds=0.3))
        assert time.monotonic() - started >= 0.3

        now = talker.get_clock().now()
        dynamic.sendTransform(transform("laser", "carrot", now.to_msg(), 2.0))
        end = time.monotonic() + 5
        while not future.done() and time.monotonic() < end:
            time.sleep(0.01)
        assert future.done() and future.result().transform.translation.x == 3.25
        later = now + Duration(seconds=1)
        with pytest.raises(ExtrapolationException) as e:
            buffer.lookup_transform("world", "carrot", later)
        assert isinstance(e.value, TransformException)
        assert "Lookup would require extrapolation at time" in str(e.value)
        assert "when looking up transform from frame [carrot] to frame [world]" in str(e.value)
        assert "carrot: \n  parent: 'laser'\n  broadcaster: 'default_authority'" in buffer.all_frames_as_yaml()
        executor.shutdown()
        spinner.join(5)
    finally:
        rclpy.try_shutdown()


@pytest.mark.usefixtures("router")
def test_listener_with_its_own_thread_and_buffer_transform() -> None:
    import rclpy
    import tf2_geometry_msgs  # noqa: F401 (registers the geometry_msgs types with Buffer.transform)
    from geometry_msgs.msg import PointStamped
    from rclpy.duration import Duration
    from rclpy.executors import SingleThreadedExecutor
    from rclpy.time import Time
    from tf2_ros import Buffer, StaticTransformBroadcaster, TransformListener, TypeException

    rclpy.init()
    try:
        talker = rclpy.create_node("tf_static_talker")
        StaticTransformBroadcaster(talker).sendTransform(
            transform("map", "sensor", talker.get_clock().now().to_msg(), -2.0))
        talker_executor = SingleThreadedExecutor()
        talker_executor.add_node(talker)
        talker_spinner = threading.Thread(target=talker_executor.spin, daemon=True)
        talker_spinner.start()

        node = rclpy.create_node("tf_user")
        buffer = Buffer()
        listener = TransformListener(buffer, node, spin_thread=True)  # nobody else spins `node`
        point = PointStamped()
        point.header.frame_id = "sensor"
        point.point.x, point.point.y = 0.5, 1.0
        moved = buffer.transform(point, "map", timeout=Duration(seconds=5.0))
        assert (moved.header.frame_id, moved.point.x, moved.point.y) == ("map", -1.5, 1.0)
        with pytest.raises(TypeException):
            buffer.transform(object(), "map")
        assert buffer.get_latest_common_time("map", "sensor") == Time()  # static frames: time zero
        assert listener.dedicated_listener_thread is not None and listener.dedicated_listener_thread.is_alive()
        listener.executor.shutdown()
        talker_executor.shutdown()
        listener.dedicated_listener_thread.join(5)
        talker_spinner.join(5)
    finally:
        rclpy.try_shutdown()
