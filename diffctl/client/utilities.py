"""rclpy.utilities: argument helpers and the context shortcuts."""

from __future__ import annotations

from diffctl.client.context import Context, get_default_context


def remove_ros_args(args: list[str] | None = None) -> list[str]:
    """argv without its --ros-args spans (and the `--` ending one), as rcl_remove_ros_arguments."""
    import sys

    from diffctl.ros_args import split_argv

    plain, _ = split_argv(list(sys.argv if args is None else args))
    return plain


def get_rmw_implementation_identifier() -> str:
    return "rmw_zenoh_cpp"


def ok(*, context: Context | None = None) -> bool:
    return (get_default_context() if context is None else context).ok()


def shutdown(*, context: Context | None = None) -> None:
    (get_default_context() if context is None else context).shutdown()


def try_shutdown(*, context: Context | None = None) -> None:
    (get_default_context() if context is None else context).try_shutdown()


def get_available_rmw_implementations() -> set[str]:
    return {"rmw_zenoh_cpp"}


def timeout_sec_to_nsec(timeout_sec: float | None) -> int:
    if timeout_sec is None or timeout_sec < 0:
        return -1
    return int(float(timeout_sec) * 1e9)


__all__ = ["get_default_context", "get_rmw_implementation_identifier", "ok", "remove_ros_args", "shutdown",
           "timeout_sec_to_nsec", "try_shutdown"]
