"""`diffctl sim run WORLD`: the `gz sim` counterpart (package ros_gz_sim, executable gz_sim).

Accepts Gazebo's flags, also packed in one string as ros_gz_sim's `gz_args` passes them
("-r -s -v4 empty.world"): -r run at start (else paused), -s server only (headless: the default), -g GUI
only (there is no separate GUI client: use --gui on the server or `diffctl viz`), -v N verbosity 0-4,
--iterations N, --seed N; plus --gui (the PyBullet window) and --rtf X (0 = as fast as possible; default
the world's <real_time_factor>).
"""

from __future__ import annotations

import os
import re
import shlex
import signal
import threading
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import click

from diffctl.errors import ConfigError

LEVELS = {0: "ERROR", 1: "WARN", 2: "WARN", 3: "INFO", 4: "DEBUG"}


@dataclass
class GzArgs:
    world: str | None = None
    run: bool = False
    server_only: bool = False
    gui_only: bool = False
    verbosity: int | None = None
    iterations: int | None = None
    seed: int | None = None
    rtf: float | None = None
    gui: bool = False


# `gz sim`'s options as gz-sim 8's Ruby front end declares them (src/cmd/cmdsim.rb.in): name → the type of
# its argument (None: a flag). Every argument is "placed" (`-v [verbose]`): it is the attached text (`-v4`,
# `--seed=3`) or the next word unless that word starts with '-', else it is absent.
_SHORT: dict[str, str | None] = {"h": None, "r": None, "g": None, "s": None, "v": "str", "z": "float"}
_LONG: dict[str, str | None] = {
    "help": None,
    "iterations": "int",
    "network-role": "str",
    "network-secondaries": "int",
    "initial-sim-time": "float",
    "levels": None,
    "record": None,
    "record-path": "str",
    "record-resources": None,
    "record-topic": "str",
    "record-period": "float",
    "log-overwrite": None,
    "log-compress": None,
    "playback": "str",
    "verbose": "str",
    "gui-config": "str",
    "physics-engine": "str",
    "headless-rendering": None,
    "render-engine-gui": "str",
    "render-engine-gui-api-backend": "str",
    "render-engine-server": "str",
    "render-engine-server-api-backend": "str",
    "render-engine": "str",
    "render-engine-api-backend": "str",
    "version": None,
    "seed": "int",
    # diffctl's own, also read inside a gz_args string (ros_gz_sim's gz_sim.launch.py hands them over in one)
    "rtf": "float",
    "gui": None,
}
_RUBY_INTEGER = re.compile(
    r"[-+]?(?:0[bB][01]+(?:_[01]+)*|0[xX][\da-fA-F]+(?:_[\da-fA-F]+)*|0[oO]?[0-7]*(?:_[0-7]+)*|[1-9]\d*(?:_\d+)*)"
)
_RUBY_FLOAT = re.compile(r"[-+]?(?:\d+(?:_\d+)*(?:\.\d+(?:_\d+)*)?(?:[eE][-+]?\d+)?|\.\d+(?:[eE][-+]?\d+)?)")


def parse_gz_args(tokens: list[str]) -> GzArgs:
    """Gazebo's `gz sim` flags from loose tokens (each may hold several, as a gz_args string does), read as
    gz sim 8's Ruby OptionParser reads them: short flags cluster (`-rs`), `-v` takes an attached or following
    value unless that starts with '-' (bare `-v` is 3; `-v -v1` is 1: the last wins), long options take
    `=value` and unambiguous prefixes, and the world is the last word that is no option's value."""
    words: list[str] = []
    for t in tokens:
        try:
            words.extend(shlex.split(t))
        except ValueError as e:  # a quote left open: the shell that splits a gz_args string refuses it too
            raise ConfigError(f"sim run: cannot split the arguments {t!r}: {str(e).lower()}",
                              hint="close the quote, or quote the whole world path") from None
    out = GzArgs()
    positional: list[str] = []
    i = 0
    while i < len(words):
        w = words[i]
        i += 1
        if w == "--":
            positional.extend(words[i:])
            break
        if w.startswith("--"):
            name, eq, attached = w[2:].partition("=")
            long_name = _long_option(name, w)
            i = _apply(out, f"--{long_name}", _LONG[long_name], attached if eq else None, words, i)
        elif w.startswith("-") and len(w) > 1:
            rest = w[1:]
            while rest:
                flag, rest = rest[0], rest[1:]
                if flag not in _SHORT:
                    raise ConfigError(
                        f"sim run: invalid option: -{flag}" + (f" (in {w!r})" if len(w) > 2 else ""),
                        hint="valid: -r, -s, -g, -v [N], -z HZ, --iterations N, --seed N, --gui, --rtf X, "
                        "and gz sim's other long options",
                    )
                kind = _SHORT[flag]
                if kind is None:
                    _apply(out, f"-{flag}", None, None, words, i)
                    continue
                i = _apply(out, f"-{flag}", kind, rest or None, words, i)
                break
        else:
            positional.append(w)
    if positional:
        out.world = positional[-1]  # cmdsim.rb pops the last one; others are not read
    if out.iterations is not None and out.iterations < 0:
        raise ConfigError(f"sim run: --iterations {out.iterations} must be >= 0")
    return out


def _long_option(name: str, word: str) -> str:
    if name in _LONG:
        return name
    matches = [n for n in _LONG if n.startswith(name)] if name else []
    if len(matches) == 1:
        return matches[0]
    what = "ambiguous option" if matches else "invalid option"
    raise ConfigError(
        f"sim run: {what}: {word}" + (f" ({', '.join('--' + m for m in matches)})" if matches else ""),
        hint="valid: -r, -s, -g, -v [N], -z HZ, --iterations N, --seed N, --gui, --rtf X, "
        "and gz sim's other long options",
    )


def _apply(out: GzArgs, flag: str, kind: str | None, attached: str | None, words: list[str], i: int) -> int:
    """Record one option; returns the index of the next word (one further when it took that word)."""
    value = attached
    if kind is not None and value is None and i < len(words) and not words[i].startswith("-"):
        value = words[i]
        i += 1
    if kind is None and attached is not None:
        raise ConfigError(f"sim run: needless argument: {flag}={attached}")
    if flag == "-r":
        out.run = True
    elif flag == "-s":
        out.server_only = True
    elif flag == "-g":
        out.gui_only = True
    elif flag == "--gui":
        out.gui = True
    elif flag == "--rtf":
        if value is None or not _RUBY_FLOAT.fullmatch(value):
            raise ConfigError(f"sim run: invalid argument: --rtf {value}", hint="a number >= 0, e.g. 1 (0 = max)")
        out.rtf = float(value)
    elif flag in ("-v", "--verbose"):
        # gz hands the text to atoi(): "-v" alone is 3, a word that is no number is 0; past 4 is as loud as 4
        out.verbosity = max(0, min(4, _atoi(value))) if value is not None else 3
    elif flag in ("--iterations", "--seed"):
        if value is None:
            raise ConfigError(f"sim run: {flag} needs a value")
        number = _ruby_integer(value, flag)
        if flag == "--iterations":
            out.iterations = number
        else:
            out.seed = number
    elif kind == "int" and value is not None:
        _ruby_integer(value, flag)
    elif kind == "float" and flag.startswith("--") and value is not None and not _RUBY_FLOAT.fullmatch(value):
        # (a short option's bad number is not an error to Ruby's OptionParser: `-z x` reads as no rate)
        raise ConfigError(f"sim run: invalid argument: {flag} {value}", hint="a number, e.g. 1000")
    return i


def _atoi(text: str) -> int:
    m = re.match(r"\s*([-+]?\d+)", text)
    return int(m.group(1)) if m else 0


def _ruby_integer(text: str, flag: str) -> int:
    """An Integer option's value as Ruby's Integer() reads it (0x.., 0b.., 0o../0.. octal, 1_000)."""
    if not _RUBY_INTEGER.fullmatch(text):
        raise ConfigError(f"sim run: invalid argument: {flag} {text}", hint="an integer, e.g. 100")
    t = text.replace("_", "")
    sign = -1 if t.startswith("-") else 1
    t = t.lstrip("+-")
    if len(t) > 1 and t[0] == "0" and t[1] not in "xXbBoO":
        return sign * int(t[1:], 8)
    return sign * int(t, 0)


def find_world(name: str) -> Path:
    """The world file: a path, or a name looked up on GZ_SIM_RESOURCE_PATH, the project's worlds and Gazebo's."""
    if name.startswith(("http://", "https://")):
        return _fuel_world(name)
    p = Path(name).expanduser()
    if p.is_file():
        return p
    from diffctl.description.resources import env_search_path
    from diffctl.workspace.builtin import GAZEBO_WORLDS

    here = Path(__file__).resolve().parent.parent
    # Last, Gazebo's own worlds (empty.sdf …), as `gz sim empty.sdf` finds them.
    candidates = [
        *env_search_path(),
        here.parent / "config" / "worlds",
        here / "share" / "config" / "worlds",
        GAZEBO_WORLDS,
    ]
    for d in candidates:
        for cand in (d / name, d / f"{name}.sdf", d / f"{name}.world"):
            if cand.is_file():
                return cand
    raise ConfigError(
        f"world file {name!r} not found",
        hint="give a path to an SDF world, or a name found on GZ_SIM_RESOURCE_PATH (e.g. empty.world)",
    )


def _fuel_world(url: str) -> Path:
    """A Fuel world URL (`gz sim https://fuel.gazebosim.org/1.0/OpenRobotics/worlds/X`): Gazebo's Fuel cache,
    else a download into it."""
    from diffctl.fuel.resolve import FuelModelUnavailable, resolve_fuel_world

    try:
        path = resolve_fuel_world(url)
    except FuelModelUnavailable as e:
        raise ConfigError(e.message, hint=e.hint) from None
    if path is None:
        raise ConfigError(
            f"world {url!r} is not a Fuel world URL", hint="e.g. https://fuel.gazebosim.org/1.0/<owner>/worlds/<name>"
        )
    return path


@click.group()
def sim() -> None:
    """The PyBullet simulator: runs SDF worlds as Gazebo does (gz sim).

    \b
    Example:
      diffctl sim run -r config/worlds/empty.world
      diffctl sim run "-r -s -v4 config/worlds/empty.world"
    """


@sim.command("run", context_settings={"ignore_unknown_options": True})
@click.argument("args", nargs=-1, type=click.UNPROCESSED)
@click.option("--gui", is_flag=True, help="Open the PyBullet window (Gazebo's GUI counterpart).")
@click.option("--rtf", type=float, default=None, help="Target real-time factor; 0 = as fast as possible.")
def run(args: tuple[str, ...], gui: bool, rtf: float | None) -> None:
    """Simulate WORLD (an SDF file): physics, sensors, Gazebo systems, ros2_control endpoints.

    ARGS are Gazebo's: WORLD, -r (run at start, else paused), -s (server only), -g, -v N (0-4),
    --iterations N (stop after N steps), --seed N (noise seed). The world services live under
    gz/world/<name>/ (control, create, remove, state) and statistics on /world/<name>/stats.

    \b
    Example:
      diffctl sim run -r -v 3 config/worlds/empty.world
      diffctl sim run --gui --rtf 1 -r config/worlds/empty.world
    """
    from diffctl import ros_args
    from diffctl.client import ros_logging
    from diffctl.sim.log import Logger

    ros_logging.configure_from_args(["--ros-args", *ros_args.current_argv()])
    g = parse_gz_args(list(args))
    rtf = rtf if rtf is not None else g.rtf
    gui = gui or g.gui
    if rtf is not None and (rtf != rtf or rtf < 0 or rtf == float("inf")):
        raise ConfigError(f"--rtf {rtf} must be a finite number >= 0 (0 = as fast as possible)")
    g.rtf = rtf
    log = Logger("sim", LEVELS[g.verbosity if g.verbosity is not None else 1])
    if g.gui_only and g.world is None:
        log.warn(
            "`-g` starts only Gazebo's GUI client; diffctl's sim draws its own window with --gui, "
            "and `diffctl viz` shows the world in a browser. Nothing to do."
        )
        return
    if g.world is None:
        raise click.UsageError("give a world file, e.g. `diffctl sim run -r config/worlds/empty.world`")
    serve(find_world(g.world), g, gui=gui and not g.server_only, log=log)


def serve(world_path: Path, g: GzArgs, *, gui: bool, log: Any) -> None:
    """Load the world (errors exit 2 before anything starts), open the bus, run until SIGINT/SIGTERM."""
    from diffctl.description.sdf_loader import load_world

    # The world first: what it says about itself (a model left out, an error) comes before anything PyBullet
    # prints when it is imported.
    world = load_world(world_path)
    from diffctl.bus import open_session
    from diffctl.sim.runner import Simulation
    from diffctl.sim.services import WorldServices

    session = open_session()
    seed = g.seed if g.seed is not None else int(os.environ.get("DIFFCTL_SIM_SEED", "0") or 0)
    sim_ = Simulation(world, gui=gui, rtf=g.rtf, paused=not g.run, seed=seed, log=log, session=session)
    stop = threading.Event()
    lost: list[bool] = []

    def router_lost() -> None:
        lost.append(True)
        stop.set()

    try:
        WorldServices(sim_, on_router_lost=router_lost)
        for sig in (signal.SIGINT, signal.SIGTERM):
            signal.signal(sig, lambda *_: stop.set())
        if g.iterations:
            sim_.stepper.add_task(
                "iterations",
                g.iterations * sim_.stepper.step_ns,
                lambda _t: stop.set(),
                first_ns=g.iterations * sim_.stepper.step_ns,
            )
        state = "running" if g.run else 'paused (resume: gz/world/<w>/control {"pause": false})'
        log.info(
            f"world {world.name!r} from {world_path}: {len(world.models)} model(s), step "
            f"{sim_.physics.step_s * 1e3:g} ms, rtf {sim_.stepper.rtf:g}, {state}"
        )
        try:
            sim_.run(stop)
        except Exception as e:
            import pybullet as pb

            if gui and isinstance(e, pb.error):
                log.info("the PyBullet window was closed; stopping")
                return
            raise
    finally:
        sim_.close()
        log.debug("stopped")
    if lost:
        from diffctl.errors import RuntimeFailure

        raise RuntimeFailure("lost the Zenoh router; the simulator stopped")


# --- talking to a running simulator (Gazebo: `gz service -s /world/<w>/control …`) -------------------------

_world_option = click.option("--world", default=None, help="World to talk to (default: the only one running).")


def _control(world: str | None, req: dict[str, Any], timeout: float = 10.0) -> dict[str, Any]:
    import time

    from diffctl.bus import open_session
    from diffctl.sim.world_client import call, wait_for_world

    session = open_session()
    deadline = time.monotonic() + timeout
    target = wait_for_world(session, world, time.monotonic() + 2.0)
    return call(session, target, "control", req, deadline)


def _status_line(st: dict[str, Any]) -> str:
    state = "paused" if st["paused"] else "running"
    return f"{state} at sim time {st['sim_time_ns'] / 1e9:.3f} s ({st['iterations']} steps)"


@sim.command("pause")
@_world_option
def pause(world: str | None) -> None:
    """Pause the simulation (sim time stops; controllers in lockstep wait).

    \b
    Example:
      diffctl sim pause
    """
    click.echo(_status_line(_control(world, {"pause": True})))


@sim.command("resume")
@_world_option
def resume(world: str | None) -> None:
    """Resume a paused simulation.

    \b
    Example:
      diffctl sim resume
    """
    click.echo(_status_line(_control(world, {"pause": False})))


@sim.command("step")
@click.argument("steps", type=click.IntRange(1, 10_000_000), default=1)
@_world_option
def step(steps: int, world: str | None) -> None:
    """Pause, then advance STEPS physics steps (default 1); returns when they are done.

    \b
    Example:
      diffctl sim step 100
    """
    click.echo(_status_line(_control(world, {"multi_step": steps}, timeout=60.0)))


@sim.command("reset")
@_world_option
def reset(world: str | None) -> None:
    """Reset the world: sim time 0, every model back where it was spawned.

    \b
    Example:
      diffctl sim reset
    """
    click.echo(_status_line(_control(world, {"reset": {"all": True}})))


@sim.command("rtf")
@click.argument("factor", type=click.FloatRange(0.0, 1e6))
@_world_option
def rtf_cmd(factor: float, world: str | None) -> None:
    """Set the target real-time factor (0 = as fast as possible).

    \b
    Example:
      diffctl sim rtf 0
    """
    click.echo(_status_line(_control(world, {"rtf": factor})))


@sim.command("state")
@_world_option
def state(world: str | None) -> None:
    """Show the running world: time, models and their poses.

    \b
    Example:
      diffctl sim state
    """
    import time

    from diffctl.bus import open_session
    from diffctl.console import console, table
    from diffctl.sim.world_client import call, wait_for_world

    session = open_session()
    target = wait_for_world(session, world, time.monotonic() + 2.0)
    st = call(session, target, "state", {}, time.monotonic() + 10.0)
    rows = []
    for m in st["models"]:
        p = m["pose"]
        kind = "static" if m["static"] else ("ros2_control" if m["ros2_control"] else "dynamic")
        rows.append((m["name"], kind, f"{p['x']:.3f} {p['y']:.3f} {p['z']:.3f}", f"{p['yaw']:.3f}"))
    target_rtf = "max" if st["rtf_target"] <= 0 else f"{st['rtf_target']:g}"
    console.print(f"world {st['world']!r}: {_status_line(st)}, target rtf {target_rtf}")
    console.print(table(None, ["model", "kind", "x y z (m)", "yaw (rad)"], rows))
