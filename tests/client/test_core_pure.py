"""The client library's pure pieces, on rclpy's documented behaviour: futures and tasks, QoS profiles, time,
parameter types, logging filters, name validation. (Everything touching the wire is in the differential tests.)"""

from __future__ import annotations

import pytest

from diffctl.client import ros_logging
from diffctl.client.callback_groups import MutuallyExclusiveCallbackGroup, ReentrantCallbackGroup
from diffctl.client.clock import Clock, ClockType, ROSClock
from diffctl.client.duration import Duration
from diffctl.client.exceptions import InvalidNodeNameException, InvalidQoSProfileException
from diffctl.client.names import expand_topic_name, validate_namespace, validate_node_name
from diffctl.client.parameter import Parameter
from diffctl.client.qos import (
    DurabilityPolicy,
    QoSCompatibility,
    QoSProfile,
    ReliabilityPolicy,
    as_profile,
    qos_check_compatible,
    qos_profile_sensor_data,
)
from diffctl.client.ros_time import Time
from diffctl.client.task import Future, Task


def test_future_result_none_while_pending_and_exception_raised() -> None:
    f = Future()
    assert f.result() is None and not f.done()
    seen = []
    f.add_done_callback(lambda fut: seen.append(fut.result()))
    f.set_result(3)
    assert f.done() and seen == [3]
    g = Future()
    g.set_exception(ValueError("x"))
    with pytest.raises(ValueError):
        g.result()


def test_task_steps_a_coroutine_awaiting_a_future() -> None:
    inner = Future()

    async def co() -> int:
        value = await inner
        return value + 1

    t = Task(co)
    t()
    assert not t.done()
    inner.set_result(41)
    t()
    assert t.done() and t.result() == 42


def test_callback_groups() -> None:
    me, re_ = MutuallyExclusiveCallbackGroup(), ReentrantCallbackGroup()
    a, b = Future(), Future()
    assert me.beginning_execution(a) and not me.can_execute(b) and not me.beginning_execution(b)
    me.ending_execution(a)
    assert me.can_execute(b)
    assert re_.beginning_execution(a) and re_.beginning_execution(b)


def test_qos_profiles() -> None:
    with pytest.raises(InvalidQoSProfileException, match="History and/or depth settings are required"):
        QoSProfile()
    with pytest.raises(AssertionError, match="Invalid arguments passed to constructor"):
        QoSProfile(depth=1, foo=2)
    p = as_profile(7)
    assert (p.depth, p.reliability, p.durability) == (7, ReliabilityPolicy.RELIABLE, DurabilityPolicy.VOLATILE)
    with pytest.raises(ValueError, match="history depth must be greater than or equal to zero"):
        as_profile(-1)
    with pytest.raises(TypeError, match="Expected QoSProfile or int"):
        as_profile("10")
    assert qos_profile_sensor_data.reliability == ReliabilityPolicy.BEST_EFFORT
    sub = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL)
    comp, reason = qos_check_compatible(qos_profile_sensor_data, sub)
    assert comp == QoSCompatibility.ERROR
    assert "Best effort publisher and reliable subscription" in reason
    assert "Volatile publisher and transient local subscription" in reason


def test_time_and_duration() -> None:
    t = Time(seconds=1.5)
    assert repr(t) == "Time(nanoseconds=1500000000, clock_type=SYSTEM_TIME)"
    assert repr(Duration(seconds=2)) == "Duration(nanoseconds=2000000000)"
    with pytest.raises(TypeError):
        Duration(seconds=1) + Duration(seconds=1)
    with pytest.raises(TypeError, match="Can't compare times with different clock types"):
        t < Time(clock_type=ClockType.ROS_TIME)  # noqa: B015
    assert (t + Duration(seconds=1)).nanoseconds == 2_500_000_000
    assert (Time(seconds=3) - t) == Duration(seconds=1.5)
    assert isinstance(Clock(clock_type=ClockType.ROS_TIME), ROSClock)
    # the fast paths (diffctl's, rclcpp's Duration::from_nanoseconds) make what the constructors make
    for ns in (0, 1, 1_500_000_000, 2**63 - 1):
        fast = Time.from_nanoseconds(ns, ClockType.ROS_TIME)
        assert (repr(fast), type(fast)) == (repr(Time(nanoseconds=ns, clock_type=ClockType.ROS_TIME)), Time)
        assert fast == Time(nanoseconds=ns, clock_type=ClockType.ROS_TIME)
        assert Duration.from_nanoseconds(-ns) == Duration(nanoseconds=-ns)
    assert Time.from_nanoseconds(3).clock_type == ClockType.SYSTEM_TIME
    with pytest.raises(ValueError, match="must not be negative"):
        Time.from_nanoseconds(-1)
    with pytest.raises(OverflowError):
        Time.from_nanoseconds(2**63)
    with pytest.raises(OverflowError):
        Duration.from_nanoseconds(-(2**63) - 1)
    c = ROSClock()
    c._set_ros_time_is_active(True)
    c.set_ros_time_override(Time(seconds=5, clock_type=ClockType.ROS_TIME))
    assert c.now().nanoseconds == 5_000_000_000


def test_parameter_types() -> None:
    assert Parameter.Type.from_parameter_value([]) == Parameter.Type.BYTE_ARRAY
    assert Parameter("x", value=[1.0, 2.0]).type_ == Parameter.Type.DOUBLE_ARRAY
    with pytest.raises(ValueError, match="do not agree"):
        Parameter("x", Parameter.Type.INTEGER, 1.5)


def test_logging_filters(capsys: pytest.CaptureFixture[str]) -> None:
    log = ros_logging.get_logger("pure_test")
    results = [log.info("once", once=True) for _ in range(3)]
    assert results == [True, False, False]
    results = [log.info("skip", skip_first=True) for _ in range(2)]
    assert results == [False, True]
    with pytest.raises(TypeError, match='parameter "foo" is not one of the recognized logging options'):
        log.info("x", foo=1)
    err = capsys.readouterr().err
    assert "[INFO] [" in err and "] [pure_test]: once" in err
    log.set_level(ros_logging.LoggingSeverity.WARN)
    assert not log.info("hidden")


def test_names() -> None:
    with pytest.raises(InvalidNodeNameException) as e:
        validate_node_name("my-node")
    assert str(e.value).splitlines() == [
        "Invalid node name: node name must not contain characters other than alphanumerics or '_':",
        "  'my-node'", "     ^"]
    assert validate_namespace("/a/b")
    assert expand_topic_name("~/x", "n", "/ns") == "/ns/n/x"
    assert expand_topic_name("x", "n", "/") == "/x"
