"""`diffctl spawn controller`: controller_manager's spawner — load, configure and activate controllers.

Flow per controller (Jazzy tip): list_controllers; load unless already loaded (after setting
`<name>.params_file` and `<name>.type` from --param-file on the manager); configure unless --load-only;
activate with a STRICT switch unless --inactive (one switch for all with --activate-as-group).
--controller-ros-args become `<name>.node_options_args` on the manager (the controller node's remaps and
parameters), -t sets `<name>.type`, -n (deprecated) is the spawner's namespace for a relative -c.
Concurrent spawners of one bus (router endpoints + ROS domain) are serialised by a file lock under
$ROS_HOME/locks; stacks on other routers or domains of the same machine do not wait for each other.
Exit code 0 on success, 1 with the reason on failure. With -u it stays up and, on Ctrl-C/SIGTERM,
deactivates and unloads what it spawned.
"""

from __future__ import annotations

import contextlib
import fcntl
import hashlib
import os
import shlex
import signal
import sys
import threading
import time
from collections.abc import Iterator
from pathlib import Path

import click

from diffctl.control.cm_client import ManagerClient
from diffctl.control.params import section_type
from diffctl.control.switching import STRICT
from diffctl.errors import ParameterError, RuntimeFailure

LOCK_NAME = "ros2-control-controller-spawner.lock"


def bus_scope() -> str:
    """What makes two spawners talk to the same controller managers: the router endpoints their sessions
    connect to and the ROS domain. Spawners of separate stacks never contend for a manager, so they need not
    queue behind each other's lock (upstream's lock is per machine because ROS has no router to scope by)."""
    from diffctl.bus import session

    try:
        endpoints = sorted(session.connect_endpoints(session.peer_config()))
    except Exception:  # an unreadable session config: Node() reports it in one line right after
        endpoints = [session.router_endpoint()]
    return f"{','.join(endpoints)}|domain {os.environ.get('ROS_DOMAIN_ID', '0') or '0'}"


def lock_path(scope: str | None = None) -> Path:
    home = os.environ.get("ROS_HOME") or os.path.join(os.path.expanduser("~"), ".ros")
    if scope is None:
        return Path(home) / "locks" / LOCK_NAME
    digest = hashlib.sha256(scope.encode()).hexdigest()[:16]
    return Path(home) / "locks" / LOCK_NAME.replace(".lock", f"-{digest}.lock")


def _try_lock(fh, wait_s: float) -> bool:
    deadline = time.monotonic() + wait_s
    while True:
        try:
            fcntl.flock(fh, fcntl.LOCK_EX | fcntl.LOCK_NB)
            return True
        except BlockingIOError:
            if time.monotonic() >= deadline:
                return False
            time.sleep(0.01)


@contextlib.contextmanager
def spawner_lock(log, attempts: int = 5, wait_s: float = 20.0, scope: str | None = None) -> Iterator[None]:
    """Serialise spawners of one bus, as controller_manager's spawner does on a machine (5 attempts × 20 s)."""
    path = lock_path(scope)
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path, "a") as fh:
        for k in range(1, attempts + 1):
            if _try_lock(fh, wait_s):
                break
            log.warn(f"Attempt {k} of {attempts}: another spawner holds {path}")
        else:
            raise RuntimeFailure(f"could not take the spawner lock {path} after {attempts} attempts")
        try:
            yield
        finally:
            fcntl.flock(fh, fcntl.LOCK_UN)


def controller_node_options(ros_args_texts: list[str]) -> list[str]:
    """`--controller-ros-args '-r ~/cmd_vel:=/cmd_vel'` (repeatable) → `<ctrl>.node_options_args` words."""
    words: list[str] = []
    for text in ros_args_texts:
        try:
            words += shlex.split(text)
        except ValueError as e:
            raise click.BadParameter(f"cannot split {text!r}: {e}", param_hint="--controller-ros-args") from None
    return words


def spawn(
    names: list[str],
    *,
    param_files: list[str],
    inactive: bool,
    load_only: bool,
    manager: str,
    manager_timeout_s: float,
    switch_timeout_s: float,
    activate_as_group: bool,
    unload_on_kill: bool,
    switch_asap: bool = True,
    call_timeout_s: float = 10.0,
    controller_ros_args: list[str] | None = None,
    controller_type: str | None = None,
    namespace: str | None = None,
) -> bool:
    """The spawner; raises RuntimeFailure (exit 1) with the reason when anything fails. True when it is done
    and may exit at once: every controller reached its state and it was not asked to stay (-u)."""
    from diffctl import ros_args
    from diffctl.client.context import get_default_context
    from diffctl.client.node import Node

    ra = ros_args.current(f"spawner_{names[0]}")
    # `--ros-args --params-file` files count as --param-file (controller_manager 4.44+): a launch file's
    # `parameters=[…]` on the spawner Node reach the controllers this way.
    param_files = [*param_files, *(f for f in ra.params_files if f not in param_files)]
    for f in param_files:
        if not Path(f).is_file():
            raise RuntimeFailure(f"parameter file {f!r} does not exist", hint="--param-file takes an existing YAML")
    spawner_ns = ra.namespace or "/"
    if namespace is not None:
        if ra.namespace not in (None, "/"):
            raise click.UsageError("give the spawner's namespace with -n/--namespace or with -r __ns:=, not both")
        spawner_ns = namespace if namespace.startswith("/") else "/" + namespace
    options = controller_node_options(controller_ros_args or [])
    context = get_default_context()
    if not context.ok():
        context.init(["spawner", "--ros-args", *ros_args.current_argv()])
    node = Node(f"spawner_{names[0]}", namespace=None if namespace is None else spawner_ns, context=context)
    log = node.get_logger()
    types = {}
    for name in names:
        for f in param_files:
            try:
                t = section_type(f, name, node.get_namespace(), log.fatal)
            except ParameterError as e:
                node.destroy_node()
                raise RuntimeFailure(str(e)) from None
            if t:
                types[name] = t
        if controller_type:
            types[name] = controller_type
    if namespace is not None:
        log.warn("the -n/--namespace argument is deprecated; use --ros-args -r __ns:=<namespace>")
    cm = ManagerClient(node, manager, call_timeout_s)
    stop = threading.Event()

    def on_signal(*_: object) -> None:
        stop.set()
        cm.interrupt()  # KeyboardInterrupt now, or where a call in progress can take it

    # SIGINT too (the real spawner handles its signals itself, rclpy.init with SignalHandlerOptions.NO): should
    # its KeyboardInterrupt be lost (raised inside a finalizer, where Python only prints it), the event still
    # ends the wait for --unload-on-kill.
    signal.signal(signal.SIGTERM, on_signal)
    signal.signal(signal.SIGINT, on_signal)
    try:
        with spawner_lock(log, scope=bus_scope()):
            cm.wait("list_controllers", manager_timeout_s, log.info, log.warn)
            for service in ("load_controller", "configure_controller", "switch_controller", "set_parameters"):
                cm.wait(service, manager_timeout_s, None, log.warn)
            known: dict[str, str] = {}  # the states this spawner has seen or made
            for name in names:
                known[name] = _load_and_configure(cm, log, name, types.get(name), param_files, load_only, options)
                if not (load_only or inactive or activate_as_group):
                    _activate(cm, log, [name], switch_timeout_s, switch_asap, known)
            if activate_as_group and not (load_only or inactive):
                _activate(cm, log, names, switch_timeout_s, switch_asap, known)
        if not unload_on_kill:
            return True
        log.info("waiting until interrupted to unload controllers (--unload-on-kill)")
        with contextlib.suppress(KeyboardInterrupt):
            while not stop.wait(0.25):
                pass
        _unload(cm, log, names, deactivate=not (inactive or load_only), switch_timeout_s=switch_timeout_s)
    except KeyboardInterrupt:
        if unload_on_kill:
            _unload(cm, log, names, deactivate=not (inactive or load_only), switch_timeout_s=switch_timeout_s)
        # Interrupted without -u: ROS's spawner exits 0.
    finally:
        cm.close()
        node.destroy_node()
    return False


def _set_node_options(cm: ManagerClient, name: str, options: list[str]) -> None:
    cm.set_parameters({f"{name}.node_options_args": options})


def _load_and_configure(
    cm: ManagerClient,
    log,
    name: str,
    type_name: str | None,
    param_files: list[str],
    load_only: bool,
    options: list[str] | None = None,
) -> str:
    """Load and configure `name` unless it is further already; its state then (as list_controllers says it)."""
    state = cm.controller_state(name)
    if state is not None:
        log.warn(f"Controller already loaded, skipping load_controller ({name} is {state})")
    else:
        if options:
            _set_node_options(cm, name, options)
        if param_files:
            cm.set_controller_params(name, type_name, param_files)
        elif type_name:
            cm.set_parameters({f"{name}.type": type_name})
        if not cm.ok("load_controller", name):
            raise RuntimeFailure(
                f"Failed loading controller {name}",
                hint="the controller manager's log says why (e.g. no '<name>.type' parameter)",
            )
        log.info(f"Loaded {name}")
        state = "unconfigured"
    if load_only:
        return state
    if state == "unconfigured":
        if not cm.ok("configure_controller", name):
            raise RuntimeFailure(f"Failed to configure controller {name}", hint="the controller manager's log says why")
        log.info(f"Configured {name}")
        state = "inactive"
    return state


def _activate(cm: ManagerClient, log, names: list[str], timeout_s: float, asap: bool,
              known: dict[str, str] | None = None) -> None:
    """Activate those of `names` not active yet; `known` states (just seen or made by this spawner) are not asked
    for again (one list_controllers round trip less per spawner)."""
    known = known or {}
    if all(n in known for n in names):
        states = known
    else:
        listed = {str(c.name): str(c.state) for c in cm.list_controllers()}
        states = {n: listed.get(n, "") for n in names}
    todo = [n for n in names if states.get(n) != "active"]
    for n in set(names) - set(todo):
        log.warn(f"Controller {n} is already active")
    if not todo:
        return
    ok, msg = cm.switch(todo, [], STRICT, asap, timeout_s)
    if not ok:
        raise RuntimeFailure(
            f"Failed to activate controller{'s' if len(todo) > 1 else ''} {', '.join(todo)}"
            + (f": {msg}" if msg else "")
        )
    log.info(f"Configured and activated {', '.join(todo)}")


def _unload(cm: ManagerClient, log, names: list[str], *, deactivate: bool, switch_timeout_s: float) -> None:
    cm.interrupt_handled()
    failed = []
    if deactivate:
        ok, msg = cm.switch([], names, STRICT, True, switch_timeout_s)
        if not ok:
            failed.append(f"deactivate: {msg}")
        else:
            log.info(f"Deactivated {', '.join(names)}")
    for n in names:
        if cm.ok("unload_controller", n):
            log.info(f"Unloaded {n}")
        else:
            failed.append(f"unload {n}")
    if failed:
        raise RuntimeFailure("Failed to unload controllers: " + "; ".join(failed))


@click.command("controller", context_settings={"help_option_names": ["-h", "--help"]})
@click.argument("names", nargs=-1, required=True)
@click.option(
    "-p",
    "--param-file",
    "param_files",
    multiple=True,
    metavar="FILE",
    help="Controller parameter file (repeatable); sets <name>.params_file and <name>.type on the manager.",
)
@click.option("--inactive", is_flag=True, help="Load and configure, but do not activate.")
@click.option("--load-only", is_flag=True, help="Only load the controller.")
@click.option(
    "-c",
    "--controller-manager",
    "manager",
    default="controller_manager",
    show_default=True,
    help="Name of the controller manager node.",
)
@click.option(
    "--controller-manager-timeout",
    "manager_timeout",
    type=float,
    default=0.0,
    show_default=True,
    help="Seconds to wait for the manager's services; 0 waits forever (saying so every 10 s).",
)
@click.option(
    "--switch-timeout",
    type=float,
    default=5.0,
    show_default=True,
    help="Seconds the manager may take to carry out the activation.",
)
@click.option(
    "--service-call-timeout",
    type=float,
    default=10.0,
    show_default=True,
    help="Seconds to wait for each service answer (3 attempts).",
)
@click.option("--activate-as-group", is_flag=True, help="Activate all named controllers in one switch.")
@click.option(
    "--switch-asap/--no-switch-asap", default=True, show_default=True, help="Switch in the next control cycle."
)
@click.option(
    "-u", "--unload-on-kill", is_flag=True, help="Stay up; on Ctrl-C/SIGTERM deactivate and unload the controllers."
)
@click.option(
    "--controller-ros-args",
    "controller_ros_args",
    multiple=True,
    metavar="ARGS",
    help="--ros-args for the controller's node, e.g. '-r ~/cmd_vel:=/cmd_vel' (repeatable).",
)
@click.option(
    "-t",
    "--controller-type",
    "controller_type",
    default=None,
    help="The controller's type when no parameter file gives it (older spawners' option).",
)
@click.option(
    "-n", "--namespace", default=None, help="Deprecated: the spawner's namespace (use --ros-args -r __ns:=NS)."
)
def spawn_controller(
    names: tuple[str, ...],
    param_files: tuple[str, ...],
    inactive: bool,
    load_only: bool,
    manager: str,
    manager_timeout: float,
    switch_timeout: float,
    service_call_timeout: float,
    activate_as_group: bool,
    switch_asap: bool,
    unload_on_kill: bool,
    controller_ros_args: tuple[str, ...],
    controller_type: str | None,
    namespace: str | None,
) -> None:
    """Load, configure and activate controllers in a running controller manager (controller_manager spawner).

    Exits 0 when every controller reached the requested state, 1 with the reason otherwise.

    \b
    Example:
      diffctl spawn controller joint_state_broadcaster
      diffctl spawn controller diffbot_base_controller --param-file config/diff_drive_controller.yaml
      diffctl spawn controller a b --activate-as-group --controller-manager-timeout 10
      diffctl spawn controller diff_cont -c my_ctrl_mgr --controller-ros-args '-r ~/cmd_vel:=/cmd_vel'
    """
    if manager_timeout < 0 or switch_timeout < 0 or service_call_timeout <= 0:
        raise click.BadParameter("timeouts must be ≥ 0 (the service call timeout > 0)")
    done = spawn(
        list(names),
        param_files=list(param_files),
        inactive=inactive,
        load_only=load_only,
        manager=manager,
        manager_timeout_s=manager_timeout,
        switch_timeout_s=switch_timeout,
        activate_as_group=activate_as_group,
        unload_on_kill=unload_on_kill,
        switch_asap=switch_asap,
        call_timeout_s=service_call_timeout,
        controller_ros_args=list(controller_ros_args),
        controller_type=controller_type,
        namespace=namespace,
    )
    if done and _is_program():
        _exit_now()


def _is_program() -> bool:
    """Whether this process is `python -m diffctl …` (not a test or a tool calling the command in-process)."""
    spec = getattr(sys.modules.get("__main__"), "__spec__", None)
    return spec is not None and spec.name == "diffctl.__main__"


def _exit_now() -> None:
    """Exit 0 without Zenoh's orderly close and the interpreter's teardown (together 60-150 ms with the
    stack's peers, on the launch's critical path: the tutorial starts the next spawner on this one's exit).
    Nothing is lost: the controllers are active, the node's endpoints were undeclared by node.close(), and
    the peers drop this session when its links close with the process."""
    for stream in (sys.stdout, sys.stderr):
        with contextlib.suppress(Exception):
            stream.flush()
    os._exit(0)
