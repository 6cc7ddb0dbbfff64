"""`gz`: Gazebo's command line for diffctl's simulator (`gz sim`, `gz topic`, `gz service`, `gz model`, `gz fuel`).

Launch files run `ExecuteProcess(cmd=['gz', 'sim', '-r', 'empty.sdf'])` and users type `gz topic -e -t /clock`;
both reach diffctl through this console script (on PATH in the venv and inside every launch). Flags and output
follow gz-tools2 / gz-sim8 / gz-transport13: `gz sim` becomes `diffctl sim run` with the same arguments; topic
payloads are printed and read in protobuf's text format.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from typing import Any, NoReturn

from diffctl.errors import ConfigError, DiffctlError, RuntimeFailure

USAGE = """Gazebo's command line, served by diffctl.

Usage: gz <command> [options]

  sim      Run a world: gz sim [-r] [-s] [-g] [-v N] [--iterations N] WORLD
  topic    gz topic -l | -i -t T | -e -t T [-n N] [-d S] [--json-output] | -p TEXT -t T -m gz.msgs.X
  service  gz service -l | -i -s S | -s S --reqtype A --reptype B [--timeout MS] --req TEXT
  model    gz model --list | -m NAME [-p] [-l [LINK]] [-j [JOINT]] [-s [SENSOR]]
  fuel     gz fuel download -u URL

Options: -h, --help
"""

WORLD_SERVICES = {
    "control": ("gz.msgs.WorldControl", "gz.msgs.Boolean"),
    "create": ("gz.msgs.EntityFactory", "gz.msgs.Boolean"),
    "remove": ("gz.msgs.Entity", "gz.msgs.Boolean"),
    "state": ("gz.msgs.Empty", "gz.msgs.SerializedStepMap"),
}


def main(argv: list[str] | None = None) -> None:
    args = list(sys.argv[1:] if argv is None else argv)
    try:
        code = dispatch(args)
    except DiffctlError as e:
        print(f"error: {e}", file=sys.stderr)
        code = e.exit_code
    except KeyboardInterrupt:
        code = 130
    except BrokenPipeError:  # `gz topic -e … | head`: the reader left, which is no error
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        code = 0
    finally:
        session = sys.modules.get("diffctl.bus.session")
        if session is not None:
            session.close_session()
    sys.exit(code)


def dispatch(args: list[str]) -> int:
    if not args or args[0] in ("-h", "--help", "help"):
        print(USAGE, end="")
        return 0 if args else 1
    command, rest = args[0], args[1:]
    if command in ("sim", "gazebo"):  # `ign gazebo` is the older spelling
        return sim(rest)
    if command == "topic":
        return topic(rest)
    if command == "service":
        return service(rest)
    if command == "model":
        return model(rest)
    if command == "fuel":
        return fuel(rest)
    from diffctl.errors import suggest

    raise ConfigError(
        f"gz: unknown command {command!r}{suggest(command, ['sim', 'topic', 'service', 'model', 'fuel'])}",
        hint="diffctl serves: sim, topic, service, model, fuel",
    )


def sim(rest: list[str]) -> int:
    """`gz sim …` is `diffctl sim run …`: exec'd, so a launch supervises the simulator itself."""
    from diffctl.sim.cli import parse_gz_args

    if any(a in ("-h", "--help") for a in rest):
        print("Usage: gz sim [-r] [-s] [-g] [-v N] [--iterations N] [--seed N] WORLD  (diffctl sim run)")
        return 0
    args = parse_gz_args(rest)  # bad flags are reported here, before anything starts
    if args.gui_only and not args.server_only:
        return _gui_client()
    from diffctl.workspace import find_workspace, use_in_children

    # typed in a workspace (not sourced, as diffctl needs no build): its packages' hooks apply, as after
    # `source install/setup.bash`; inside a launch this was done already and changes nothing
    use_in_children(find_workspace())
    os.execv(sys.executable, [sys.executable, "-m", "diffctl", "sim", "run", *rest])
    return 0  # not reached


def _gui_client() -> int:
    """`gz sim -g`: Gazebo's GUI client, which stays until its window closes. diffctl has no such window (the
    browser visualizer shows the scene), so this says so once and idles until the launch stops it."""
    import signal

    for sig in (signal.SIGINT, signal.SIGTERM):
        signal.signal(sig, lambda *_: sys.exit(0))
    print(
        "[WARN] gz sim -g starts Gazebo's GUI client; diffctl's simulator has none: `diffctl viz` (rviz2) shows "
        "the scene, `diffctl sim run --gui` opens PyBullet's window",
        file=sys.stderr,
        flush=True,
    )
    while True:
        signal.pause()


class _Parser(argparse.ArgumentParser):
    """argparse, its refusal one error line (argparse itself prints its usage and exits)."""

    def error(self, message: str) -> NoReturn:
        usage = " ".join(self.format_usage().split())
        # argparse quotes no argument it names: one that holds a newline or another control character is escaped
        shown = "".join(c if c.isprintable() else repr(c)[1:-1] for c in message)
        raise ConfigError(f"{self.prog}: {shown}", hint=usage)


def _parser(prog: str) -> argparse.ArgumentParser:
    return _Parser(prog=prog, add_help=True, allow_abbrev=False)


def _parse(parser: argparse.ArgumentParser, rest: list[str]) -> argparse.Namespace:
    return parser.parse_args(rest)


def _session() -> Any:
    from diffctl.bus import open_session
    from diffctl.bus.session import use_client_mode

    use_client_mode()  # one-shot tool: the router knows every token at once (a fresh peer may miss some)
    return open_session()


def _endpoints(session: Any) -> list[tuple[str, str, str, str]]:
    from diffctl.bus import gz

    found = []
    for reply in session.liveliness().get(f"{gz.ENDPOINT_TOKEN_PREFIX}/**", timeout=1.0):
        if reply.ok is not None:
            parsed = gz.parse_endpoint_token(str(reply.ok.key_expr))
            if parsed is not None:
                found.append(parsed)
    return found


def topic(rest: list[str]) -> int:
    p = _parser("gz topic")
    p.add_argument("-l", "--list", action="store_true")
    p.add_argument("-i", "--info", action="store_true")
    p.add_argument("-e", "--echo", action="store_true")
    p.add_argument("-p", "--pub", metavar="TEXT")
    p.add_argument("-t", "--topic")
    p.add_argument("-m", "--msgtype")
    p.add_argument("-n", "--num", type=int, default=-1)
    p.add_argument("-d", "--duration", type=float, default=-1.0)
    p.add_argument("--json-output", action="store_true")
    a = _parse(p, rest)
    if a.list:
        for name in sorted({t for kind, _, t, _ in _endpoints(_session()) if kind != "srv"}):
            print(name)
        return 0
    if not a.topic:
        raise ConfigError("gz topic: -t TOPIC is required", hint="e.g. gz topic -e -t /clock")
    if a.info:
        return _topic_info(a.topic)
    if a.echo:
        return _echo(a.topic, a.num, a.duration, a.json_output)
    if a.pub is not None:
        if not a.msgtype:
            raise ConfigError("gz topic -p: -m MSGTYPE is required", hint="e.g. -m gz.msgs.Twist")
        return _publish(a.topic, a.msgtype, a.pub)
    raise ConfigError("gz topic: one of -l, -i, -e, -p is required")


def _norm(topic_name: str) -> str:
    return "/" + topic_name.strip("/")


def _topic_info(name: str) -> int:
    found = [e for e in _endpoints(_session()) if e[2] == _norm(name)]
    for kind, title in (("pub", "Publishers"), ("sub", "Subscribers")):
        mine = sorted({(zid, t) for k, zid, _, t in found if k == kind})
        if mine:
            print(f"{title} [Address, Message Type]:")
            for zid, gz_type in mine:
                print(f"  zenoh/{zid}, {gz_type}")
        else:
            print(f"No {title.lower()} on topic [{_norm(name)}]")
    return 0


def _echo(name: str, count: int, duration_s: float, as_json: bool) -> int:
    import queue

    from diffctl.bus import gz
    from diffctl.gz.textproto import format_message, json_value

    session = _session()
    samples: queue.Queue[bytes] = queue.Queue()
    sub = session.declare_subscriber(gz.key(name), lambda s: samples.put(s.payload.to_bytes()))
    end = time.monotonic() + duration_s if duration_s >= 0 else None
    printed = 0
    try:
        while count < 0 or printed < count:
            timeout = None if end is None else end - time.monotonic()
            if timeout is not None and timeout <= 0:
                break
            try:
                payload = samples.get(timeout=0.2 if timeout is None else min(timeout, 0.2))
            except queue.Empty:
                continue
            _, fields = gz.decode(payload)
            if as_json:
                print(json.dumps(json_value(fields)), flush=True)
            else:
                print(format_message(fields), flush=True)
            printed += 1
    finally:
        sub.undeclare()
    return 0


def _publish(name: str, gz_type: str, text: str) -> int:
    from diffctl.bus import gz
    from diffctl.gz.textproto import parse_message

    if not gz_type.startswith(("gz.msgs.", "ignition.msgs.")):
        raise ConfigError(f"gz topic -p: message type {gz_type!r} is not a gz.msgs type", hint="e.g. gz.msgs.Twist")
    fields = parse_message(text)
    gz_type = "gz.msgs." + gz_type.split(".msgs.", 1)[1]
    session = _session()
    pub = session.declare_publisher(gz.key(name))
    token = gz.announce(session, "pub", name, gz_type)
    time.sleep(0.8)  # as gz-transport's `gz topic -p`: give subscribers time to discover the publisher
    pub.put(gz.encode(gz_type, fields))
    time.sleep(0.1)
    token.undeclare()
    pub.undeclare()
    return 0


def _worlds(session: Any) -> list[str]:
    from diffctl.sim.world_client import running_worlds

    return running_worlds(session)


def service(rest: list[str]) -> int:
    p = _parser("gz service")
    p.add_argument("-l", "--list", action="store_true")
    p.add_argument("-i", "--info", action="store_true")
    p.add_argument("-s", "--service")
    p.add_argument("--reqtype")
    p.add_argument("--reptype")
    p.add_argument("--timeout", type=int, default=1000)
    p.add_argument("-r", "--req", default="")
    a = _parse(p, rest)
    session = _session()
    worlds = _worlds(session)
    services = {"/gazebo/worlds": ("gz.msgs.Empty", "gz.msgs.StringMsg_V")}
    for w in worlds:
        for leaf, types in WORLD_SERVICES.items():
            services[f"/world/{w}/{leaf}"] = types
    # the services systems advertise (a battery's recharge/start, …), from their announcing tokens
    announced = {t: tuple(types.split("~", 1)) for kind, _, t, types in _endpoints(session) if kind == "srv"}
    services.update({n: (r[0], r[1]) for n, r in announced.items() if len(r) == 2})
    if a.list:
        for name in sorted(services):
            print(name)
        return 0
    if not a.service:
        raise ConfigError("gz service: -s SERVICE is required", hint="e.g. gz service -l")
    name = _norm(a.service)
    if a.info:
        if name not in services:
            print(f"No service providers on service [{name}]")
            return 0
        print("Service providers [Address, Request Message Type, Response Message Type]:")
        print(f"  zenoh, {services[name][0]}, {services[name][1]}")
        return 0
    if name not in services:
        print("Service call timed out")
        return 1
    if name in announced:
        return _call_announced(session, name, a.reqtype or services[name][0], a.reptype or "", a.req, a.timeout)
    return _call(session, name, a.req, a.timeout)


def _call_announced(session: Any, name: str, req_type: str, rep_type: str, text: str, timeout_ms: int) -> int:
    """A request to a system's gz service, as gz-transport's `gz service -s` sends it: with `--reptype
    gz.msgs.Empty` it waits at most a second and prints nothing; otherwise it prints the response."""
    from diffctl.bus import gz
    from diffctl.gz.textproto import format_message, parse_message

    req_type = "gz.msgs." + req_type.split(".msgs.", 1)[-1]
    payload = gz.encode(req_type, parse_message(text) if text.strip() else {})
    empty = rep_type.endswith(".msgs.Empty")
    timeout_s = 1.0 if empty else max(timeout_ms, 1) / 1000.0
    for reply in session.get(gz.service_key(name), payload=payload, timeout=timeout_s):
        if reply.ok is not None:
            if not empty:
                _, fields = gz.decode(reply.ok.payload.to_bytes())
                print(format_message(fields), end="")
            return 0
    if empty:
        return 0
    print("Service call timed out")
    return 1


def _call(session: Any, name: str, text: str, timeout_ms: int) -> int:
    from diffctl.gz.textproto import format_message, parse_message
    from diffctl.sim.world_client import call

    req = parse_message(text) if text.strip() else {}
    if name == "/gazebo/worlds":
        print(format_message({"data": _worlds(session)}), end="")
        return 0
    _, _, world, leaf = name.split("/", 3)
    body: dict[str, Any]
    if leaf == "control":
        body = {}
        if "pause" in req:
            body["pause"] = bool(req["pause"])
        if req.get("multi_step"):
            body["multi_step"] = int(req["multi_step"])
        elif req.get("step"):
            body["step"] = True
        if isinstance(req.get("reset"), dict) and req["reset"].get("all"):
            body["reset"] = {"all": True}
    elif leaf == "create":
        body = {k: req[k] for k in ("sdf", "sdf_filename", "name", "allow_renaming") if k in req}
        pose = req.get("pose") or {}
        pos, quat = pose.get("position") or {}, pose.get("orientation") or {}
        if pos or quat:
            from diffctl.description.pose import Pose

            q = (float(quat.get("x", 0)), float(quat.get("y", 0)), float(quat.get("z", 0)), float(quat.get("w", 1)))
            roll, pitch, yaw = Pose((0.0, 0.0, 0.0), q).rpy
            body["pose"] = {"x": pos.get("x", 0), "y": pos.get("y", 0), "z": pos.get("z", 0)}
            body["pose"].update(roll=roll, pitch=pitch, yaw=yaw)
    elif leaf == "remove":
        body = {"name": req.get("name", "")}
    else:
        body = {}
    try:
        reply = call(session, world, leaf, body, time.monotonic() + max(timeout_ms, 1) / 1000.0)
    except RuntimeFailure as e:
        print("Service call failed" if "failed" in e.message else "Service call timed out")
        return 1
    if leaf == "state":
        print(json.dumps(reply, indent=2))
    else:
        print(format_message({"data": bool(reply.get("ok"))}), end="")
    return 0


def model(rest: list[str]) -> int:
    p = _parser("gz model")
    p.add_argument("--list", action="store_true")
    p.add_argument("-m", "--model")
    p.add_argument("-p", "--pose", action="store_true")
    p.add_argument("-l", "--link", nargs="?", const="")
    p.add_argument("-j", "--joint", nargs="?", const="")
    p.add_argument("-s", "--sensor", nargs="?", const="")
    a = _parse(p, rest)
    from diffctl.sim.world_client import call

    session = _session()
    worlds = _worlds(session)
    if not worlds:
        print("\nService call to [/gazebo/worlds] timed out\n", file=sys.stderr)
        return 1
    world = worlds[0]
    print(f"\nRequesting state for world [{world}]...\n")
    state = call(session, world, "state", {}, time.monotonic() + 5.0)
    models = {m["name"]: m for m in state.get("models", [])}
    if a.list or not a.model:
        print("Available models:")
        for name in models:
            print(f"    - {name}")
        return 0
    m = models.get(a.model)
    if m is None:
        print(f"No model named <{a.model}> was found")
        return 1
    print(model_text(m, _entity_ids(list(models.values())), a.pose, a.link, a.joint, a.sensor), end="")
    return 0


def _entity_ids(models: list[dict[str, Any]]) -> dict[str, int]:
    """Entity numbers as an ECM hands them out in load order (the world is 1): each model, then its links,
    then its joints (a link's sensors after it). Keys are `model`, `model/link`, `model/link/sensor` and
    `model//joint`."""
    ids: dict[str, int] = {}
    n = 1
    for m in models:
        n += 1
        ids[m["name"]] = n
        for link in m.get("links", []):
            n += 1
            ids[f"{m['name']}/{link['name']}"] = n
            for sensor in link.get("sensors", []):
                n += 1
                ids[f"{m['name']}/{link['name']}/{sensor['name']}"] = n
        for joint in m.get("joints", []):
            n += 1
            ids[f"{m['name']}//{joint['name']}"] = n
    return ids


def _pose_lines(pose: dict[str, float], spaces: int) -> str:
    pad = " " * spaces
    return (
        f"{pad}[{pose['x']:.6f} {pose['y']:.6f} {pose['z']:.6f}]\n"
        f"{pad}[{pose['roll']:.6f} {pose['pitch']:.6f} {pose['yaw']:.6f}]\n"
    )


def _vector(values: list[float]) -> str:
    # gz-math's stream output: six significant digits, a zero as 0
    return " ".join("0" if v == 0 else f"{v:.6g}" for v in values)


def _sensor_text(lk: dict[str, Any], model: str, ids: dict[str, int], only: str, spaces: int) -> str:
    pad, pad2 = " " * spaces, " " * (spaces + 2)
    out = []
    for s in lk.get("sensors", []):
        if only and only != s["name"]:
            continue
        out.append(f"{pad}- Sensor [{ids[model + '/' + lk['name'] + '/' + s['name']]}]\n{pad2}- Name: {s['name']}\n")
        out.append(f"{pad2}- Parent: {model} [{ids[model]}]\n{pad2}- Pose [ XYZ (m) ] [ RPY (rad) ]:\n")
        out.append(_pose_lines(s["pose"], spaces + 4))
    return "".join(out)


def model_text(
    m: dict[str, Any],
    ids: dict[str, int],
    pose: bool = False,
    link: str | None = None,
    joint: str | None = None,
    sensor: str | None = None,
) -> str:
    """What gz-sim 8's `gz model -m NAME [-p] [-l [LINK]] [-j [JOINT]] [-s [SENSOR]]` prints (ModelCommandAPI.cc),
    sensors with their name, parent and pose (not their type's own details)."""
    name = m["name"]
    every = not pose and link is None and joint is None and sensor is None
    parent = f"{name} [{ids[name]}]"
    out = []
    spaces = 0
    if every or pose:
        out.append(f"Model: [{ids[name]}]\n  - Name: {name}\n  - Pose [ XYZ (m) ] [ RPY (rad) ]:\n")
        out.append(_pose_lines(m["pose"], 4))
        spaces = 2
    pad, pad2, pad4 = " " * spaces, " " * (spaces + 2), " " * (spaces + 4)
    if every or link is not None or sensor is not None:
        for lk in m.get("links", []):
            if link and link != lk["name"]:
                continue
            if sensor:  # a sensor named: no link block, at the links' indentation (bare -s lists links too)
                out.append(_sensor_text(lk, name, ids, sensor, spaces))
                continue
            out.append(f"{pad}- Link [{ids[name + '/' + lk['name']]}]\n{pad2}- Name: {lk['name']}\n")
            out.append(f"{pad2}- Parent: {parent}\n")
            if "mass" in lk:
                ixx, ixy, ixz, iyy, iyz, izz = lk["inertia"]
                out.append(f"{pad2}- Mass (kg): {lk['mass']:.6f}\n{pad2}- Inertial Pose [ XYZ (m) ] [ RPY (rad) ]:\n")
                out.append(_pose_lines(lk["inertial_pose"], spaces + 4))
                out.append(
                    f"{pad2}- Inertial Matrix (kg.m^2):\n{pad4}[{ixx:.6f} {ixy:.6f} {ixz:.6f}]\n"
                    f"{pad4}[{ixy:.6f} {iyy:.6f} {iyz:.6f}]\n{pad4}[{ixz:.6f} {iyz:.6f} {izz:.6f}]\n"
                )
            out.append(f"{pad2}- Pose [ XYZ (m) ] [ RPY (rad) ]:\n")
            out.append(_pose_lines(lk["pose"], spaces + 4))
            out.append(_sensor_text(lk, name, ids, "", spaces + 2))
    if every or joint is not None:

        def link_info(link_name: str) -> str:
            known = ids.get(f"{name}/{link_name}")
            return f"{link_name} [{known}]" if known is not None else link_name  # "world" has no link entity

        for jt in m.get("joints", []):
            if joint and joint != jt["name"]:
                continue
            out.append(f"{pad}- Joint [{ids[name + '//' + jt['name']]}]\n{pad2}- Name: {jt['name']}\n")
            out.append(f"{pad2}- Parent: {parent}\n{pad2}- Type: {jt['type']}\n")
            out.append(f"{pad2}- Parent Link: {link_info(jt['parent'])}\n")
            out.append(f"{pad2}- Child Link: {link_info(jt['child'])}\n")
            out.append(f"{pad2}- Pose [ XYZ (m) ] [ RPY (rad) ]:\n")
            out.append(_pose_lines(jt["pose"], spaces + 4))
            if jt.get("axis") is not None:
                out.append(f"{pad2}- Axis unit vector [ XYZ ]:\n{pad4}[{_vector(jt['axis'])}]\n")
    return "".join(out)


def fuel(rest: list[str]) -> int:
    p = _parser("gz fuel")
    p.add_argument("action", choices=["download"])
    p.add_argument("-u", "--url", required=True)
    a = _parse(p, rest)
    from diffctl.cli.main import main as diffctl_main

    diffctl_main(["fuel", a.action, a.url])
    return 0
