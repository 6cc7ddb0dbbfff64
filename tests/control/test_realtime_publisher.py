"""The controllers' RealtimePublisher: bytes taken at publish time, put later in order, overflow dropped oldest."""

from __future__ import annotations

import threading

from diffctl.client.interfaces import cls, deserialize
from diffctl.control.cdr_template import CdrTemplate
from diffctl.control.realtime_publisher import PublishingThread, RealtimePublisher

FLOAT64 = "std_msgs/msg/Float64"


def value(data: float):
    return cls(FLOAT64)(data=data)


class SlowSink:
    """A client publisher stand-in whose put blocks until released."""

    msg_type = cls(FLOAT64)

    def __init__(self) -> None:
        self.sent: list[float] = []
        self.release = threading.Event()

    def publish(self, cdr: bytes) -> None:
        self.release.wait(5)
        self.sent.append(deserialize(cdr, self.msg_type).data)


def test_a_reused_message_is_sent_as_it_was_when_published_in_order() -> None:
    sink = SlowSink()
    pub = RealtimePublisher(sink, PublishingThread())
    msg = value(0.0)
    for i in range(5):
        msg.data = float(i)  # controllers reuse their message objects from cycle to cycle
        pub.publish(msg)
    sink.release.set()
    assert pub._thread.flush(5)
    assert sink.sent == [0.0, 1.0, 2.0, 3.0, 4.0]
    assert pub.msg_type is cls(FLOAT64)  # everything else is the wrapped publisher's


def test_when_the_network_stalls_the_oldest_samples_are_dropped_and_counted() -> None:
    sink = SlowSink()
    thread = PublishingThread(capacity=3)
    pub = RealtimePublisher(sink, thread)
    for i in range(10):
        pub.publish(value(float(i)))  # returns at once although nothing can be put
    sink.release.set()
    assert thread.flush(5)
    assert sink.sent[-3:] == [7.0, 8.0, 9.0] and thread.dropped >= 6


class Sink:
    msg_type = cls(FLOAT64)

    def __init__(self) -> None:
        self.sent: list[float] = []
        self.got = threading.Event()

    def publish(self, cdr: bytes) -> None:
        self.sent.append(deserialize(cdr, self.msg_type).data)
        self.got.set()


def test_a_held_cycle_hands_its_samples_over_at_release_and_other_threads_at_once(monkeypatch) -> None:
    from diffctl.control import realtime_publisher

    thread = PublishingThread()
    monkeypatch.setattr(realtime_publisher, "_thread", thread)
    sink = Sink()
    pub = RealtimePublisher(sink, thread)
    held = realtime_publisher.hold()
    assert held is thread and realtime_publisher.hold() is None  # nested: the outer release wakes
    pub.publish(value(1.0))
    pub.publish_values(CdrTemplate(value(0.0), FLOAT64, [("data", "d")]), (2.0,))
    assert not sink.got.wait(0.2) and sink.sent == []  # queued, the publishing thread not woken
    realtime_publisher.release(held)
    assert sink.got.wait(5) and thread.flush(5)
    assert sink.sent == [1.0, 2.0]

    held = realtime_publisher.hold()
    sink.got.clear()
    other = threading.Thread(target=pub.publish, args=(value(3.0),))
    other.start()
    other.join()
    assert sink.got.wait(5) and sink.sent == [1.0, 2.0, 3.0]  # not the holder's: woken at once
    realtime_publisher.release(held)


def test_a_polling_thread_takes_held_cycles_samples_without_being_woken_and_stops_when_idle(monkeypatch) -> None:
    from diffctl.control import realtime_publisher

    monkeypatch.setattr(realtime_publisher, "IDLE_NS", 50_000_000)
    thread = PublishingThread()
    thread.poll_held = True  # as ros2_control_node's wall-clock loop sets it
    monkeypatch.setattr(realtime_publisher, "_thread", thread)
    sink = Sink()
    pub = RealtimePublisher(sink, thread)
    for i in range(3):
        held = realtime_publisher.hold()
        sink.got.clear()
        pub.publish(value(float(i)))
        assert not sink.got.wait(0.02)  # never taken in the middle of a cycle
        realtime_publisher.release(held)
        if i:  # the first release woke the thread and set it polling; the later ones leave it to the polling
            assert thread._polling and thread._signal.locked()
        assert sink.got.wait(5)
    assert sink.sent == [0.0, 1.0, 2.0]
    sink.got.clear()
    other = threading.Thread(target=pub.publish, args=(value(2.5),))  # another thread's sample, while polling
    other.start()
    other.join()
    assert sink.got.wait(5) and sink.sent[-1] == 2.5
    pause = threading.Event()
    for _ in range(500):  # idle for IDLE_NS: back to being woken (5 s: a generous failure bound)
        if not thread._polling:
            break
        pause.wait(0.01)
    assert not thread._polling
    sink.got.clear()
    held = realtime_publisher.hold()
    pub.publish(value(3.0))
    realtime_publisher.release(held)
    assert sink.got.wait(5) and sink.sent[-1] == 3.0
