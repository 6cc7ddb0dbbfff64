"""`diffctl control manager`: the ros2_control_node process around a ControllerManager.

Start-up as in Jazzy: the robot description comes from `--description FILE` or the latched
`/robot_description` topic (the manager waits for it, saying so); only then are hardware loaded, the
services created and the real-time loop started. Parameters: the gz_ros2_control plugin's `<parameters>`
files, then `--param-file`s, then `--ros-args` (`--params-file`, `-p`). Bad input is refused before
anything starts; Ctrl-C deactivates and unloads every controller and finalizes the hardware.
"""

from __future__ import annotations

import gc
import sys
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from diffctl import ros_args
from diffctl.control.controller_node import BusControllerNode
from diffctl.control.manager import ControllerManager
from diffctl.control.params import load_manager_files, manager_params
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


@dataclass
class ManagerOptions:
    description_file: str | None = None
    param_files: list[str] = field(default_factory=list)
    hardware_plugin: str | None = None
    hardware_params: dict[str, str] = field(default_factory=dict)


class ControlNode:
    """The manager node: waits for a description, then runs the manager until shutdown."""

    def __init__(self, opts: ManagerOptions, rargs: ros_args.RosArgs | None = None) -> None:
        from diffctl.bus import Node

        self.opts = opts
        self.ra = rargs or ros_args.current("controller_manager")
        for f in opts.param_files:
            if not Path(f).is_file():
                raise ConfigError("parameter file not found", source=f, hint="--param-file takes an existing YAML")
        self.name = self.ra.node_name or "controller_manager"
        self.fqn = ros_args.node_fqn(self.name, self.ra.namespace or "/")
        self.base_flat = {**load_manager_files(opts.param_files, self.fqn), **self.ra.params}
        manager_params(self.base_flat, source="controller manager parameters")  # refuse bad values up front
        self.description: str | None = None
        self.description_source = "robot_description"
        self.infos: list[Any] = []
        self.gz_files: list[str] = []
        if opts.description_file:
            p = Path(opts.description_file)
            if not p.is_file():
                raise ConfigError("robot description file not found", source=str(p))
            from diffctl.description.robot_files import read_description_text  # a xacro file expands first

            self._prepare(read_description_text(p), str(p))
        self.node = Node(self.name, self.ra.namespace or "/", remaps=self.ra.remaps, params=dict(self.base_flat))
        self.log = self.node.log
        self.cm: ControllerManager | None = None
        self.services: ManagerServices | None = None
        self.stats = LoopStats()
        self.stop = threading.Event()
        self._got_description = threading.Event()
        self._loop_thread: threading.Thread | None = None
        self._last_cycle_ns = 0
        self.ticker: Ticker | None = None

    # --- description → hardware and parameters --------------------------------------------------------
    def _prepare(self, text: str, source: str) -> None:
        """Parse everything the description gives before anything starts (raises ConfigError subclasses)."""
        extra = dict(self.opts.hardware_params)
        self.infos = hardware_infos(text, source, plugin_override=self.opts.hardware_plugin, extra_params=extra)
        for info in self.infos:
            hardware_for(info)  # an unknown plugin is bad input: refuse it before starting anything
        files, problems = parameter_files(text, source)
        self.gz_files = files
        self.problems = problems
        self.description, self.description_source = text, source

    def _flat_params(self) -> dict[str, Any]:
        return {**load_manager_files(self.gz_files, self.fqn), **self.base_flat}

    def now_ns(self) -> int:
        if self.cm is not None and self.cm.params.use_sim_time:
            return max(self._last_cycle_ns, self.node.clock.now_ns())
        return time.time_ns()

    def _on_cycle_time(self, t_ns: int) -> None:
        self._last_cycle_ns = t_ns

    def start(self) -> None:
        """Build the manager from the description, load hardware, create services, start the loop."""
        assert self.description is not None
        for p in getattr(self, "problems", []):
            if self.opts.param_files or self.ra.params_files:
                self.log.info(f"{p}; using the parameter files given on the command line")
            else:
                self.log.warn(p)
        flat = self._flat_params()
        files = tuple(self.gz_files) + tuple(self.opts.param_files) + tuple(self.ra.params_files)
        # The process's arguments, every node's of it: diffctl's --param-file and the plugin's files first, then
        # --ros-args' files and -p rules in their order (the controllers' global arguments, as in Jazzy).
        process = ros_args.ParameterOverrides()
        for f in (*self.gz_files, *self.opts.param_files):
            process.add_file(f)
        for key, entry in self.ra.overrides.entries.items():
            process.entries.setdefault(key, {}).update(entry)
        params = manager_params(flat, source="controller manager parameters", params_files=files,
                                namespace=self.node.namespace, overrides=process)
        self.node.params.update(flat)
        if params.use_sim_time and not self.node.clock.use_sim_time:
            self.node.clock.use_sim_time = True
            self.node.create_subscription("/clock", "rosgraph_msgs/msg/Clock", self.node.clock.on_clock)

        process_argv = ros_args.current_argv()

        def factory(name: str, p: dict[str, Any], remaps: dict[str, str] | None = None) -> BusControllerNode:
            # The node's own rules (--controller-ros-args) first, then the process's that apply to it
            # (unprefixed, or prefixed with its name: `diffbot_base_controller:~/cmd_vel:=/cmd_vel`).
            own = dict(remaps or {})
            for k, v in ros_args.parse(process_argv, name, self.node.namespace).remaps.items():
                own.setdefault(k, v)
            return BusControllerNode(name, self.node.namespace, p, self.now_ns, remaps=own)

        self.cm = ControllerManager(
            params, log=self.log, node_factory=factory, robot_description=self.description, cancel=self.stop
        )
        self.cm.load_hardware(self.infos)
        self.services = ManagerServices(self.node, self.cm)
        self.ticker = self._make_ticker()
        # A waking control thread waits for the GIL up to the switch interval (5 ms by default) while a bus
        # thread runs: shorten it so a period's jitter stays well under a millisecond. Objects alive after
        # start-up never become garbage; freezing them keeps full collections short inside the loop.
        sys.setswitchinterval(SWITCH_INTERVAL_S)
        gc.freeze()
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
            return SimClockTicker(self.cm.update_rate, self.node.clock)

        def overrun(text: str) -> None:
            self.log.throttled("overrun", text, 1.0)

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
            run(cm.cycle, self.ticker, self.stop, self.stats, self._on_cycle_time)  # read → update → write
        except Exception as e:  # the loop dying silently would freeze the robot with no word
            self.log.error(f"the control loop stopped: {type(e).__name__}: {e}")
            self.node.request_shutdown()

    # --- process lifetime ------------------------------------------------------------------------------
    def _on_description(self, msg: Any) -> None:
        if self._got_description.is_set():
            self.log.warn("ignoring a second robot_description: the manager was already initialised")
            return
        try:
            self._prepare(str(msg.data), "robot_description topic")
        except ConfigError as e:
            self.log.error(f"robot_description: {e}")
            self.failed = e
            self.node.request_shutdown()
            return
        self._got_description.set()

    def serve(self) -> None:
        """Run until SIGINT/SIGTERM; raises the ConfigError that stopped start-up, if any."""
        import signal

        self.failed: ConfigError | None = None

        def on_signal(*_: object) -> None:
            self.stop.set()
            self.node.request_shutdown()

        for sig in (signal.SIGINT, signal.SIGTERM):
            signal.signal(sig, on_signal)
        try:
            if self.description is None:
                self.node.create_subscription(
                    "robot_description", "std_msgs/msg/String", self._on_description, latched=True
                )
                ticks = 0
                while not self._got_description.wait(0.1) and not self.node.shutting_down:
                    if ticks % 50 == 0:
                        self.log.warn("Waiting for data on 'robot_description' topic to finish initialization")
                    ticks += 1
                if self.failed is not None:
                    raise self.failed
                if self.node.shutting_down:
                    return
            self.start()
            self.node.spin()
        finally:
            self.shutdown()

    def shutdown(self) -> None:
        self.stop.set()
        if self._loop_thread is not None:
            self._loop_thread.join(2.0)
        if self.cm is not None:
            self.cm.loop_running = False
            self.cm.shutdown()
        if self.services is not None:
            self.services.close()
        stats = self.stats.summary(1.0 / self.cm.update_rate) if self.cm is not None else {}
        if stats.get("overruns"):
            self.log.warn(f"{stats['overruns']} overruns in {stats['cycles']} cycles")
        self.node.close()


def main(opts: ManagerOptions) -> None:
    ControlNode(opts).serve()
