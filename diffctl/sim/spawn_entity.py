"""`diffctl spawn entity`: ros_gz_sim's `create` — put a model into the running simulator, or remove one.

Takes the model from a latched topic (`--topic /robot_description`, std_msgs/msg/String), a file or a string,
waits for the simulator (its `gz/world/<w>/sim` token) and the description, asks the world's `create`
service, and exits 0 once the model is in. Any failure (name taken, bad SDF, nothing answering in time)
exits 1 with the reason; the simulator keeps running. ROS-style single-dash flags work as with `create`.
"""

from __future__ import annotations

import math
import os
import threading
import time
from pathlib import Path
from typing import Any

import click

from diffctl.errors import RuntimeFailure
from diffctl.sim.world_client import call, wait_for_world

DEFAULT_TIMEOUT_S = 30.0


def _num(name: str) -> Any:
    return click.option(f"-{name}", f"--{name}", type=float, default=None, help=f"Spawn pose {name}.")


@click.command("entity")
@click.option("-name", "--name", default=None, help="Entity name (default: the model's name).")
@click.option("-topic", "--topic", default=None, help="Latched std_msgs/String topic with the SDF.")
@click.option("-file", "--file", "file_", default=None, type=click.Path(dir_okay=False), help="SDF file.")
@click.option("-string", "--string", "sdf_string", default=None, help="SDF text.")
@click.option("-world", "--world", default=None, help="World to spawn into (default: the only one running).")
@_num("x")
@_num("y")
@_num("z")
@click.option("-R", "--R", "roll", type=float, default=None, help="Spawn roll (rad).")
@click.option("-P", "--P", "pitch", type=float, default=None, help="Spawn pitch (rad).")
@click.option("-Y", "--Y", "yaw", type=float, default=None, help="Spawn yaw (rad).")
@click.option("-allow_renaming", "--allow-renaming", is_flag=True, help="Rename instead of failing on a taken name.")
@click.option("--remove", "remove_name", default=None, metavar="NAME", help="Remove entity NAME instead.")
@click.option(
    "--timeout",
    type=float,
    default=DEFAULT_TIMEOUT_S,
    show_default=True,
    help="Seconds to wait for the simulator and the description.",
)
def spawn_entity(
    name: str | None,
    topic: str | None,
    file_: str | None,
    sdf_string: str | None,
    world: str | None,
    x: float | None,
    y: float | None,
    z: float | None,
    roll: float | None,
    pitch: float | None,
    yaw: float | None,
    allow_renaming: bool,
    remove_name: str | None,
    timeout: float,
) -> None:
    """Spawn a model into the simulator (ros_gz_sim create), or remove one with --remove.

    \b
    Example:
      diffctl spawn entity --name robot --topic /robot_description
      diffctl spawn entity -topic /robot_description -name robot -x 1.0 -Y 1.57
      diffctl spawn entity --file description/my_diff_car.sdf --name car2 --y 1
      diffctl spawn entity --remove car2
    """
    from diffctl.bus import open_session

    if not (math.isfinite(timeout) and timeout > 0):
        raise click.BadParameter(f"{timeout!r} must be a positive number of seconds", param_hint="--timeout")
    sources = [s for s in (topic, file_, sdf_string) if s]
    if remove_name is None and len(sources) != 1:
        raise click.UsageError("give exactly one of --topic, --file or --string (or --remove NAME)")
    pose_vals = {"x": x, "y": y, "z": z, "roll": roll, "pitch": pitch, "yaw": yaw}
    for k, v in pose_vals.items():
        if v is not None and not (math.isfinite(v) and abs(v) <= 1e6):
            raise click.BadParameter(f"{v!r} must be a finite number (|value| <= 1e6)", param_hint=f"-{k}")
    deadline = time.monotonic() + timeout
    session = open_session()
    target = wait_for_world(session, world, deadline)
    if remove_name is not None:
        call(session, target, "remove", {"name": remove_name}, deadline)
        click.echo(f"removed {remove_name!r} from world {target!r}")
        return
    req: dict[str, Any] = {"allow_renaming": allow_renaming, "base_dir": os.getcwd()}
    if name:
        req["name"] = name
    if any(v is not None for v in pose_vals.values()):
        req["pose"] = {k: (v or 0.0) for k, v in pose_vals.items()}
    if file_:
        path = Path(file_).expanduser().resolve()
        if not path.is_file():
            raise RuntimeFailure(f"{file_}: no such file")
        req["sdf_filename"] = str(path)
    elif sdf_string:
        req["sdf"] = sdf_string
    else:
        req["sdf"] = _wait_for_description(str(topic), deadline)
    reply = call(session, target, "create", req, deadline)
    click.echo(f"spawned {reply.get('name')!r} into world {target!r}")


def _wait_for_description(topic: str, deadline: float) -> str:
    from diffctl.bus import Node

    got: list[str] = []
    event = threading.Event()

    def on_msg(msg: Any) -> None:
        got.append(str(msg.data))
        event.set()

    node = Node("ros_gz_sim_create")
    try:
        node.create_subscription(topic, "std_msgs/msg/String", on_msg, latched=True)
        if not event.wait(max(0.0, deadline - time.monotonic())):
            raise RuntimeFailure(
                f"no description arrived on {topic} in time",
                hint="is robot_state_publisher running with a robot_description parameter?",
            )
    finally:
        node.close()
    if not got[0].strip():
        raise RuntimeFailure(f"the description on {topic} is empty")
    return got[0]
