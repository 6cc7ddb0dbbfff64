"""`diffctl launch`: run a launch file on diffctl's launch (ros2/launch's API), supervised (ros2 launch).

The command does what ros2launch does — find the file, include it with the `name:=value` arguments in a
LaunchService, or describe it (`--print`: the introspector's text; `--show-args`: its arguments), running no
user code beyond loading the file — and adds diffctl's launcher: an embedded Zenoh router, the fork server
for diffctl's own components, a guard so nothing outlives the launcher, bus probes for `wait_for`, a status
table on Enter or SIGUSR1, and its exit code policy (launch_outcome.py). Bad input (an unknown file, tag or
argument) is one message and exit 2 before anything starts; an error while the launch runs (a custom action
that raises, a substitution that fails) stops everything and exits 2 as well.
"""

from __future__ import annotations

import gc
import os
import re
import signal
import sys
import time
import traceback
from pathlib import Path
from typing import TYPE_CHECKING, Any

import click

from diffctl.errors import DiffctlError, LaunchError, suggest
from diffctl.source_paths import user_source

if TYPE_CHECKING:
    import asyncio


def _split_targets(targets: tuple[str, ...]) -> tuple[list[str], dict[str, str]]:
    positional = [t for t in targets if ":=" not in t]
    arguments: dict[str, str] = {}
    for t in targets:
        if ":=" in t:
            name, value = t.split(":=", 1)
            if not name:
                raise LaunchError(f"launch argument {t!r} has no name", hint="write NAME:=VALUE")
            arguments[name] = value  # the last one wins, as in ros2 launch
    if not 1 <= len(positional) <= 2:
        raise click.UsageError("give a launch file: NAME, PATH, or PACKAGE FILE, then any NAME:=VALUE arguments")
    return positional, arguments


@click.command("launch")
@click.argument("target", nargs=-1, required=True, metavar="NAME|PATH [PACKAGE FILE] [ARG:=VALUE ...]")
@click.option("-s", "--show-args", is_flag=True, help="List the launch file's arguments and exit.")
@click.option(
    "-p",
    "--print",
    "print_description",
    is_flag=True,
    help="Print the launch description (its entities, as ros2 launch --print) without running it.",
)
@click.option(
    "--log-dir",
    type=click.Path(file_okay=False, path_type=Path),
    help="Directory for this run's logs (default: ~/.ros/log/<time>-<host>-<pid>).",
)
@click.option("--no-color", is_flag=True, help="No colours in the output.")
@click.option(
    "--output-default",
    type=click.Choice(["screen", "log"]),
    default="screen",
    help="The output of processes that give none: screen (diffctl) or log (ros2 launch: stdout to launch.log only).",
)
@click.option(
    "--exit-code",
    "exit_code_mode",
    type=click.Choice(["diffctl", "ros"]),
    default="diffctl",
    help="diffctl: 1 when a required process or readiness failed; ros: 1 only on an error in the launch itself.",
)
@click.option(
    "--signal",
    "signal_scope",
    type=click.Choice(["group", "process"]),
    default="group",
    help="Stop signals to each process's whole group (diffctl) or the process alone (ros2 launch).",
)
@click.option(
    "--process-names",
    type=click.Choice(["diffctl", "ros"]),
    default="diffctl",
    help="Process labels: the name (a Node's: its node name), name-2 for a second one (diffctl); or ros2 "
    "launch's name-N, N from one counter (ros).",
)
@click.option("--no-router", is_flag=True, help="Do not start the embedded Zenoh router.")
@click.option(
    "--workspace",
    "workspace_dir",
    type=click.Path(file_okay=False, path_type=Path),
    default=None,
    help="The ROS workspace whose packages to use (default: $DIFFCTL_WORKSPACE, else the enclosing one).",
)
@click.option("-d", "--debug", is_flag=True, help="Put the launch in debug mode (more output, as ros2 launch -d).")
def launch(
    target: tuple[str, ...],
    show_args: bool,
    print_description: bool,
    log_dir: Path | None,
    no_color: bool,
    output_default: str,
    exit_code_mode: str,
    signal_scope: str,
    process_names: str,
    no_router: bool,
    workspace_dir: Path | None,
    debug: bool,
) -> None:
    """Start a launch file and supervise its processes (ros2 launch).

    NAME is launch/NAME.yaml or launch/NAME.launch.py of the project (YAML first); PATH is any YAML, XML or
    Python launch file; PACKAGE FILE looks in that package's share directory (the packages of the workspace
    enclosing the current directory, or --workspace, come first; `diffctl pkg list` shows them all). Every
    process gets its own process group and dies with the launcher; Ctrl-C stops them all (SIGINT, then
    SIGTERM, then SIGKILL), a second Ctrl-C kills at once. Press Enter (or send SIGUSR1) for a status table.

    \b
    Example:
      diffctl launch sim_control
      diffctl launch sim_control use_sim_time:=false --print
      diffctl launch diffctl_demo sim_control.launch.py
      diffctl launch ./my_robot.yaml --show-args
    """
    # Status requests and hang-ups reach the launcher's signal manager once the launch runs (_LauncherSignals);
    # until then a status request kills nothing.
    signal.signal(signal.SIGUSR1, _no_op)
    from diffctl.cli.deferred_ssl import defer_ssl

    defer_ssl()  # before anything imports asyncio
    positional, arguments = _split_targets(target)
    from diffctl.cli import launch_start

    # The fork server starts before the launcher imports the launch core: its imports run while the launcher's
    # own do and the launch file is read (the first component waits for them). The entry point started it
    # already, unless the command line was one it could not read alone.
    early = None if show_args or print_description else launch_start.take_early(workspace_dir, log_dir)
    if early is not None:
        workspace, run_dir, server = early
    else:
        workspace = launch_start.prepare_environment(workspace_dir)
        describing = show_args or print_description
        run_dir = None if describing else (log_dir or launch_start.default_log_dir())
        server = None if run_dir is None else launch_start.start_fork_server(run_dir)
    try:
        if run_dir is not None:
            _use_log_dir(run_dir, latest=log_dir is None)
        _use_diffctls_launch()
        _import_workspace_python(workspace)
        from diffctl.workspace import package_index

        path = package_index.find_launch_file(*positional)
        description = _load(path)
        if show_args:
            from diffctl.cli.show_args import arguments_text

            print(arguments_text(description.get_launch_arguments()), end="")
            return
        if print_description:
            from diffctl.launch import LaunchIntrospector

            print(LaunchIntrospector().format_launch_description(description))
            return
        _check_arguments(description, arguments, path)
    except BaseException as e:
        if server is not None:
            server.close(kill=True)
        if exit_code_mode == "ros" and isinstance(e, LaunchError):
            e.exit_code = 1  # ros2 launch: "Caught exception in launch", rc 1
        raise
    assert run_dir is not None
    # SystemExit, not ctx.exit: the entry point runs click with standalone_mode=False, which drops exit codes.
    raise SystemExit(
        _run(
            path,
            description,
            arguments,
            run_dir,
            server=server,
            no_color=no_color,
            no_router=no_router,
            debug=debug,
            policy={
                "output_default": output_default,
                "exit_code_mode": exit_code_mode,
                "signal_scope": signal_scope,
                "process_names": process_names,
            },
        )
    )


# ---- before anything starts ------------------------------------------------------------------------------------


def _use_diffctls_launch() -> None:
    """Launch files loaded here import diffctl's launch, launch_xml, launch_yaml and launch_ros under ROS's
    names, also where a sourced ROS 2 comes first on PYTHONPATH: the launcher runs its own engine (the
    processes it starts still get the sourced ROS first)."""
    from diffctl.module_alias import alias

    for name in ("launch", "launch_xml", "launch_yaml", "launch_ros"):
        alias(name, f"diffctl.{name}")


def _import_workspace_python(workspace: Path | None) -> None:
    """The workspace's Python packages importable by launch files, after diffctl's overlay (as a sourced
    workspace's site-packages come after the overlay's .pth)."""
    if workspace is None:
        return
    from diffctl.workspace import workspace_python_path

    for folder in workspace_python_path(workspace):
        if str(folder) not in sys.path:
            sys.path.append(str(folder))


def _use_log_dir(run_dir: Path, *, latest: bool) -> None:
    """launch's log files (launch.log, one per process) go to `run_dir`, with a `latest` link beside it when
    diffctl chose the directory (as ros2 launch makes one). Set before anything logs: loading a launch file
    already opens launch.log."""
    from diffctl.launch import logging as launch_logging

    try:
        run_dir.mkdir(parents=True, exist_ok=True)
    except OSError as e:
        raise LaunchError(
            f"cannot create the log directory {run_dir}: {e.strerror}", hint="pass --log-dir DIR"
        ) from None
    launch_logging.launch_config.log_dir = str(run_dir)
    if latest:
        link = run_dir.parent / "latest"
        try:
            if link.is_symlink() or link.exists():
                link.unlink()
            link.symlink_to(run_dir.name)
        except OSError:
            pass  # a shared log folder where another run holds the link: only the link is lost


def _load(path: Path) -> Any:
    """The file's LaunchDescription, by the frontend its name calls for; errors are one line naming the file
    and line (what the frontend of the file's kind raised, not what the other frontends made of it)."""
    from diffctl.launch.invalid_launch_file_error import InvalidLaunchFileError
    from diffctl.launch.launch_description_sources import get_launch_description_from_any_launch_file

    try:
        return get_launch_description_from_any_launch_file(str(path))
    except InvalidLaunchFileError as e:
        cause = e.__cause__ if e.__cause__ is not None else e
        raise _with_hint(_located(cause, path)) from None
    except Exception as e:
        raise _with_hint(_located(e, path)) from None


def _with_hint(e: DiffctlError) -> DiffctlError:
    """What would be valid: the tags or substitutions the frontends and extensions installed know, for one they
    do not; the tag diffctl's older `wait_for` form (a list inside the gated action) is now."""
    if e.hint is not None:
        return e
    text = str(e)
    if re.search(r"Unexpected \w+\(s\) found in .*'wait_(for|timeout)'", text):
        e.hint = "wait_for is a tag wrapping what it gates: `- wait_for: {exited: NAME, children: [ACTIONS]}`"
        return e
    unknown = re.search(r"(Unrecognized entity of the type|Unknown substitution): (\S+)", text)
    if unknown:
        from diffctl.launch.frontend import expose

        tag = unknown.group(1).startswith("Unrecognized")
        known = sorted(expose.action_parse_methods if tag else expose.substitution_parse_methods)
        close = suggest(unknown.group(2), known).strip(" ()")
        e.hint = (f"{close} " if close else "") + ("tags" if tag else "substitutions") + " known: " + ", ".join(known)
    return e


def _located(e: BaseException, path: Path) -> DiffctlError:
    """A DiffctlError naming where: the markup frontend's location of the failing tag, else the file's line."""
    if isinstance(e, DiffctlError):
        if e.source is None:
            where = getattr(e, "launch_location", None)
            file, _, line = str(where).rpartition(":") if where else ("", "", "")
            if file and line.isdigit():
                e.source, e.line = file, int(line)
            else:
                e.source, e.line = str(path), _line_in(e, path)
        return e
    error = LaunchError(_one_line(e, path))
    if isinstance(e, ModuleNotFoundError) and e.name:
        from diffctl.workspace.ros_programs import missing_module_hint

        error.hint = missing_module_hint(e.name)
    return error


def _line_in(e: BaseException, path: Path) -> int | None:
    """The line of `path` (a Python launch file) where `e` was raised, innermost first."""
    line = None
    for frame in traceback.extract_tb(e.__traceback__):
        if os.path.realpath(frame.filename) == os.path.realpath(path):
            line = frame.lineno
    if isinstance(e, SyntaxError) and e.lineno is not None:
        line = e.lineno
    return line


def _one_line(e: BaseException, path: Path) -> str:
    """`FILE:LINE: what`: the file's line where Python raised, when the error is not located already."""
    text = " ".join(str(e).split()) or type(e).__name__
    if str(path) in text:
        return text
    where = getattr(e, "launch_location", None)  # a markup file's failing tag, noted while parsing it
    if not where:
        line = _line_in(e, path)
        shown = user_source(str(path))  # the file under src/, not its link in diffctl's workspace cache
        where = f"{shown}:{line}" if line is not None else shown
    return f"{where}: {type(e).__name__}: {text}" if not isinstance(e, DiffctlError) else f"{where}: {text}"


def _check_arguments(description: Any, arguments: dict[str, str], path: Path) -> None:
    """What ros2 launch finds only once it has started things: a missing required argument, a value not among
    its choices. Also warns of an argument the file does not declare."""
    declared = {a.name: a for a in description.get_launch_arguments()}
    for name in arguments:
        if name not in declared:
            from diffctl.console import warn  # rich, only for the warning

            warn(f"argument {name!r} is not declared by {path.name}{suggest(name, list(declared))}")
    missing = [
        a.name
        for a in declared.values()
        if a.default_value is None and a.name not in arguments and not getattr(a, "_conditionally_included", False)
    ]
    if missing:
        raise LaunchError(
            f"missing required launch argument{'s' if len(missing) > 1 else ''} " + ", ".join(repr(m) for m in missing),
            source=str(path),
            hint="its arguments: " + ", ".join(declared) + f" (see `diffctl launch {path} --show-args`)",
        )
    for name, value in arguments.items():
        choices = getattr(declared.get(name), "choices", None)
        if choices and value not in choices:
            raise LaunchError(
                f"argument {name!r} is {value!r}, not one of its choices",
                source=str(path),
                hint="valid: " + ", ".join(choices),
            )


# ---- the run ---------------------------------------------------------------------------------------------------


def _run(
    path: Path,
    description: Any,
    arguments: dict[str, str],
    run_dir: Path,
    *,
    server: Any,
    no_color: bool,
    no_router: bool,
    debug: bool,
    policy: dict[str, str],
) -> int:
    from diffctl.cli.launch_outcome import LaunchOutcome
    from diffctl.cli.launch_status import ProcessLogFiles, ProcessTable
    from diffctl.launch import LaunchDescription, LaunchService
    from diffctl.launch.actions import IncludeLaunchDescription
    from diffctl.launch.event_handlers import OnShutdown
    from diffctl.launch.launch_description_source import LaunchDescriptionSource
    from diffctl.launch_extensions import process_watch, readiness
    from diffctl.supervision.launcher_spawner import LauncherSpawner

    probes = _LazyBusProbes()
    router = None
    files = None
    from diffctl.launch import logging as launch_logging

    spawner = LauncherSpawner(
        fork_server=server, signal_scope=policy["signal_scope"], logger=launch_logging.get_logger("launch")
    )
    try:
        service = LaunchService(
            argv=[f"{k}:={v}" for k, v in arguments.items()],
            noninteractive=not sys.stdin.isatty(),
            debug=debug,
            spawner=spawner,
            output_default=policy["output_default"],
            process_label=DiffctlLabels() if policy["process_names"] == "diffctl" else None,
            shutdown_on_sigterm=True,
        )
        context = service.context
        outcome, processes, files = LaunchOutcome(), ProcessTable(), ProcessLogFiles(str(run_dir))
        observers: list[Any] = [outcome, processes, files]
        for observer in observers:
            context.register_event_handler(observer, append=True)
        process_watch.install(context)
        context.register_event_handler(OnShutdown(on_shutdown=lambda event, context: spawner.launch_ending()))
        readiness.provide_probes(context, {"topic": probes.topic_has_publisher, "service": probes.service_available})
        service.include_launch_description(
            LaunchDescription(
                [
                    IncludeLaunchDescription(
                        LaunchDescriptionSource(description, str(path)), launch_arguments=list(arguments.items())
                    ),
                ]
            )
        )
        router = None if no_router else _ensure_router()
        # What is loaded by now lives until the launcher exits: kept out of the collector, the exit after a
        # Ctrl-C does not walk it all again in the interpreter's final collection. Frozen without a full
        # collection first (20-30 ms before the first process starts, for the few cycles the imports left).
        gc.freeze()
        with _LauncherSignals(service, processes, no_color=no_color) as signals:
            processes.began_at = time.monotonic()
            code = service.run()
        return _exit_code(code, outcome, context, policy["exit_code_mode"], run_dir, signals.stopped_by)
    finally:
        spawner.close()  # the fork server and the guard, also when the run never began
        probes.close()
        if files is not None:
            files.close()
        if router is not None:
            router.close()


def _exit_code(code: int, outcome: Any, context: Any, mode: str, run_dir: Path, stopped_by: str | None) -> int:
    """ros: what the LaunchService returned. diffctl: 1 for a failed required process or readiness condition
    or (the launch having ended by itself) a failed process, 2 for an error in the launch (bad input); a
    launch stopped by a signal that nothing else failed exits 0."""
    from diffctl.launch import logging as launch_logging
    from diffctl.launch_extensions.readiness import FAILED_KEY

    logger = launch_logging.get_logger("launch")
    logger.info(f"logs: {run_dir}")
    if mode == "ros":
        return code
    failures = outcome.failures()
    readiness = context.get_locals_as_dict().get(FAILED_KEY)
    if readiness:
        failures.append(str(readiness))
    if failures:
        logger.error("launch failed: " + "; ".join(failures))
        return 1
    if code != 0 and stopped_by == "SIGTERM" and outcome.shutdown_reason is None:
        return 0  # canceled by SIGTERM, as a service manager stops it: not an error in the launch
    return 2 if code != 0 else 0


class DiffctlLabels:
    """`--process-names diffctl`: a process is labelled by its name (a Node given a node name: that name,
    without its namespace), the second of a name `name-2`, the third `name-3`, …"""

    def __init__(self) -> None:
        self.taken: set[str] = set()

    def __call__(self, action: Any, name: str) -> str:
        from diffctl.launch_ros.actions import Node

        if isinstance(action, Node):
            node = action.node_name.rsplit("/", 1)[-1]
            if node != Node.UNSPECIFIED_NODE_NAME:
                name = node
        label, n = name, 2
        while label in self.taken:
            label, n = f"{name}-{n}", n + 1
        self.taken.add(label)
        return label


def _no_op(signum: int, frame: Any) -> None:
    """A Python-level handler: the signal then reaches the signal managers' wakeup fd, and kills nothing."""


class _LauncherSignals:
    """The launcher's own signals, heard on the launch's loop beside the LaunchService's (whose signal manager
    passes every signal on to this one, the outer): Enter and SIGUSR1 print the status table; SIGHUP shuts the
    launch down as Ctrl-C does; a second Ctrl-C SIGKILLs every process group at once (the LaunchService
    ignores it); SIGTERM (which the LaunchService, told to, shuts down in order) is remembered, for the exit
    code."""

    def __init__(self, service: Any, processes: Any, *, no_color: bool) -> None:
        import asyncio

        from diffctl.launch.utilities.signal_management import AsyncSafeSignalManager

        self.service = service
        self.processes = processes
        self.no_color = no_color
        self.loop = asyncio.new_event_loop()
        asyncio.set_event_loop(self.loop)  # the loop LaunchService.run() takes
        self.manager = AsyncSafeSignalManager(self.loop)
        self.interrupts = 0
        self.stopped_by: str | None = None
        self._stdin: int | None = None
        self._pending: list[asyncio.Future[Any]] = []

    def __enter__(self) -> _LauncherSignals:
        for signum in (signal.SIGUSR1, signal.SIGHUP):
            signal.signal(signum, _no_op)
        self.manager.__enter__()
        self.manager.handle(signal.SIGUSR1, lambda signum: self._show())
        self.manager.handle(signal.SIGHUP, self._hangup)
        self.manager.handle(signal.SIGTERM, self._terminate)
        self.manager.handle(signal.SIGINT, self._interrupt)
        if sys.stdin is not None and sys.stdin.isatty():
            self._stdin = sys.stdin.fileno()
            self.loop.add_reader(self._stdin, self._on_stdin)
        return self

    def __exit__(self, *exc: Any) -> None:
        if self._stdin is not None:
            self.loop.remove_reader(self._stdin)
        self.manager.__exit__(*exc)
        signal.signal(signal.SIGHUP, signal.SIG_DFL)

    def _show(self) -> None:
        from diffctl.cli.launch_status import show

        show(self.processes, no_color=self.no_color)

    def _on_stdin(self) -> None:
        assert self._stdin is not None
        try:
            data = os.read(self._stdin, 4096)
        except OSError:
            data = b""
        if not data:
            self.loop.remove_reader(self._stdin)  # end of input: nothing more to listen to
            self._stdin = None
        elif b"\n" in data:
            self._show()

    def _hangup(self, signum: int) -> None:
        self.stopped_by = self.stopped_by or "SIGHUP"
        pending = self.service.shutdown()
        if pending is not None:
            import asyncio

            self._pending.append(asyncio.ensure_future(pending))

    def _terminate(self, signum: int) -> None:
        self.stopped_by = self.stopped_by or signal.Signals(signum).name

    def _interrupt(self, signum: int) -> None:
        self.stopped_by = self.stopped_by or "SIGINT"
        self.interrupts += 1
        if self.interrupts == 2:
            from diffctl.launch import logging as launch_logging

            launch_logging.get_logger("launch").warning("ctrl-c again: sending SIGKILL to every process group")
            self.service.spawner.signal_all(signal.SIGKILL)


def _ensure_router() -> Any:
    from diffctl.bus.router import ensure_router

    return ensure_router()


class _LazyBusProbes:
    """`wait_for`'s topic and service conditions, answered through the bus, opened on first use (a launch
    that waits on none never imports the bus)."""

    def __init__(self) -> None:
        self._probes: Any = None

    def _get(self) -> Any:
        if self._probes is None:
            from diffctl.bus.probes import BusProbes

            self._probes = BusProbes()
        return self._probes

    def topic_has_publisher(self, name: str) -> bool:
        return bool(self._get().topic_has_publisher(name))

    def service_available(self, name: str) -> bool:
        return bool(self._get().service_available(name))

    def close(self) -> None:
        if self._probes is not None:
            self._probes.close()
