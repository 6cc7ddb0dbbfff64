"""The gz_ros2_control system plugin: a controller manager hosted inside the simulator for one model.

As gz_ros2_control does (reference ros2_control.md §4, workspace_urdf.md §5): when a model whose description
carries `<plugin filename="gz_ros2_control-system" name="gz_ros2_control::GazeboSimROS2ControlPlugin">` is
spawned, the simulator builds a controller manager named `<controller_manager_name>` (default
controller_manager) in `<ros><namespace>`, whose node arguments are gz_ros2_control's (`--ros-args`, a
`--params-file` per `<parameters>` file, later ones overriding, and a `-r` per `<ros><remapping>`; its
controllers inherit them), `use_sim_time` forced on, and a GazeboSimSystem hardware bound to the model's joints
for every `<ros2_control>` block that asks for it. The managers' and controllers' client Nodes are spun by one
multi-threaded executor of the simulator process.
Every 1/update_rate of sim time the physics loop calls read → update → write synchronously on the sim thread,
so results do not depend on machine speed and no message crosses a process boundary. The manager serves the
same `/controller_manager/*` services as `diffctl control manager`. A controller that raises is deactivated
and reported by the manager; the simulation goes on. While the world is paused, no cycle runs (a pending
switch waits, as in Gazebo).
"""

from __future__ import annotations

import shlex
import threading
from dataclasses import dataclass
from typing import Any

from lxml import etree

from diffctl.control.controller_node import ManagerTime, make_controller_node, spin_resiliently
from diffctl.control.hardware_interface import HardwareInfo
from diffctl.control.manager import ControllerManager
from diffctl.control.manager_node import make_manager_node, manager_flat_params
from diffctl.control.params import manager_params
from diffctl.control.robot_hardware import PLACEHOLDER, infos_from_blocks
from diffctl.control.services import ManagerServices
from diffctl.description.model import Model, Plugin
from diffctl.errors import ConfigError, DescriptionError
from diffctl.sim.entity import Entity
from diffctl.sim.plugins.base import PluginContext, SystemPlugin, bool_param, float_param
from diffctl.sim.plugins.gazebo_sim_system import PLUGIN_ALIASES, GazeboSimSystem


@dataclass(frozen=True)
class GzRos2ControlParams:
    """The plugin's own elements."""

    parameters: tuple[str, ...]  # parameter files of the manager and its controllers, in order
    namespace: str
    remappings: tuple[tuple[str, str], ...]
    controller_manager_name: str
    hold_joints: bool
    position_proportional_gain: float

    @staticmethod
    def from_plugin(plugin: Plugin, source: str) -> GzRos2ControlParams:
        where = f"plugin {plugin.filename}"
        files = tuple(f.strip() for f in plugin.get_all("parameters"))
        if not files or any(not f for f in files):
            raise DescriptionError(
                "the gz_ros2_control plugin needs a <parameters> file (found an empty or missing one)",
                source=source or None,
                field=f"{where}: parameters",
                hint="<parameters>$(find my_pkg)/config/controllers.yaml</parameters>",
            )
        for f in files:
            if f == PLACEHOLDER:
                raise DescriptionError(
                    f"the gz_ros2_control <parameters> is still {PLACEHOLDER}",
                    source=source or None,
                    field=f"{where}: parameters",
                    hint="the launch file replaces it with the controller YAML's path before the model is spawned",
                )
        namespace, remaps = _ros_element(plugin, source)
        name = (plugin.get("controller_manager_name") or "controller_manager").strip()
        return GzRos2ControlParams(
            parameters=files,
            namespace=namespace,
            remappings=remaps,
            controller_manager_name=name,
            hold_joints=bool_param(plugin, "hold_joints", True, source=source),
            position_proportional_gain=float_param(plugin, "position_proportional_gain", 0.1, source=source) or 0.1,
        )


def _ros_element(plugin: Plugin, source: str) -> tuple[str, tuple[tuple[str, str], ...]]:
    """`<ros><namespace>` and `<ros><remapping>from:=to</remapping>` (also `--ros-args -r from:=to`)."""
    if not plugin.xml:
        return "/", ()
    root = etree.fromstring(plugin.xml.encode())
    namespace = "/"
    remaps: list[tuple[str, str]] = []
    for ros in root.findall("ros"):
        ns = ros.findtext("namespace")
        if ns and ns.strip():
            namespace = "/" + ns.strip().strip("/")
        for r in ros.findall("remapping"):
            words = [w for w in shlex.split(r.text or "") if w not in ("--ros-args", "-r", "--remap")]
            for w in words:
                src, sep, dst = w.partition(":=")
                if not sep or not src or not dst:
                    raise DescriptionError(
                        f"<remapping> {r.text!r} is not from:=to",
                        source=source or None,
                        field=f"plugin {plugin.filename}: ros/remapping",
                        hint="e.g. <remapping>/diff_drive_controller/cmd_vel:=/cmd_vel</remapping>",
                    )
                remaps.append((src, dst))
    return namespace, tuple(remaps)


def wants_controller_manager(model: Model) -> list[Plugin]:
    return [p for p in model.plugins if p.system == "gz_ros2_control"]


def warn_skipped(ctx: PluginContext, model_name: str, blocks: list[Any]) -> None:
    for b in blocks:
        asks = f"asks for {b.hardware_plugin}" if b.hardware_plugin else "names no <hardware> plugin"
        ctx.log.warn(
            f"model {model_name!r}: <ros2_control name={b.name!r}> {asks}; inside the "
            f"simulator only {PLUGIN_ALIASES[0]} exists (as with gz_ros2_control): block skipped"
        )


class PreparedManager:
    """A model's controller manager before its model is in the physics: parameters, node and manager, built
    off the sim thread (a `create` request's thread), so the simulation loop does not stop while a node comes
    up. `GzRos2Control` adopts it and adds what needs the model (hardware, services, the control task);
    `close` releases one that was never adopted (the spawn failed first)."""

    def __init__(self, ctx: PluginContext, model: Model, plugin: Plugin, description: str = "") -> None:

        self.plugin = plugin
        self.adopted = False
        source = model.source or ""
        self.params = GzRos2ControlParams.from_plugin(plugin, source)
        blocks = [b for b in model.ros2_control if b.hardware_plugin in PLUGIN_ALIASES]
        self.skipped = [b for b in model.ros2_control if b.hardware_plugin not in PLUGIN_ALIASES]
        if not blocks:
            warn_skipped(ctx, model.name, self.skipped)
            raise DescriptionError(
                f"model {model.name!r} has the gz_ros2_control plugin but no <ros2_control> block with "
                f"{PLUGIN_ALIASES[0]} hardware",
                source=source or None,
                field=f"plugin {plugin.filename}",
            )
        self.infos = infos_from_blocks(blocks, source or None)
        name = self.params.controller_manager_name
        arguments = ["--ros-args", *(w for f in self.params.parameters for w in ("--params-file", f))]
        if self.params.remappings:
            arguments += ["--ros-args", *(w for src, dst in self.params.remappings for w in ("-r", f"{src}:={dst}"))]
        self.stop = threading.Event()
        self.node: Any = None
        self.cm: ControllerManager | None = None
        if ctx.transport is None:
            raise ConfigError("the gz_ros2_control plugin needs the bus (the simulator runs without one)")
        from diffctl.client.parameter import Parameter

        context, self.executor = hosted_executor()
        # Its own arguments only: the simulator process's (`-r __node:=gz_sim` from a launch file) are not its.
        try:
            self.node = make_manager_node(name, self.params.namespace or "/", arguments, context=context,
                                          use_global_arguments=False)
        except Exception:
            release_hosted()
            raise
        self.time = ManagerTime()
        try:
            self.node.set_parameters([Parameter("use_sim_time", Parameter.Type.BOOL, True)])
            self.time.follow(self.node)
            self.time.set_ns(ctx.stepper.sim_time_ns)
            flat = {**manager_flat_params(self.node), "use_sim_time": True}
            cm_params = manager_params(flat, source=f"{name} parameters", node_arguments=arguments)
            namespace = self.node.get_namespace()

            def controller_node(cname: str, node_arguments: list[str]) -> Any:
                node = make_controller_node(cname, namespace, node_arguments, context=context)
                self.time.follow(node)
                self.time.set_ns(ctx.stepper.sim_time_ns)
                return node

            self.cm = ControllerManager(
                cm_params,
                log=self.node.get_logger(),
                node_factory=controller_node,
                robot_description=description,
                cancel=self.stop,
                executor=self.executor,
            )
            self.cm.on_node_released = self.time.forget
        except Exception:
            self.close()
            raise

    def close(self) -> None:
        """Release a manager that no model adopted."""
        if self.adopted:
            return
        self.stop.set()
        if self.node is not None:
            self.node.destroy_node()
            self.node = None
            release_hosted()
        self.cm = None


@dataclass
class _Hosted:
    context: Any
    executor: Any
    thread: threading.Thread
    owns_context: bool  # made ready here: shut down with the last manager
    stop: threading.Event
    users: int = 0


_hosted: _Hosted | None = None
_hosted_lock = threading.Lock()


def hosted_executor() -> tuple[Any, Any]:
    """(context, executor) of the simulator process's controller managers: the default client context (made
    ready with the process's ROS arguments if nobody did, without signal handlers: the simulator has its own)
    and one multi-threaded executor spinning their nodes in a daemon thread, as gz_ros2_control's. Made anew
    when the previous one stopped (its session closed); each caller calls `release_hosted` once done."""
    global _hosted
    with _hosted_lock:
        if _hosted is None or not _hosted.thread.is_alive():
            import sys

            from diffctl import ros_args
            from diffctl.client.context import get_default_context
            from diffctl.client.executors import MultiThreadedExecutor
            from diffctl.client.ros_logging import get_logger

            context = get_default_context()
            owns = not context.ok()
            if owns:
                context.init([sys.argv[0], "--ros-args", *ros_args.current_argv()])
            executor = MultiThreadedExecutor(num_threads=2, context=context)
            log = get_logger("gz_ros2_control")
            stop = threading.Event()

            def spin() -> None:
                spin_resiliently(executor, lambda: context.ok() and not stop.is_set(), log)

            thread = threading.Thread(target=spin, name="gz_ros2_control_executor", daemon=True)
            thread.start()
            _hosted = _Hosted(context, executor, thread, owns, stop)
        _hosted.users += 1
        return _hosted.context, _hosted.executor


def release_hosted() -> None:
    """One user of `hosted_executor` is done; the last one stops the executor (and the context it made)."""
    global _hosted
    with _hosted_lock:
        h = _hosted
        if h is None:
            return
        h.users -= 1
        if h.users > 0:
            return
        _hosted = None
    h.stop.set()
    h.executor.shutdown(timeout_sec=1.0)
    h.thread.join(1.0)
    if h.owns_context:
        from diffctl.client import runtime
        from diffctl.client.context import get_default_context

        if get_default_context() is h.context:
            runtime.try_shutdown()  # hands the default context over: a later init makes a fresh one
        else:
            h.context.try_shutdown()


class GzRos2Control(SystemPlugin):
    """One model's controller manager, stepped by the simulator."""

    def __init__(
        self,
        ctx: PluginContext,
        entity: Entity,
        plugin: Plugin,
        description: str = "",
        prepared: PreparedManager | None = None,
    ) -> None:
        self.ctx, self.entity = ctx, entity
        self.systems: list[GazeboSimSystem] = []
        self.node: Any = None
        self.cm: ControllerManager | None = None
        self.services: ManagerServices | None = None
        self._task = None
        self._last_ns: int | None = None
        self._hooked = False  # _each_step in the stepper's step hooks: only while a system steps (see _cycle)
        self.stop = threading.Event()
        if prepared is None or prepared.plugin is not plugin:
            if prepared is not None:
                prepared.close()
            prepared = PreparedManager(ctx, entity.model, plugin, description)
        prepared.adopted = True
        self.params, self.infos, self.stop = prepared.params, prepared.infos, prepared.stop
        self.node, self.cm, self.executor = prepared.node, prepared.cm, prepared.executor
        self.time = prepared.time
        warn_skipped(ctx, entity.name, prepared.skipped)
        try:
            assert self.cm is not None
            self.cm.load_hardware(self.infos, self._hardware)
            self.services = ManagerServices(self.node, self.cm)
            self.executor.add_node(self.node)
            self.cm.loop_running = True
            self._start_loop()
        except Exception:
            self.close()
            raise
        ctx.log.info(
            f"controller manager {self.node.get_fully_qualified_name()} for model {entity.name!r}: "
            f"{self.cm.update_rate} Hz of sim time, "
            f"hardware [{', '.join(f'{i.name} ({i.plugin_name})' for i in self.infos)}]"
        )

    def _hardware(self, info: HardwareInfo) -> GazeboSimSystem:
        hw = GazeboSimSystem().bind(
            self.entity,
            hold_joints=self.params.hold_joints,
            position_proportional_gain=self.params.position_proportional_gain,
        )
        self.systems.append(hw)
        return hw

    def _start_loop(self) -> None:
        assert self.cm is not None
        step_ns = self.ctx.stepper.step_ns
        wanted_ns = round(1e9 / self.cm.update_rate)
        if wanted_ns < step_ns:
            self.ctx.log.warn(
                f"controller manager update_rate {self.cm.update_rate} Hz is faster than the physics step "
                f"({step_ns * 1e-6:g} ms): it runs once per step"
            )
        self.period_ns = max(step_ns, wanted_ns)
        self._task = self.ctx.stepper.add_task(f"controller_manager:{self.entity.name}", self.period_ns, self._cycle)

    def _cycle(self, sim_time_ns: int) -> None:
        cm = self.cm
        if cm is None:
            return
        period_s = self.period_ns * 1e-9 if self._last_ns is None else (sim_time_ns - self._last_ns) * 1e-9
        if period_s <= 0:  # the world was reset: time went back
            period_s = self.period_ns * 1e-9
        self._last_ns = sim_time_ns
        self.time.set_ns(sim_time_ns)
        try:
            cm.cycle(sim_time_ns, period_s)  # read → update → write under one lock, as the real-time loop
        except Exception as e:  # the simulation goes on; the manager already deactivated what it could
            self.ctx.log.throttled(
                f"cm:{self.entity.name}", f"controller manager of {self.entity.name!r}: {type(e).__name__}: {e}"
            )
        # A velocity-commanded robot (a wheel) has nothing to do between cycles: the per-step hook is in the
        # stepper's list only while a position or effort command needs the physics' every step.
        stepping = any(hw.steps for hw in self.systems)
        if stepping != self._hooked:
            hooks = self.ctx.stepper.step_hooks
            if stepping:
                hooks.append(self._each_step)
            elif self._each_step in hooks:
                hooks.remove(self._each_step)
            self._hooked = stepping

    def _each_step(self) -> None:
        for hw in self.systems:
            hw.step()

    def reset(self) -> None:
        self._last_ns = None
        for hw in self.systems:
            hw.reset_initial_states()

    def close(self) -> None:
        self.stop.set()
        if self._task is not None:
            self.ctx.stepper.remove_task(self._task)
            self._task = None
        if self._each_step in self.ctx.stepper.step_hooks:
            self.ctx.stepper.step_hooks.remove(self._each_step)
        if self.cm is not None:
            self.cm.loop_running = False
            try:
                self.cm.shutdown()
            except Exception as e:
                self.ctx.log.warn(f"controller manager of {self.entity.name!r} did not shut down cleanly: {e}")
        if self.services is not None:
            self.services.close()
            self.services = None
        if self.node is not None:
            self.executor.remove_node(self.node)
            self.node.destroy_node()
            self.node = None
            release_hosted()
        self.cm = None
