"""A controller's node, made as controller_manager makes it (ControllerManager::determine_controller_node_options).

The node is a diffctl.client Node named after the controller, in the manager's namespace, that ignores the
process's global arguments and gets instead: the manager node's own arguments (its parameter files, -p rules
and remaps — not `__node`, `__ns` or robot_description), then `--params-file` for each `<name>.params_file`,
then `-p use_sim_time:=true` when the manager runs on sim time, then `<name>.node_options_args` (the
spawner's --controller-ros-args). Its logger services are on, as controller_interface asks, and it declares
what an rclcpp node declares (the read-only QoS overrides of /parameter_events, and /clock's on sim time).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

_REMAP_OR_PARAM_FLAGS = ("-r", "--remap", "-p", "--param")


def controller_node_arguments(
    manager_arguments: Sequence[str],
    params_files: Sequence[str] = (),
    use_sim_time: bool = False,
    node_options_args: Sequence[str] = (),
) -> list[str]:
    """The controller node's arguments (`--ros-args …`), from the manager's and the controller's settings."""
    out: list[str] = []
    for arg in manager_arguments:
        if "__ns" in arg or "__node" in arg or "robot_description" in arg:
            if out and out[-1] in _REMAP_OR_PARAM_FLAGS:
                out.pop()  # the flag whose value this is goes with it
            continue
        out.append(arg)
    extra: list[str] = []
    for f in params_files:
        extra += ["--params-file", f]
    if use_sim_time:
        extra += ["-p", "use_sim_time:=true"]
    if extra and "--ros-args" not in out:
        out.append("--ros-args")
    out += extra
    if node_options_args:
        if "--ros-args" not in node_options_args:
            out.append("--ros-args")
        out += list(node_options_args)
    return out


def make_controller_node(name: str, namespace: str, arguments: Sequence[str], context: Any = None) -> Any:
    """The controller's client Node (raises the client's exceptions on bad arguments)."""
    from diffctl.client.node import Node

    return Node(name, namespace=namespace, cli_args=list(arguments), use_global_arguments=False,
                context=context, enable_logger_service=True, client_library="rclcpp")


class ManagerTime:
    """Nodes whose ROS clock is the manager's cycle time instead of /clock: the simulator-hosted manager's and
    its controllers', so their `now()` is the sim time of the cycle being run, with or without a bridge carrying
    /clock (a zero-stamped command means that time, and a respawning bridge stops nothing)."""

    def __init__(self) -> None:
        # Replaced whole on every change (the sim thread reads it while a service thread loads or unloads).
        self._clocks: tuple[tuple[int, Any], ...] = ()

    def follow(self, node: Any) -> None:
        # rclpy's TimeSource.detach_node on the node's own time source: its clock stops following /clock.
        node.get_node_time_source_interface().detach_node()
        self._clocks = (*self._clocks, (id(node), node.get_clock()))

    def forget(self, node: Any) -> None:
        self._clocks = tuple(c for c in self._clocks if c[0] != id(node))

    def set_ns(self, time_ns: int) -> None:
        # set_ros_time_override's work without a Time to build and check: this runs on every cycle of the
        # simulator's manager, for its node and each controller's (as the nodes' own time sources set it).
        for _, clock in self._clocks:
            clock.set_ros_time_override_ns(time_ns)


def spin_resiliently(executor: Any, running: Any, log: Any) -> None:
    """Spin `executor` while `running()`: a callback that raises (a controller's, or one fed a well-formed but
    absurd request) is reported and the others go on being served, instead of the exception ending the spin
    and, with it, every node's callbacks."""
    from diffctl.client.executors import ExternalShutdownException, ShutdownException

    while running():
        try:
            executor.spin_once(timeout_sec=0.1)
        except (ExternalShutdownException, ShutdownException):
            return
        except Exception as e:
            log.error(f"a callback raised {type(e).__name__}: {e}", throttle_duration_sec=5.0)
