"""`diffctl spawn entity`: ros_gz_sim's `create` — put a model into the running simulator, or remove one.

Flags as `create` takes them (gflags style: `-name robot`, `-name=robot`, `--name robot`): the model from
`-file` (a path, a model folder, `model://`/`package://` URI found on GZ_SIM_RESOURCE_PATH), `-string`,
`-topic` (latched std_msgs/String, relative names in the node's namespace) or `-param NAME` (a parameter
of this node), in create's precedence (-file > -param > -string > -topic); `-name`, `-allow_renaming`
(a bool flag: alone or `=true`/`=false`; a separate `false` word is ignored, as gflags does), `-world`,
and the pose `-x -y -z -R -P -Y`. ROS parameters of the same names (`--ros-args -p name:=…`) win over
flags as in create: a non-empty string, a non-zero pose value, `allow_renaming` true; the source
parameters go file > string > topic. Waits for the simulator and the description, asks the world's
`create` service, exits 0 once the model is in; a refusal exits 1, bad flags exit 2.
"""

from __future__ import annotations

import contextlib
import math
import os
import threading
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import click

from diffctl.errors import ConfigError, RuntimeFailure
from diffctl.sim.world_client import call, running_worlds, wait_for_world

DEFAULT_TIMEOUT_S = 30.0
NODE_NAME = "ros_gz_sim"
POSE_FIELDS = (("x", "x"), ("y", "y"), ("z", "z"), ("R", "roll"), ("P", "pitch"), ("Y", "yaw"))
_RENAMING_FLAGS = ("-allow_renaming", "--allow_renaming", "--allow-renaming")
_POSE_FLAGS = {flag for flag, _ in POSE_FIELDS}
_TRUE, _FALSE = ("true", "t", "yes", "y", "1"), ("false", "f", "no", "n", "0")


@dataclass(frozen=True)
class CreateRequest:
    """What to spawn, validated: exactly one model source, a finite pose."""

    source: str  # "file", "string" or "topic"
    value: str  # the path, the XML text, or the topic name
    name: str | None
    world: str | None
    allow_renaming: bool
    pose: dict[str, float] | None


def gflags_args(args: list[str]) -> tuple[list[str], list[str]]:
    """gflags spellings click does not take → click's; the warnings to print. `-allow_renaming[=v]`
    becomes `--allow-renaming`/`--no-allow-renaming` (gflags never reads a separate word as a bool
    flag's value), `-R=0.1` becomes `-R 0.1`."""
    out: list[str] = []
    notes: list[str] = []
    i = 0
    while i < len(args):
        flag, eq, value = args[i].partition("=")
        if eq and flag.lstrip("-") in _POSE_FLAGS and flag in (f"-{flag.lstrip('-')}", f"--{flag.lstrip('-')}"):
            out += [flag, value]  # gflags' -R=0.1; click would read "=0.1" as the value of -R
        elif flag not in _RENAMING_FLAGS:
            out.append(args[i])
        elif eq:
            v = value.strip().lower()
            if v not in _TRUE + _FALSE:
                raise click.BadParameter(f"{value!r} is not a boolean (valid: true, false)", param_hint=flag)
            out.append("--allow-renaming" if v in _TRUE else "--no-allow-renaming")
        else:
            out.append("--allow-renaming")
            nxt = args[i + 1].strip().lower() if i + 1 < len(args) else ""
            if nxt in _TRUE + _FALSE:
                if nxt in _FALSE:
                    notes.append(
                        f"{flag} {args[i + 1]}: the flag alone means true and the word is ignored (as ros_gz_sim's "
                        f"create reads it): renaming is allowed; write {flag}=false to refuse it"
                    )
                i += 1
        i += 1
    return out, notes


def _ros_param(params: dict[str, Any], name: str, kind: type) -> Any:
    """A parameter of create's node; launch files often pass numbers and booleans as text ('0.0', 'False')."""
    value = params.get(name)
    if value is None:
        return None
    if kind is float and isinstance(value, str) and value.strip():
        try:
            value = float(value)
        except ValueError:
            pass
    if kind is bool and isinstance(value, str) and value.strip().lower() in _TRUE + _FALSE:
        value = value.strip().lower() in _TRUE
    if kind is float and isinstance(value, int) and not isinstance(value, bool):
        value = float(value)
    if kind is float and value == "":
        return None
    if not isinstance(value, kind) or isinstance(value, bool) != (kind is bool):
        raise ConfigError(f"parameter {name!r} of create must be a {kind.__name__}, got {value!r}", field=name)
    return value


def build_request(flags: dict[str, Any], params: dict[str, Any]) -> CreateRequest:
    """Flags and ROS parameters → one request, with create's precedence between them."""
    source: tuple[str, str] | None = None
    for key, kind in (("file", "file"), ("string", "string"), ("topic", "topic")):
        value = _ros_param(params, key, str)
        if value:
            source = (kind, value)
            break
    if source is None and flags.get("file"):
        source = ("file", flags["file"])
    if source is None and flags.get("param"):
        xml = params.get(flags["param"])
        if not isinstance(xml, str) or not xml.strip():
            raise ConfigError(
                f"-param {flags['param']}: this node has no parameter {flags['param']!r} holding the model",
                hint=f'pass it with --ros-args -p {flags["param"]}:="$(cat FILE)"',
            )
        source = ("string", xml)
    if source is None and flags.get("string"):
        source = ("string", flags["string"])
    if source is None and flags.get("topic"):
        source = ("topic", flags["topic"])
    if source is None:
        raise ConfigError("no model given", hint="give -file FILE, -string XML, -topic TOPIC or -param NAME")
    pose: dict[str, float] = {}
    for flag, key in POSE_FIELDS:
        value = _ros_param(params, flag, float) or flags.get(key)
        if value is None:
            continue
        if not (math.isfinite(value) and abs(value) <= 1e6):
            raise ConfigError(f"-{flag} {value!r} must be a finite number (|value| <= 1e6)", field=f"-{flag}")
        pose[key] = float(value)
    return CreateRequest(
        source=source[0],
        value=source[1],
        name=_ros_param(params, "name", str) or flags.get("name") or None,
        world=_ros_param(params, "world", str) or flags.get("world") or None,
        allow_renaming=bool(_ros_param(params, "allow_renaming", bool)) or bool(flags.get("allow_renaming")),
        pose={k: pose.get(k, 0.0) for _, k in POSE_FIELDS} if pose else None,
    )


def resolve_model_file(text: str, cwd: Path) -> Path:
    """`-file`: a path, a model folder, or a model://, package://, file:// URI on the resource path."""
    from diffctl.description.resources import env_search_path, model_file_in, resolve_uri

    found = resolve_uri(text, cwd, env_search_path())
    if found is not None and found.is_dir():
        found = model_file_in(found)
    if found is None or not found.is_file():
        raise ConfigError(
            f"-file {text}: no such model file",
            hint="give a path, a model folder, or a model:// URI found on GZ_SIM_RESOURCE_PATH",
        )
    return found


class _GflagsCommand(click.Command):
    def parse_args(self, ctx: click.Context, args: list[str]) -> list[str]:
        args, notes = gflags_args(list(args))
        ctx.meta["gflags_notes"] = notes
        return super().parse_args(ctx, args)


def _flag(name: str, dest: str, help_text: str, **kw: Any) -> Any:
    return click.option(f"-{name}", f"--{name}", dest, default=None, help=help_text, **kw)


@click.command("entity", cls=_GflagsCommand)
@_flag("name", "name", "Entity name (default: the model's name).")
@_flag("topic", "topic", "Latched std_msgs/String topic with the model (relative: in the node's namespace).")
@_flag("file", "file", "SDF or URDF file, model folder or model:// URI.")
@_flag("string", "string", "The model's SDF or URDF text.")
@_flag("param", "param", "Name of this node's parameter holding the model's text.")
@_flag("world", "world", "World to spawn into (default: the only one running).")
@_flag("x", "x", "Spawn position x (m).", type=float)
@_flag("y", "y", "Spawn position y (m).", type=float)
@_flag("z", "z", "Spawn position z (m).", type=float)
@_flag("R", "roll", "Spawn roll (rad).", type=float)
@_flag("P", "pitch", "Spawn pitch (rad).", type=float)
@_flag("Y", "yaw", "Spawn yaw (rad).", type=float)
@click.option(
    "--allow-renaming/--no-allow-renaming",
    "allow_renaming",
    default=False,
    help="Rename instead of failing on a taken name (also -allow_renaming, -allow_renaming=true).",
)
@click.option("--remove", "remove_name", default=None, metavar="NAME", help="Remove entity NAME instead.")
@click.option(
    "--timeout",
    type=float,
    default=DEFAULT_TIMEOUT_S,
    show_default=True,
    help="Seconds to wait for the simulator and the description.",
)
@click.pass_context
def spawn_entity(ctx: click.Context, remove_name: str | None, timeout: float, **flags: Any) -> None:
    """Spawn a model into the simulator (ros_gz_sim create), or remove one with --remove.

    \b
    Example:
      diffctl spawn entity -topic robot_description -name robot -allow_renaming -z 0.1
      diffctl spawn entity -file description/my_diff_car.sdf -name car2 -x 1.0 -Y 1.57
      diffctl spawn entity -file model://my_robot -name r1 --ros-args -r __ns:=/r1
      diffctl spawn entity --remove car2
    """
    from diffctl import ros_args
    from diffctl.bus import open_session

    if not (math.isfinite(timeout) and timeout > 0):
        raise click.BadParameter(f"{timeout!r} must be a positive number of seconds", param_hint="--timeout")
    if ctx.meta.get("gflags_notes"):
        from diffctl.console import warn  # rich: 0.15 s of a launch's critical path when imported for nothing

        for note in ctx.meta["gflags_notes"]:
            warn(note)
    req = None
    if remove_name is None:
        req = build_request(flags, dict(ros_args.current(NODE_NAME).params))
    model_file = resolve_model_file(req.value, Path.cwd()) if req is not None and req.source == "file" else None
    deadline = time.monotonic() + timeout
    session = open_session()
    # The description is subscribed to before the world is waited for: the two waits overlap.
    description = _Description(req.value) if req is not None and req.source == "topic" and model_file is None else None
    try:
        target = _wait_for_world(session, None if req is None else req.world, deadline)
        if req is None:
            call(session, target, "remove", {"name": remove_name}, deadline)
            click.echo(f"removed {remove_name!r} from world {target!r}")
            return
        sdf = description.wait(deadline) if description is not None else None
        body: dict[str, Any] = {"allow_renaming": req.allow_renaming, "base_dir": os.getcwd()}
        if req.name:
            body["name"] = req.name
        if req.pose is not None:
            body["pose"] = req.pose
        if model_file is not None:
            body["sdf_filename"] = str(model_file)
        elif req.source == "string":
            body["sdf"] = req.value
        else:
            body["sdf"] = sdf
        try:
            reply = call(session, target, "create", body, deadline)
        except RuntimeFailure as e:
            # ros_gz_sim's create: "Entity creation failed." and exit 1; the simulator's reason names file and line
            reason = e.message.removeprefix("create failed: ")
            raise RuntimeFailure(f"Entity creation failed: {reason}", hint=e.hint) from None
    finally:
        # The node that read the description ends after the call: its endpoints' undeclarations (20-30 ms
        # under load) held the call back, and with it the robot's spawn.
        if description is not None:
            description.close()
    click.echo(f"spawned {reply.get('name')!r} into world {target!r}")


def _wait_for_world(session: Any, world: str | None, deadline: float) -> str:
    """world_client.wait_for_world, woken by the simulator's presence token as it appears instead of
    querying every 0.1 s (the simulator usually comes up while `create` waits for it)."""
    from diffctl.sim.world_keys import SIM_TOKEN_PATTERN, sim_token_key

    appeared = threading.Event()
    try:
        sub = session.liveliness().declare_subscriber(
            sim_token_key(world) if world else SIM_TOKEN_PATTERN, lambda _sample: appeared.set(), history=True
        )
    except Exception:  # no liveliness subscriber: poll as world_client does
        return wait_for_world(session, world, deadline)
    try:
        while time.monotonic() <= deadline:
            appeared.clear()
            worlds = running_worlds(session, world)
            if len(worlds) == 1:
                return worlds[0]
            if worlds:
                break
            # Woken by the token, but asked again after 0.1 s regardless: a token declared while this
            # subscriber's history is being delivered can miss it (seen as a 1 s stall in 1 of 6 launches).
            appeared.wait(min(0.1, max(0.0, deadline - time.monotonic())))
    finally:
        with contextlib.suppress(Exception):
            sub.undeclare()
    return wait_for_world(session, world, deadline)  # several worlds or none in time: its error, as always


class _Description:
    """The latched description topic, subscribed to at once; `wait` returns its text."""

    def __init__(self, topic: str) -> None:
        from diffctl.client import component
        from diffctl.client.node import Node

        self._got: list[str] = []
        self._event = threading.Event()
        component.init()
        self._node = Node(NODE_NAME, client_library="rclcpp")
        try:
            self.resolved = self._node.resolve_topic_name(topic)
            # One latched sample, taken on the transport's thread: the node is never spun.
            self._node.bus_node.create_subscription(self.resolved, "std_msgs/msg/String", self._on_msg,
                                                    latched=True)
        except BaseException:
            self._node.destroy_node()
            raise

    def _on_msg(self, msg: Any) -> None:
        self._got.append(str(msg.data))
        self._event.set()

    def wait(self, deadline: float) -> str:
        if not self._event.wait(max(0.0, deadline - time.monotonic())):
            raise RuntimeFailure(
                f"no description arrived on {self.resolved} in time",
                hint="is robot_state_publisher running with a robot_description parameter?",
            )
        if not self._got[0].strip():
            raise RuntimeFailure(f"the description on {self.resolved} is empty")
        return self._got[0]

    def close(self) -> None:
        self._node.destroy_node()
