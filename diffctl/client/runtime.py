"""rclpy's top-level functions: init/shutdown, the global executor and the spin helpers."""

from __future__ import annotations

from typing import Any

from diffctl.client.context import Context, get_default_context, track
from diffctl.client.signals import SignalHandlerOptions, install_signal_handlers, shut_down_by_signal
from diffctl.client.task import Future

_global_executor: Any = None


class InitContextManager:
    """What init() returns: `with rclpy.init():` shuts the context down on leaving. (Jazzy's init returns None;
    later releases return this, and ros2/examples use it, so programs written for either run.)"""

    def __init__(self, args: list[str] | None, context: Context | None, domain_id: int | None) -> None:
        self.context = get_default_context() if context is None else context
        track(self.context)
        self.context.init(args, domain_id=domain_id)

    def __enter__(self) -> InitContextManager:
        return self

    def __exit__(self, *exc: Any) -> None:
        self.context.try_shutdown()


def init(*, args: list[str] | None = None, context: Context | None = None, domain_id: int | None = None,
         signal_handler_options: SignalHandlerOptions | None = None) -> InitContextManager:
    if signal_handler_options is None:
        signal_handler_options = (SignalHandlerOptions.ALL if context is None or context is get_default_context()
                                  else SignalHandlerOptions.NO)
    manager = InitContextManager(args, context, domain_id)
    # After the context's init, as rclpy: a signal during a long init still ends the process the default way.
    install_signal_handlers(signal_handler_options)
    return manager


def shutdown(*, context: Context | None = None, uninstall_handlers: bool | None = None) -> None:
    _shutdown(context=context, uninstall_handlers=uninstall_handlers, try_only=False)


def try_shutdown(*, context: Context | None = None, uninstall_handlers: bool | None = None) -> None:
    _shutdown(context=context, uninstall_handlers=uninstall_handlers, try_only=True)


def _shutdown(*, context: Context | None, uninstall_handlers: bool | None, try_only: bool) -> None:
    global _global_executor
    if uninstall_handlers is None:
        # rclpy's shutdown of the default context takes its signal handlers away (try_shutdown, in Jazzy, not)
        uninstall_handlers = not try_only and (context is None or context is get_default_context())
    if context is None:
        context = get_default_context(shutting_down=True)
    if try_only:
        context.try_shutdown()
    else:
        context.shutdown()
    if uninstall_handlers:
        from diffctl.client.signals import uninstall_signal_handlers

        uninstall_signal_handlers()


def ok(*, context: Context | None = None) -> bool:
    return (get_default_context() if context is None else context).ok()


def get_global_executor() -> Any:
    global _global_executor
    if _global_executor is None:
        from diffctl.client.executors import SingleThreadedExecutor

        _global_executor = SingleThreadedExecutor()
        context = get_default_context()

        def reset() -> None:
            global _global_executor
            ex, _global_executor = _global_executor, None
            if ex is not None:
                ex.shutdown()

        context.on_shutdown(reset)
        _global_executor._reset_ref = reset  # the context keeps only a weak reference to bound methods
    return _global_executor


def create_node(node_name: str, *, context: Context | None = None, cli_args: list[str] | None = None,
                namespace: str | None = None, use_global_arguments: bool = True, enable_rosout: bool = True,
                start_parameter_services: bool = True, parameter_overrides: list[Any] | None = None,
                allow_undeclared_parameters: bool = False,
                automatically_declare_parameters_from_overrides: bool = False,
                enable_logger_service: bool = False) -> Any:
    from diffctl.client.node import Node

    return Node(node_name, context=context, cli_args=cli_args, namespace=namespace,
                use_global_arguments=use_global_arguments, enable_rosout=enable_rosout,
                start_parameter_services=start_parameter_services, parameter_overrides=parameter_overrides,
                allow_undeclared_parameters=allow_undeclared_parameters,
                automatically_declare_parameters_from_overrides=automatically_declare_parameters_from_overrides,
                enable_logger_service=enable_logger_service)


def spin_once(node: Any, *, executor: Any = None, timeout_sec: float | None = None) -> None:
    executor = get_global_executor() if executor is None else executor
    added = False
    try:
        added = executor.add_node(node)
        executor.spin_once(timeout_sec=timeout_sec)
    finally:
        if added:
            executor.remove_node(node)


def spin(node: Any, executor: Any = None) -> None:
    executor = get_global_executor() if executor is None else executor
    try:
        executor.add_node(node)
        while executor.context.ok():
            executor.spin_once()
        if getattr(executor, "_raises_external_shutdown", True) and shut_down_by_signal(executor.context):
            from diffctl.client.executors import ExternalShutdownException

            raise ExternalShutdownException()
    finally:
        executor.remove_node(node)


def spin_until_future_complete(node: Any, future: Future, executor: Any = None,
                               timeout_sec: float | None = None) -> None:
    executor = get_global_executor() if executor is None else executor
    try:
        executor.add_node(node)
        executor.spin_until_future_complete(future, timeout_sec)
    finally:
        executor.remove_node(node)
