"""The controllers' RealtimePublisher: bytes taken at publish time, put later in order, overflow dropped oldest."""

from __future__ import annotations

import threading

from diffctl.control.cdr_template import CdrTemplate
from diffctl.control.realtime_publisher import PublishingThread, RealtimePublisher
from diffctl.interfaces import types


class SlowSink:
    """A bus publisher stand-in whose put blocks until released."""

    type = "std_msgs/msg/Float64"

    def __init__(self) -> None:
        self.sent: list[float] = []
        self.release = threading.Event()

    def publish_raw(self, cdr: bytes) -> None:
        self.release.wait(5)
        self.sent.append(types.deserialize(cdr, self.type).data)


def test_a_reused_message_is_sent_as_it_was_when_published_in_order() -> None:
    sink = SlowSink()
    pub = RealtimePublisher(sink, PublishingThread())
    msg = types.new(sink.type, {"data": 0.0})
    for i in range(5):
        msg.data = float(i)  # controllers reuse their message objects from cycle to cycle
        pub.publish(msg)
    sink.release.set()
    assert pub._thread.flush(5)
    assert sink.sent == [0.0, 1.0, 2.0, 3.0, 4.0]
    assert pub.type == "std_msgs/msg/Float64"  # everything else is the wrapped publisher's


def test_when_the_network_stalls_the_oldest_samples_are_dropped_and_counted() -> None:
    sink = SlowSink()
    thread = PublishingThread(capacity=3)
    pub = RealtimePublisher(sink, thread)
    for i in range(10):
        pub.publish({"data": float(i)})  # returns at once although nothing can be put
    sink.release.set()
    assert thread.flush(5)
    assert sink.sent[-3:] == [7.0, 8.0, 9.0] and thread.dropped >= 6


class Sink:
    type = "std_msgs/msg/Float64"

    def __init__(self) -> None:
        self.sent: list[float] = []
        self.got = threading.Event()

    def publish_raw(self, cdr: bytes) -> None:
        self.sent.append(types.deserialize(cdr, self.type).data)
        self.got.set()


def test_a_held_cycle_hands_its_samples_over_at_release_and_other_threads_at_once(monkeypatch) -> None:
    from diffctl.control import realtime_publisher

    thread = PublishingThread()
    monkeypatch.setattr(realtime_publisher, "_thread", thread)
    sink = Sink()
    pub = RealtimePublisher(sink, thread)
    held = realtime_publisher.hold()
    assert held is thread and realtime_publisher.hold() is None  # nested: the outer release wakes
    pub.publish({"data": 1.0})
    pub.publish_values(CdrTemplate(types.new(sink.type, {"data": 0.0}), sink.type, [("data", "d")]), (2.0,))
    assert not sink.got.wait(0.2) and sink.sent == []  # queued, the publishing thread not woken
    realtime_publisher.release(held)
    assert sink.got.wait(5) and thread.flush(5)
    assert sink.sent == [1.0, 2.0]

    held = realtime_publisher.hold()
    sink.got.clear()
    other = threading.Thread(target=pub.publish, args=({"data": 3.0},))
    other.start()
    other.join()
    assert sink.got.wait(5) and sink.sent == [1.0, 2.0, 3.0]  # not the holder's: woken at once
    realtime_publisher.release(held)
