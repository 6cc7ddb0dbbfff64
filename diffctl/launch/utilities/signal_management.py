"""`AsyncSafeSignalManager`: POSIX signals delivered as callbacks on an asyncio loop.

Python's C-level signal handler writes the number of every caught signal to the "wakeup fd". The manager
points that fd at one end of a socket pair and reads the other end on the loop, so its callbacks run as
ordinary loop callbacks (safe to touch futures and queues). The previous wakeup fd keeps receiving every
byte, so an outer manager or another library still sees its signals. Only signals that have a Python-level
handler reach the wakeup fd: whoever wants one handled must install one (`signal.signal`).
"""

from __future__ import annotations

import asyncio
import os
import signal
import socket
import threading
from collections.abc import Callable

Handler = Callable[[int], None]


class AsyncSafeSignalManager:
    """Context manager dispatching signals to callbacks registered with `handle()`, on `loop`.

    It may be entered several times in a row and nested with other managers; callbacks registered
    outside the context take effect when it is entered. Entering it outside the main thread raises
    ValueError (as `signal.set_wakeup_fd` does).
    """

    def __init__(self, loop: asyncio.AbstractEventLoop) -> None:
        self.__loop = loop
        self.__handlers: dict[int, Handler] = {}
        self.__sockets: tuple[socket.socket, socket.socket] | None = None
        self.__previous_fd = -1

    def __enter__(self) -> AsyncSafeSignalManager:
        if threading.current_thread() is not threading.main_thread():
            raise ValueError('set_wakeup_fd only works in main thread of the main interpreter')
        reader, writer = socket.socketpair()
        reader.setblocking(False)
        writer.setblocking(False)
        try:
            self.__loop.add_reader(reader.fileno(), self.__dispatch)
            try:
                self.__previous_fd = signal.set_wakeup_fd(writer.fileno(), warn_on_full_buffer=False)
            except BaseException:
                self.__loop.remove_reader(reader.fileno())
                raise
        except BaseException:
            reader.close()
            writer.close()
            raise
        self.__sockets = (reader, writer)
        return self

    def __exit__(self, exc_type, exc_value, exc_traceback) -> None:
        if self.__sockets is None:
            return
        reader, writer = self.__sockets
        self.__sockets = None
        try:
            signal.set_wakeup_fd(self.__previous_fd)
        finally:
            self.__previous_fd = -1
            self.__loop.remove_reader(reader.fileno())
            reader.close()
            writer.close()

    def __dispatch(self) -> None:
        if self.__sockets is None:
            return
        reader = self.__sockets[0]
        while True:
            try:
                data = reader.recv(4096)
            except InterruptedError:
                continue
            except BlockingIOError:
                return
            if not data:
                return
            for signum in data:
                handler = self.__handlers.get(signum)
                if handler is not None:
                    handler(signum)
            if self.__previous_fd != -1:
                try:
                    os.write(self.__previous_fd, data)
                except OSError:
                    pass  # the outer listener is gone or full: its loss, not ours

    def handle(self, signum: signal.Signals | int, handler: Handler | None) -> Handler | None:
        """Call `handler(signum)` on the loop when `signum` arrives (None removes it); the old one is returned."""
        signum = signal.Signals(signum)
        if handler is None:
            return self.__handlers.pop(signum, None)
        if not callable(handler):
            raise ValueError('signal handler must be a callable')
        old = self.__handlers.get(signum)
        self.__handlers[signum] = handler
        return old
