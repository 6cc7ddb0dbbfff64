"""World services and statistics, as Gazebo's UserCommands and WorldStatistics offer them, on Zenoh.

Queryables under `gz/world/<world>/`, JSON in and out; every answer has "ok" (and "error" when false):
  control  {"pause": true|false} | {"multi_step": N} | {"step": true} | {"reset": {"all": true}} | {"rtf": X}
           → {"ok", "paused", "sim_time_ns", "iterations"}; a step request answers once the steps are done
             (it pauses first, as Gazebo's step button does)
  create   {"name", "sdf": "<sdf…>" | "sdf_filename": "/abs/path.sdf", "pose": {"x","y","z","roll","pitch","yaw"},
            "allow_renaming": false, "base_dir": "/dir for relative URIs"} → {"ok", "name", "ignored": [...]}
  remove   {"name"} → {"ok"}
gz service `/world/<world>/set_pose` (gz.msgs.Pose → gz.msgs.Boolean, as UserCommands): a model by name moved
  to the pose (in the world; a missing orientation is the identity), joints and velocities as they were.
  state    {} → {"ok", "world", "paused", "sim_time_ns", "iterations", "rtf_target", "models": [{"name",
            "static", "pose": P, "ros2_control": bool, "links": [{"name", "pose" (in the model frame, now),
            "mass", "inertial_pose", "inertia": [ixx, ixy, ixz, iyy, iyz, izz], "sensors": [{"name", "type",
            "pose" (in the link frame)}]}], "joints": [{"name", "type",
            "parent", "child", "pose" (in the child link's frame), "axis" (in the joint frame, or null)}]}]}
           where P = {"x","y","z","roll","pitch","yaw"}
Liveliness token `gz/world/<world>/sim` while the simulator runs (spawners wait for it).
Topic `/world/<world>/stats` (gz.msgs.WorldStatistics, 5 Hz of wall time, also while paused), with extras:
  {"sim_time", "real_time", "pause_time", "iterations", "paused", "real_time_factor", "step_size",
   "step_time_us" (mean wall time of one step and its bookkeeping), "model_count"}.
"""

from __future__ import annotations

import dataclasses
import math
import os
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pybullet as pb

from diffctl.bus import gz
from diffctl.description.model import Model
from diffctl.description.pose import Pose
from diffctl.description.robot_files import parse_description, read_description_text
from diffctl.errors import DiffctlError, RuntimeFailure
from diffctl.sim.plugins.gz_ros2_control import PreparedManager
from diffctl.sim.runner import Simulation
from diffctl.sim.transport import Reply
from diffctl.sim.world_keys import sim_token_key, world_key

STATS_PERIOD_S = 0.2
ROUTER_GRACE_S = 1.0
MAX_MULTI_STEP = 10_000_000
# Where `_prepare_create` leaves its work in a create request: not a string, so no JSON key can collide.
_PREPARED = object()


class WorldServices:
    def __init__(self, sim: Simulation, on_router_lost: Callable[[], None] | None = None) -> None:
        self.sim = sim
        self.on_router_lost = on_router_lost
        self._router_lost_since: float | None = None
        t = sim.transport
        assert t is not None
        w = sim.name
        self._stats_pub = t.publisher(f"/world/{w}/stats", "gz.msgs.WorldStatistics")
        t.service(world_key(w, "control"), self.control)
        t.service(world_key(w, "create"), self.create, fast=self._prepare_create)
        t.service(world_key(w, "remove"), self.remove)
        t.service(world_key(w, "state"), lambda req, reply: self.state())
        t.gz_service(f"/world/{w}/set_pose", "gz.msgs.Pose", "gz.msgs.Boolean", self.set_pose)
        t.token(sim_token_key(w))
        self._window = (time.perf_counter(), sim.stepper.sim_time_ns, 0, 0.0)
        self._rtf = 0.0
        self._step_us = 0.0
        sim.stepper.add_task("stats", 10_000_000, lambda _t: self._maybe_publish())
        sim.stepper.idle_hooks.append(self._maybe_publish)

    # --- services (sim thread) -----------------------------------------------------------------------

    def control(self, req: dict[str, Any], reply: Reply) -> dict[str, Any] | None:
        st = self.sim.stepper
        if "rtf" in req:
            rtf = req["rtf"]
            if not isinstance(rtf, int | float) or isinstance(rtf, bool) or not math.isfinite(rtf) or rtf < 0:
                return {"ok": False, "error": f"rtf {rtf!r} must be a number >= 0 (0 = as fast as possible)"}
            st.set_rtf(float(rtf))
        reset = req.get("reset")
        if reset:
            self.sim.reset()
        if "pause" in req:
            st.set_paused(bool(req["pause"]))
        steps = req.get("multi_step", 1 if req.get("step") else 0)
        if steps:
            if not isinstance(steps, int) or isinstance(steps, bool) or not 0 < steps <= MAX_MULTI_STEP:
                return {"ok": False, "error": f"multi_step {steps!r} must be an integer in 1..{MAX_MULTI_STEP}"}
            st.set_paused(True)
            reply.defer()
            st.step_n(steps, lambda: reply.send(self._status()))
            return None
        return self._status()

    def _prepare_create(self, req: dict[str, Any]) -> dict[str, Any] | None:
        """A create request's work that needs no simulator state, on the request's own thread before the sim
        thread sees it: the description read (a xacro file expanded), parsed, and its controller manager's
        node built: in a spawn of the tutorial's car, 40-45 ms of the 84-104 ms the loop otherwise stood
        still (fresh simulator with the fork server's warm-up). The spawn is no faster for it (the same work
        under one GIL), but sim time, /clock and the other models go on meanwhile, and a xacro file's
        expansion never stops the loop. An error answers at once; what was built rides in the request to
        `create`."""
        try:
            parsed = self._parse(req)
            if isinstance(parsed, dict):
                return parsed
            model, description = parsed
            req[_PREPARED] = (model, description, self.sim.prepare_manager(model, description))
        except DiffctlError as e:
            return {"ok": False, "error": str(e)}
        except Exception as e:  # a bug must not reach the transport's thread; the caller gets the reason
            self.sim.log.error(f"create failed: {type(e).__name__}: {e}")
            return {"ok": False, "error": f"{type(e).__name__}: {e}"}
        return None

    @staticmethod
    def _parse(req: dict[str, Any]) -> tuple[Model, str] | dict[str, Any]:
        """(model, description text) of a create request, or the refusal."""
        name = req.get("name")
        if name is not None and (not isinstance(name, str) or not name):
            return {"ok": False, "error": f"name {name!r} must be a non-empty string"}
        pose = _pose_from(req.get("pose"))
        base_dir = req.get("base_dir")
        if req.get("sdf_filename"):
            path = Path(str(req["sdf_filename"]))
            if not path.is_file():
                return {"ok": False, "error": f"{path}: no such file"}
            description = read_description_text(path)  # a xacro file expands first, for the model and the manager
            model = parse_description(
                description, source=str(path), name=name, pose=pose, base_dir=path.resolve().parent
            )
        elif req.get("sdf"):
            description = str(req["sdf"])
            model = parse_description(description, source="robot_description", name=name, pose=pose, base_dir=base_dir)
        else:
            return {"ok": False, "error": "give the model as 'sdf' (text) or 'sdf_filename' (a path)"}
        return model, description

    def create(self, req: dict[str, Any], reply: Reply) -> dict[str, Any]:
        prepared: PreparedManager | None = None
        if _PREPARED in req:
            model, description, prepared = req.pop(_PREPARED)
        else:  # called without the transport's hook (in-process callers)
            parsed = self._parse(req)
            if isinstance(parsed, dict):
                return parsed
            model, description = parsed
        try:
            if model.name in self.sim.models:
                if not req.get("allow_renaming"):
                    raise RuntimeFailure(
                        f"an entity named {model.name!r} already exists in world {self.sim.name!r}",
                        hint="choose another --name, or remove it first",
                    )
                model = _renamed(model, self.sim.models)
            self.sim.spawn(model, description, prepared)
        except BaseException:
            if prepared is not None:
                prepared.close()  # nothing if the model's plugin adopted it (the spawn's cleanup closed it)
            raise
        ignored = self.sim.model_ignored(model)
        self.sim.log.info(f"spawned {model.name!r}")
        if ignored:
            self.sim.log.warn(f"model {model.name!r}: ignored (not simulated): {'; '.join(ignored)}")
        return {"ok": True, "name": model.name, "ignored": ignored}

    def remove(self, req: dict[str, Any], reply: Reply) -> dict[str, Any]:
        name = req.get("name")
        if not isinstance(name, str) or not name:
            return {"ok": False, "error": f"name {name!r} must be a non-empty string"}
        self.sim.remove(name)
        self.sim.log.info(f"removed {name!r}")
        return {"ok": True}

    def set_pose(self, req: dict[str, Any]) -> dict[str, Any]:
        """UserCommands' set_pose for models: every PyBullet body of the model moved rigidly, so the joints
        between them keep their angles; false for a name that is no model (links and lights are not moved)."""
        rt = self.sim.models.get(str(req.get("name", "")))
        if rt is None:
            return {"data": False}
        pos, q = req.get("position") or {}, req.get("orientation") or {}
        quat = tuple(float(q.get(k, 0.0)) for k in "xyzw")
        norm = math.sqrt(sum(c * c for c in quat))
        quat = (0.0, 0.0, 0.0, 1.0) if norm < 1e-12 else tuple(c / norm for c in quat)
        target = Pose(tuple(float(pos.get(k, 0.0)) for k in "xyz"), quat)
        entity = rt.entity
        move = target.compose(entity.pose().inverse())
        for body in dict.fromkeys(entity.bodies):
            xyz, orn = pb.getBasePositionAndOrientation(body, physicsClientId=entity.client)
            moved = move.compose(Pose(tuple(xyz), tuple(orn)))
            pb.resetBasePositionAndOrientation(body, moved.xyz, moved.quat, physicsClientId=entity.client)
        return {"data": True}

    def state(self) -> dict[str, Any]:
        models = []
        for name, rt in self.sim.models.items():
            p = rt.entity.pose()
            r = p.rpy
            models.append(
                {
                    "name": name,
                    "static": rt.entity.model.static,
                    "pose": {"x": p.xyz[0], "y": p.xyz[1], "z": p.xyz[2], "roll": r[0], "pitch": r[1], "yaw": r[2]},
                    "ros2_control": rt.control is not None,
                    "links": _links(rt.entity, p),
                    "joints": _joints(rt.entity.model),
                }
            )
        return {**self._status(), "world": self.sim.name, "rtf_target": self.sim.stepper.rtf, "models": models}

    def _status(self) -> dict[str, Any]:
        st = self.sim.stepper
        return {"ok": True, "paused": st.paused, "sim_time_ns": st.sim_time_ns, "iterations": st.stats.iterations}

    # --- statistics ----------------------------------------------------------------------------------

    def _maybe_publish(self) -> None:
        now = time.perf_counter()
        wall0, sim0, it0, idle0 = self._window
        dt = now - wall0
        if dt < STATS_PERIOD_S:
            return
        st = self.sim.stepper
        steps = max(0, st.stats.iterations - it0)  # a reset restarts the count
        busy = max(0.0, dt - (st.stats.idle_s - idle0))
        self._rtf = (st.sim_time_ns - sim0) * 1e-9 / dt if st.sim_time_ns >= sim0 else 0.0
        self._step_us = busy / steps * 1e6 if steps else 0.0
        self._window = (now, st.sim_time_ns, st.stats.iterations, st.stats.idle_s)
        if self._stats_pub.matched:
            self._stats_pub.publish(self.message())
        self._watch_router(now)

    def _watch_router(self, now: float) -> None:
        """Stop when the router is gone for a second, as every node does (nothing could reach the sim)."""
        if self.on_router_lost is None or os.environ.get("ZENOH_SESSION_CONFIG_URI"):
            return
        t = self.sim.transport
        assert t is not None
        if t.session.info.routers_zid():
            self._router_lost_since = None
        elif self._router_lost_since is None:
            self._router_lost_since = now
        elif now - self._router_lost_since > ROUTER_GRACE_S:
            self.on_router_lost()
            self.on_router_lost = None

    def message(self) -> dict[str, Any]:
        st = self.sim.stepper
        real_ns = int((time.perf_counter() - st.stats.wall_start_s) * 1e9)
        return {
            "header": gz.header(st.sim_time_ns),
            "sim_time": gz.stamp(st.sim_time_ns),
            "real_time": gz.stamp(real_ns),
            "pause_time": gz.stamp(0),
            "iterations": st.stats.iterations,
            "paused": st.paused,
            "real_time_factor": round(self._rtf, 4),
            "step_size": gz.stamp(st.step_ns),
            "step_time_us": round(self._step_us, 3),
            "model_count": len(self.sim.models),
        }


def _pose_from(d: Any) -> Pose | None:
    if d is None:
        return None
    if not isinstance(d, dict):
        raise RuntimeFailure(f"pose {d!r} must be an object with x, y, z, roll, pitch, yaw")
    vals = []
    for k in ("x", "y", "z", "roll", "pitch", "yaw"):
        v = d.get(k, 0.0)
        if not isinstance(v, int | float) or isinstance(v, bool) or not math.isfinite(v) or abs(v) > 1e6:
            raise RuntimeFailure(f"pose {k} {v!r} must be a finite number (|value| <= 1e6)")
        vals.append(float(v))
    return Pose.from_xyz_rpy(vals[:3], vals[3:])


def _renamed(model: Any, taken: dict[str, Any]) -> Any:
    i = 1
    while f"{model.name}_{i}" in taken:
        i += 1
    return dataclasses.replace(model, name=f"{model.name}_{i}")


def _pose6(p: Pose) -> dict[str, float]:
    r = p.rpy
    return {"x": p.xyz[0], "y": p.xyz[1], "z": p.xyz[2], "roll": r[0], "pitch": r[1], "yaw": r[2]}


def _links(entity: Any, model_pose: Pose) -> list[dict[str, Any]]:
    """Each link as `gz model -m` shows it: its pose in the model frame where physics has it now."""
    out = []
    to_model = model_pose.inverse()
    for link in entity.model.links:
        try:
            pose = to_model.compose(entity.link_pose(link.name))
        except KeyError:  # a link physics does not carry on its own: where the description puts it
            pose = link.pose_model
        entry: dict[str, Any] = {
            "name": link.name,
            "pose": _pose6(pose),
            "sensors": [{"name": s.name, "type": s.sdf_type, "pose": _pose6(s.pose_link)} for s in link.sensors],
        }
        if link.inertial is not None:
            i = link.inertial
            entry.update(
                mass=i.mass_kg,
                inertial_pose=_pose6(i.pose_link),
                inertia=[i.ixx, i.ixy, i.ixz, i.iyy, i.iyz, i.izz],
            )
        out.append(entry)
    return out


def _joints(model: Model) -> list[dict[str, Any]]:
    out = []
    for j in model.joints:
        # SDF's <axis><xyz> is in the joint frame by default; the description keeps it in the child's
        axis = j.pose_child.inverse().rotate(j.axis_child) if j.axis_child is not None else None
        out.append(
            {
                "name": j.name,
                "type": j.type,
                "parent": j.parent,
                "child": j.child,
                "pose": _pose6(j.pose_child),
                "axis": list(axis) if axis is not None else None,
            }
        )
    return out
