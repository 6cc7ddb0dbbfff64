"""`diffctl control manager`: the ros2_control_node process around a ControllerManager.

As in Jazzy: the manager's node (`controller_manager`, renamed/namespaced by `--ros-args -r __node:=`/`__ns:=`)
is made from the process's ROS arguments, with diffctl's `--param-file`s (and, when `--description FILE` is
given, that description's gz_ros2_control `<parameters>` files) as `--params-file`s before them. The robot
description comes from `--description FILE` or the latched `robot_description` topic (the manager waits for
it, saying so); only then are hardware loaded, the services created and the real-time loop started. A
multi-threaded executor spins the manager's and the controllers' nodes. Bad input is refused before anything
starts; Ctrl-C deactivates and unloads every controller and finalizes the hardware.
"""

from __future__ import annotations

import gc
import sys
import threading
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from diffctl import ros_args
from diffctl.control import realtime_publisher
from diffctl.control.controller_node import make_controller_node, spin_resiliently
from diffctl.control.manager import ControllerManager
from diffctl.control.manager_node import make_manager_node, manager_flat_params
from diffctl.control.params import manager_params
from diffctl.control.plugin_registry import hardware_for
from diffctl.control.realtime_loop import (
    LoopStats,
    SimClockTicker,
    Ticker,
    WallTicker,
    configure_sched_fifo,
    run,
)
from diffctl.control.robot_hardware import hardware_infos, parameter_files
from diffctl.control.services import ManagerServices
from diffctl.errors import ConfigError

SWITCH_INTERVAL_S = 0.0002
NODE_NAME = "controller_manager"


@dataclass
class ManagerOptions:
    description_file: str | None = None
    param_files: list[str] = field(default_factory=list)
    hardware_plugin: str | None = None
    hardware_params: dict[str, str] = field(default_factory=dict)


class ControlNode:
    """The manager node: waits for a description, then runs the manager until shutdown."""

    def __init__(self, opts: ManagerOptions, ros_argv: list[str] | None = None) -> None:
        from diffctl.client.context import get_default_context
        from diffctl.client.executors import MultiThreadedExecutor

        self.opts = opts
        ros_argv = ros_args.current_argv() if ros_argv is None else list(ros_argv)
        for f in opts.param_files:
            if not Path(f).is_file():
                raise ConfigError("parameter file not found", source=f, hint="--param-file takes an existing YAML")
        self.description: str | None = None
        self.infos: list[Any] = []
        self.problems: list[str] = []
        gz_files: list[str] = []
        if opts.description_file:
            p = Path(opts.description_file)
            if not p.is_file():
                raise ConfigError("robot description file not found", source=str(p))
            from diffctl.description.robot_files import read_description_text  # a xacro file expands first

            gz_files = self._prepare(read_description_text(p), str(p))
        files = [*gz_files, *opts.param_files]
        self.arguments = ["--ros-args", *(w for f in files for w in ("--params-file", f)), *ros_argv]
        # Bad values are refused before anything starts (the node is not made yet: no router needed).
        ra = ros_args.parse(ros_args.split_argv(self.arguments)[1], NODE_NAME)
        manager_params(ra.params, source="controller manager parameters")
        self.context = get_default_context()
        if not self.context.ok():
            self.context.init(["ros2_control_node", "--ros-args", *ros_argv])
        self.node = make_manager_node(NODE_NAME, "/", self.arguments, context=self.context,
                                      use_global_arguments=False)
        self.log = self.node.get_logger()
        # Refuse bad values before anything starts.
        self.params = manager_params(manager_flat_params(self.node), source="controller manager parameters",
                                     node_arguments=self.arguments)
        self.executor = MultiThreadedExecutor(num_threads=2, context=self.context)
        self.executor.add_node(self.node)
        self.cm: ControllerManager | None = None
        self.services: ManagerServices | None = None
        self.stats = LoopStats()
        self.stop = threading.Event()
        self._got_description = threading.Event()
        self._loop_thread: threading.Thread | None = None
        self._spin_thread: threading.Thread | None = None
        self.ticker: Ticker | None = None
        self.failed: ConfigError | None = None

    # --- description → hardware --------------------------------------------------------------------------
    def _prepare(self, text: str, source: str) -> list[str]:
        """Parse what the description gives before anything starts (raises ConfigError subclasses); returns its
        gz_ros2_control `<parameters>` files."""
        extra = dict(self.opts.hardware_params)
        self.infos = hardware_infos(text, source, plugin_override=self.opts.hardware_plugin, extra_params=extra)
        for info in self.infos:
            hardware_for(info)  # an unknown plugin is bad input: refuse it before starting anything
        files, self.problems = parameter_files(text, source)
        self.description = text
        return files

    def start(self) -> None:
        """Build the manager from the description, load hardware, create services, start the loop."""
        assert self.description is not None
        for p in self.problems:
            if self.opts.param_files or "--params-file" in self.arguments:
                self.log.info(f"{p}; using the parameter files given on the command line")
            else:
                self.log.warn(p)
        params = self.params
        namespace = self.node.get_namespace()

        def factory(name: str, arguments: list[str]) -> Any:
            return make_controller_node(name, namespace, arguments, context=self.context)

        self.cm = ControllerManager(params, log=self.log, node_factory=factory, robot_description=self.description,
                                    cancel=self.stop, executor=self.executor)
        self.cm.load_hardware(self.infos)
        self.services = ManagerServices(self.node, self.cm)
        self.ticker = self._make_ticker()
        # A waking control thread waits for the GIL up to the switch interval (5 ms by default) while another
        # thread runs: shorten it so a period's jitter stays well under a millisecond. Objects alive after
        # start-up never become garbage; freezing them keeps full collections short inside the loop.
        sys.setswitchinterval(SWITCH_INTERVAL_S)
        gc.freeze()
        if isinstance(self.ticker, WallTicker):
            # The controllers' samples are fetched by the publishing thread's polling between cycles: waking it
            # from the cycle is a system call on the real-time thread (realtime_tools' publishers poll too).
            realtime_publisher.poll_held(True)
        self.cm.loop_running = True
        self._loop_thread = threading.Thread(target=self._loop, name="controller_manager_rt", daemon=True)
        self._loop_thread.start()
        self.log.info(
            f"controller manager ready: {params.update_rate} Hz, "
            f"{'sim' if params.use_sim_time else 'wall'} time, hardware "
            f"[{', '.join(f'{i.name} ({i.plugin_name})' for i in self.infos)}]"
        )

    def _make_ticker(self) -> Ticker:
        assert self.cm is not None
        if self.cm.params.use_sim_time:
            return SimClockTicker(self.cm.update_rate, self.node.get_clock())

        def overrun(text: str) -> None:
            if self.node.get_parameter_or("overruns.print_warnings").value is not False:
                self.log.warn(text, throttle_duration_sec=1.0)

        return WallTicker(self.cm.update_rate, self.stats, overrun, self.cm.params.manage_overruns)

    def _loop(self) -> None:
        assert self.cm is not None and self.ticker is not None
        cm = self.cm
        why_not = configure_sched_fifo(cm.params.thread_priority)
        if why_not:
            self.log.warn(f"{why_not}; the control loop runs at normal priority")
        else:
            self.log.info(f"control loop on SCHED_FIFO priority {cm.params.thread_priority}")
        try:
            run(cm.cycle, self.ticker, self.stop, self.stats)  # read → update → write
        except Exception as e:  # the loop dying silently would freeze the robot with no word
            self.log.error(f"the control loop stopped: {type(e).__name__}: {e}")
            self.stop.set()

    # --- process lifetime ------------------------------------------------------------------------------
    def _on_description(self, msg: Any) -> None:
        if self._got_description.is_set():
            self.log.warn(
                "ResourceManager has already loaded a urdf and is initialized. Ignoring attempt to reload a robot "
                "description."
            )
            return
        self.log.info("Received robot description from topic.")
        try:
            files = self._prepare(str(msg.data), "robot_description topic")
        except ConfigError as e:
            self.log.error(f"robot_description: {e}")
            self.failed = e
            self.stop.set()
        else:
            if files and "--params-file" not in self.arguments:
                self.problems.append(
                    f"the description's gz_ros2_control <parameters> ({', '.join(files)}) are the simulator's: "
                    "ros2_control_node reads its own parameter files (--ros-args --params-file FILE)"
                )
        self._got_description.set()

    def _spin(self) -> None:
        try:
            spin_resiliently(self.executor, lambda: not self.stop.is_set() and self.context.ok(), self.log)
        finally:
            self.stop.set()

    def start_spinning(self) -> None:
        """Spin the executor on a thread of its own: the manager's services and the controllers' subscriptions
        (a controller's ~/cmd_vel) are served from then on."""
        self._spin_thread = threading.Thread(target=self._spin, name="controller_manager_executor", daemon=True)
        self._spin_thread.start()

    def serve(self) -> None:
        """Run until SIGINT/SIGTERM; raises the ConfigError that stopped start-up, if any."""
        import signal

        from diffctl.client.interfaces import cls
        from diffctl.client.qos import DurabilityPolicy, QoSProfile

        def on_signal(*_: object) -> None:
            self.stop.set()

        for sig in (signal.SIGINT, signal.SIGTERM):
            signal.signal(sig, on_signal)
        self.start_spinning()
        try:
            if self.description is None:
                # Relative, as current Jazzy: /robot_description at the root, /<ns>/robot_description in a namespace.
                self.node.create_subscription(cls("std_msgs/msg/String"), "robot_description", self._on_description,
                                              QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL))
                ticks = 0
                while not self._got_description.wait(0.1) and not self.stop.is_set():
                    if ticks % 10 == 0:
                        self.log.warn("Waiting for data on 'robot_description' topic to finish initialization")
                    ticks += 1
                if self.failed is not None:
                    raise self.failed
                if self.stop.is_set():
                    return
            self.start()
            while not self.stop.wait(0.25):
                pass
        finally:
            self.shutdown()

    def shutdown(self) -> None:
        self.stop.set()
        if self._loop_thread is not None:
            self._loop_thread.join(2.0)
        if self.cm is not None:
            self.cm.loop_running = False
            realtime_publisher.poll_held(False)
            self.cm.shutdown()
        if self.services is not None:
            self.services.close()
        if self._spin_thread is not None:
            self._spin_thread.join(2.0)
        stats = self.stats.summary(1.0 / self.cm.update_rate) if self.cm is not None else {}
        if stats.get("overruns"):
            self.log.warn(f"{stats['overruns']} overruns in {stats['cycles']} cycles")
        self.executor.shutdown(timeout_sec=1.0)
        self.node.destroy_node()
        self.context.try_shutdown()


def main(opts: ManagerOptions) -> None:
    ControlNode(opts).serve()
