"""The launch process's own ROS node, for the actions that talk to the graph: lifecycle transitions, a
container's load_node service, RosTimer's clock, SetUseSimTime.

One node per LaunchContext (`launch_ros_<pid>`, in a client Context of its own, spun by an executor on its
own thread), made by the first action that asks for it: a launch file with plain Nodes opens no session.
It is diffctl's client (rclpy's API), so it joins the graph as any node diffctl starts does. The launch's
shutdown stops it.
"""

from __future__ import annotations

import os
import threading
from typing import Any

from diffctl.launch.event_handlers import OnShutdown
from diffctl.launch.launch_context import LaunchContext


class ROSAdapter:
    """A client context, a node and the thread spinning it; `autostart` starts them at once."""

    def __init__(self, *, argv: list[str] | None = None, autostart: bool = True) -> None:
        self.__argv = [] if argv is None else list(argv)  # never None: that would read sys.argv
        self.__ros_context: Any = None
        self.__ros_node: Any = None
        self.__ros_executor: Any = None
        self.__thread: threading.Thread | None = None
        self.__is_running = False
        if autostart:
            self.start()

    def start(self) -> None:
        """Initialize the context, make the node, start spinning it."""
        if self.__is_running:
            raise RuntimeError("Cannot start a ROS adapter that is already running")
        from diffctl.client import runtime
        from diffctl.client.context import Context
        from diffctl.client.executors import SingleThreadedExecutor

        self.__ros_context = Context()
        runtime.init(args=self.__argv, context=self.__ros_context)
        self.__ros_node = runtime.create_node(f"launch_ros_{os.getpid()}", context=self.__ros_context)
        self.__ros_executor = SingleThreadedExecutor(context=self.__ros_context)
        self.__ros_executor.add_node(self.__ros_node)
        self.__is_running = True
        self.__thread = threading.Thread(target=self._run, name="launch_ros-adapter", daemon=True)
        self.__thread.start()

    def _run(self) -> None:
        try:
            self.__ros_executor.spin()  # until shutdown() stops the executor
        except Exception:  # the context was shut down under it
            pass

    def shutdown(self) -> None:
        """Stop spinning, destroy the node, shut the context down."""
        if not self.__is_running:
            raise RuntimeError("Cannot shutdown a ROS adapter that is not running")
        self.__is_running = False
        self.__ros_executor.shutdown()
        if self.__thread is not None and self.__thread is not threading.current_thread():
            self.__thread.join()
        self.__ros_node.destroy_node()
        self.__ros_context.try_shutdown()

    @property
    def argv(self) -> list[str]:
        return self.__argv

    @property
    def ros_context(self) -> Any:
        return self.__ros_context

    @property
    def ros_node(self) -> Any:
        return self.__ros_node

    @property
    def ros_executor(self) -> Any:
        return self.__ros_executor


def get_ros_adapter(context: LaunchContext) -> ROSAdapter:
    """The adapter of this launch context, made (and tied to the launch's shutdown) on first use.
    Reentrant; not safe from several threads at once."""
    adapter = getattr(context.locals, "ros_adapter", None)
    if adapter is None:
        adapter = ROSAdapter()
        context.extend_globals({"ros_adapter": adapter})

        def stop(*_args: Any, **_kwargs: Any) -> None:
            try:
                adapter.shutdown()
            except RuntimeError:  # a later Shutdown event (an on_exit=Shutdown() after the launch's): stopped already
                pass

        context.register_event_handler(OnShutdown(on_shutdown=stop))
    return adapter


def get_ros_node(context: LaunchContext) -> Any:
    """The launch process's node of this launch context (see get_ros_adapter)."""
    return get_ros_adapter(context).ros_node
