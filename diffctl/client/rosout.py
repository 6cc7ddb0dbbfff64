"""`/rosout`: a node's log lines as rcl_interfaces/msg/Log, published as rcl does.

One publisher per node with rcl's rosout QoS (reliable, transient local, keep_last 1000, lifespan 10 s), so
rqt_console and `ros2 topic echo /rosout` see a node's recent lines even when they start later. Lines are
handed to one background thread per process: a control loop that logs never waits on a Zenoh put.
"""

from __future__ import annotations

import collections
import sys
import threading
from typing import TYPE_CHECKING, Any

from diffctl.bus import wire
from diffctl.bus.session import before_close, closing, join_after_close
from diffctl.client import ros_logging
from diffctl.client.ros_logging import LogRecord
from diffctl.client.signals import shut_down_by_signal

if TYPE_CHECKING:
    from diffctl.bus.endpoints import Publisher

TOPIC = "/rosout"
LOG_TYPE = "rcl_interfaces/msg/Log"
ROSOUT_QOS = wire.QoS(transient_local=True, depth=1000, lifespan_ns=10_000_000_000)
_CONTEXT_INVALID = "publisher's context is invalid, at /project/src/rcl/publisher.c:423"
_QUEUE_MAX = 10_000  # lines waiting for the publisher thread; the oldest go first when a flood outruns it


class _Outbox:
    def __init__(self) -> None:
        self._queue: collections.deque[tuple[Publisher, LogRecord]] = collections.deque(maxlen=_QUEUE_MAX)
        self._cond = threading.Condition()
        self._thread: threading.Thread | None = None

    def put(self, pub: Publisher, rec: LogRecord) -> None:
        if closing():
            return  # the session is going: the console has the line, /rosout can no longer get it
        with self._cond:
            self._queue.append((pub, rec))
            if self._thread is None:
                self._thread = threading.Thread(target=self._run, name="rosout", daemon=True)
                self._thread.start()
                # A starved put can outlast stop()'s wait: the session's close then waits for it to leave Zenoh.
                join_after_close(self._thread)
            self._cond.notify()

    def drain(self, pub: Publisher, timeout_s: float) -> None:
        """Wait (bounded) until no line of `pub` is queued, so a node's last words reach /rosout."""
        with self._cond:
            self._cond.wait_for(lambda: all(p is not pub for p, _ in self._queue) and self._busy is not pub,
                                timeout_s)

    _busy: Publisher | None = None

    def stop(self, timeout_s: float = 1.0) -> None:
        """Publish what is queued (bounded), then end the thread: it must not be inside a Zenoh put when the
        session closes or the interpreter finalizes."""
        with self._cond:
            self._cond.wait_for(lambda: not self._queue and self._busy is None, timeout_s)
            self._queue.clear()
            thread, self._thread = self._thread, None  # the thread ends once it is no longer the outbox's
            self._cond.notify_all()
        if thread is not None and thread is not threading.current_thread():
            thread.join(timeout_s)

    def _run(self) -> None:
        me = threading.current_thread()
        while True:
            with self._cond:
                while not self._queue and self._thread is me:
                    self._cond.wait()
                if self._thread is not me:
                    return
                pub, rec = self._queue.popleft()
                self._busy = pub
            try:
                if not pub.closed:
                    pub.publish(_message(rec))
            except Exception:
                pass  # the node is closing or the session is gone; the console line was written already
            with self._cond:
                self._busy = None
                self._cond.notify_all()


_outbox = _Outbox()
before_close(_outbox.stop)


def _message(rec: LogRecord) -> dict:
    return {
        "stamp": {"sec": rec.stamp_ns // 1_000_000_000, "nanosec": rec.stamp_ns % 1_000_000_000},
        "level": rec.level, "name": rec.name, "msg": rec.msg, "file": rec.file, "function": rec.function,
        "line": max(0, rec.line),
    }


class Rosout:
    """A node's `/rosout` publisher, fed by the loggers named as the node (and their children)."""

    def __init__(self, participant: Any, logger_name: str, context: Any = None) -> None:
        self.pub = participant.create_publisher(TOPIC, LOG_TYPE, qos=ROSOUT_QOS)
        self._name = logger_name
        self._context = context
        ros_logging.attach_rosout(logger_name, self._sink)

    def _sink(self, rec: LogRecord) -> None:
        if self._context is not None and shut_down_by_signal(self._context):
            # A signal shuts the context down under rcl's logging (rclpy.shutdown() also ends the rosout
            # handler): rcl's handler then refuses the publisher and says so on stderr after the console line,
            # which is what a node that logs after Ctrl-C or SIGTERM prints under the real rclpy
            try:
                sys.stderr.write(f"Failed to publish log message to rosout: {_CONTEXT_INVALID}\n")
                sys.stderr.flush()
            except (ValueError, OSError):
                pass
            return
        _outbox.put(self.pub, rec)

    def close(self) -> None:
        ros_logging.detach_rosout(self._name, self._sink)
        _outbox.drain(self.pub, 1.0)
        self.pub.close()
