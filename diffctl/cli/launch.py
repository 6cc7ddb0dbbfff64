"""`diffctl launch`: read a launch file, resolve it, and start and supervise its processes (ros2 launch)."""

from __future__ import annotations

import gc
import os
import sys
from pathlib import Path
from typing import Any

import click

from diffctl.errors import LaunchError, suggest


def _split_targets(targets: tuple[str, ...]) -> tuple[list[str], dict[str, str]]:
    positional = [t for t in targets if ":=" not in t]
    arguments: dict[str, str] = {}
    for t in targets:
        if ":=" in t:
            name, value = t.split(":=", 1)
            if not name:
                raise LaunchError(f"launch argument {t!r} has no name", hint="write NAME:=VALUE")
            arguments[name] = value
    if not 1 <= len(positional) <= 2:
        raise click.UsageError("give a launch file: NAME, PATH, or PACKAGE FILE, then any NAME:=VALUE arguments")
    return positional, arguments


def _bus_probes(kinds: set[str]) -> Any:
    # Imported only when a description waits on topics or services: the engine itself knows processes only.
    from diffctl.bus.probes import BusProbes

    return BusProbes()


def _lifecycle(post: Any) -> Any:
    # The bus side of LifecycleNode, built when a launch first uses one: the engine itself imports no bus.
    from diffctl.cli.launch_lifecycle import make

    return make(post)


def _ensure_router(output: Any) -> Any:
    from diffctl.bus.router import ensure_router

    return ensure_router()


@click.command("launch")
@click.argument("target", nargs=-1, required=True, metavar="NAME|PATH [PACKAGE FILE] [ARG:=VALUE ...]")
@click.option("-s", "--show-args", is_flag=True, help="List the launch file's arguments and exit.")
@click.option(
    "-p",
    "--print",
    "print_plan",
    is_flag=True,
    help="Resolve everything and print the process tree without starting anything.",
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
    help="Where processes without `output` write: screen (diffctl) or log (ros2 launch: stdout to the log only).",
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
    help="Process labels: the name, -2 for a second (diffctl), or name-N from one counter (ros2 launch).",
)
@click.option("--no-router", is_flag=True, help="Do not start the embedded Zenoh router.")
@click.option(
    "--workspace",
    "workspace_dir",
    type=click.Path(file_okay=False, path_type=Path),
    default=None,
    help="The ROS workspace whose packages to use (default: $DIFFCTL_WORKSPACE, else the enclosing one).",
)
def launch(
    target: tuple[str, ...],
    show_args: bool,
    print_plan: bool,
    log_dir: Path | None,
    no_color: bool,
    output_default: str,
    exit_code_mode: str,
    signal_scope: str,
    process_names: str,
    no_router: bool,
    workspace_dir: Path | None,
) -> None:
    """Start a launch file and supervise its processes (ros2 launch).

    NAME is launch/NAME.yaml or launch/NAME.launch.py of the project (YAML first); PATH is any YAML or
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
    from diffctl.launch_legacy.environment import default_log_dir

    positional, arguments = _split_targets(target)
    _choose_workspace(workspace_dir)
    # Launching: the fork server starts before the launcher imports its engine, so the server's imports run
    # while the launcher's own do and the launch file is read and resolved (its first component waits for them).
    run_dir = None if show_args or print_plan else log_dir or default_log_dir()
    server = None if run_dir is None else _start_fork_server(run_dir)
    try:
        from diffctl.cli.show_args import arguments_text
        from diffctl.console import make_console, warn
        from diffctl.launch_legacy.loader import load
        from diffctl.launch_legacy.render import PlanView
        from diffctl.launch_legacy.resolver import Resolver, declared_arguments
        from diffctl.workspace import package_index

        path = package_index.find_launch_file(*positional)
        description = load(path)
        # Piped output is not cut to 80 columns: paths and commands must stay whole.
        console = make_console(no_color=no_color, width=None if sys.stdout.isatty() else 200)
        if show_args:
            print(arguments_text(declared_arguments(description, str(path))), end="")
            return
        if print_plan:
            # A dry run of the engine: what starts, with handlers and timers previewed as of now.
            plan = Resolver().resolve(description, arguments, str(path))
            declared = [a.name for a in plan.arguments]
            for name in arguments:
                if name not in declared:
                    warn(f"argument {name!r} is not declared by the launch file{suggest(name, declared)}")
            for message in plan.warnings:
                warn(message)
            console.print(PlanView(plan))
            return
        from diffctl.launch_legacy.plan import Plan

        # The live run: the engine visits the description once, when the launch starts (see _run).
        plan = Plan(str(path), [], (), {}, description=description, launch_arguments=arguments)
        loop = _event_loop(server)
    except BaseException as e:
        if server is not None:
            server.close(kill=True)
        _ros_exit_code(e, exit_code_mode)
        raise
    assert run_dir is not None
    # SystemExit, not ctx.exit: the entry point runs click with standalone_mode=False, which drops exit codes.
    raise SystemExit(
        _run(
            plan,
            loop,
            run_dir,
            log_given=log_dir is not None,
            no_color=no_color,
            no_router=no_router,
            options={
                "output_default": output_default,
                "exit_code_mode": exit_code_mode,
                "signal_scope": signal_scope,
                "process_names": process_names,
                "real_environ": True,
            },
        )
    )


def _ros_exit_code(e: BaseException, exit_code_mode: str) -> None:
    """--exit-code ros: an error in the launch file ends the launch with 1, as ros2 launch's "Caught exception
    in launch" does (diffctl's own: 2, bad input)."""
    if exit_code_mode == "ros" and isinstance(e, LaunchError):
        e.exit_code = 1


def _start_fork_server(run_dir: Path) -> Any:
    """The fork server, started in the environment the launch's children will get (None when turned off).
    Only light modules are imported on the way: everything the launcher imports before it delays the
    launch's first component."""
    from diffctl.launch_legacy import fork_server
    from diffctl.launch_legacy.environment import default_child_env

    env = default_child_env(_children_env(run_dir))
    if not fork_server.enabled(env):
        return None
    from diffctl.cli.fork_preload import SPEC

    return fork_server.ForkServer(env, preexec=fork_server.dies_with_launcher(), preload=SPEC)


def _event_loop(server: Any) -> Any:
    """The launcher's event loop, its spawner forking diffctl's components from `server` (if any)."""
    from diffctl.launch_legacy.loop import EventLoop

    return EventLoop(server=server)


def _children_env(run_dir: Path) -> dict[str, str]:
    # `diffctl bag record` without -o (and anything else that writes files) puts them next to the logs.
    return {**os.environ, "DIFFCTL_LOG_DIR": str(run_dir.resolve())}


def _choose_workspace(workspace_dir: Path | None) -> None:
    # Children inherit the environment: every process (and xacro run as a command) resolves packages
    # in the same workspace, whatever its own working directory.
    from diffctl.workspace import find_workspace, use_in_children

    use_in_children(find_workspace(explicit=workspace_dir))


def _run(
    plan: Any, loop: Any, run_dir: Path, *, log_given: bool, no_color: bool, no_router: bool, options: dict[str, Any]
) -> int:
    from diffctl.launch_legacy.fork_server import is_component
    from diffctl.launch_legacy.output import Output, link_latest
    from diffctl.launch_legacy.readiness import ProbePoller
    from diffctl.launch_legacy.supervisor import Supervisor

    probes = None
    output = None
    router = None
    poller = None
    try:
        env = _children_env(run_dir)
        supervisor = Supervisor(
            plan, spawner=loop.spawner, output=None, log_dir=run_dir, env=env, lifecycle=_lifecycle, **options
        )
        # The first visit of the description: a bad argument, file or substitution fails here, exit 2,
        # before anything has started (not even the log directory).
        try:
            supervisor.prepare()
        except LaunchError as e:
            _ros_exit_code(e, options["exit_code_mode"])
            raise
        try:
            output = supervisor.output = Output(log_dir=run_dir, no_color=no_color)
        except OSError as e:
            raise LaunchError(
                f"cannot create the log directory {run_dir}: {e.strerror}", hint="pass --log-dir DIR"
            ) from None
        if not supervisor.may_start_components(is_component):
            loop.spawner.drop_fork_server()  # nothing of diffctl's to fork: its imports would only take CPU
        if not log_given:
            link_latest(run_dir)
        output.launcher("INFO", f"All log files can be found below {run_dir}")
        router = None if no_router else _ensure_router(output)
        kinds = supervisor.bus_waits()
        probes = _bus_probes(kinds) if kinds else None
        if probes is not None:
            poller = ProbePoller(
                {"topic": probes.topic_has_publisher, "service": probes.service_available}, notify=loop.wake
            )
            supervisor.use_poller(poller)
        # What is loaded by now lives until the launcher exits: kept out of the collector, the exit after a
        # Ctrl-C does not walk it all again in the interpreter's final collection.
        gc.collect()
        gc.freeze()
        code = loop.run(supervisor)
        output.launcher("INFO", f"logs: {run_dir}")
        return code
    finally:
        loop.spawner.close()  # the fork server too, when the router or anything before the run failed
        if poller is not None:
            poller.close()
        if probes is not None:
            probes.close()
        if router is not None:
            router.close()
        if output is not None:
            output.close()
