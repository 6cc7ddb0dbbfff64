"""The transform tree over time, as tf2's BufferCore: per child frame a time-sorted cache of (parent,
transform) entries (or one static entry), a walk from both frames to their common ancestor, interpolation
between the two stamps around the time asked for, and tf2's errors word for word.

Pure: times are integer nanoseconds (0 means "the latest common time"), transforms are (xyz, xyzw)
tuples; `ros_io` maps messages and rclpy times onto it.
"""

from __future__ import annotations

import threading
from dataclasses import dataclass

from diffctl.tf2 import transform_math as tm
from diffctl.tf2.exceptions import (
    ConnectivityException,
    ExtrapolationException,
    InvalidArgumentException,
    LookupException,
)

DEFAULT_CACHE_TIME_NS = 10_000_000_000
MAX_GRAPH_DEPTH = 1000
_NO_PARENT = 0
_OK, _LOOKUP, _CONNECTIVITY, _EXTRAPOLATION = range(4)


@dataclass(frozen=True)
class Entry:
    stamp_ns: int
    parent: int
    translation: tm.Vec
    rotation: tm.Quat


def display_time(ns: int) -> str:
    return f"{ns / 1e9:.6f}"


class TimeCache:
    """Entries of one child frame, newest first, kept for `max_storage_ns` behind the newest."""

    static = False

    def __init__(self, max_storage_ns: int) -> None:
        self.max_storage_ns = max_storage_ns
        self.entries: list[Entry] = []

    def insert(self, entry: Entry) -> bool:
        latest = self.entries[0].stamp_ns if self.entries else 0
        self._prune(latest)
        if self.entries and entry.stamp_ns < latest - self.max_storage_ns:
            return False
        at = next((i for i, e in enumerate(self.entries) if e.stamp_ns <= entry.stamp_ns), len(self.entries))
        same = at
        while same < len(self.entries) and self.entries[same].stamp_ns == entry.stamp_ns:
            if self.entries[same] == entry:
                return True
            same += 1
        self.entries.insert(at, entry)
        return True

    def _prune(self, latest: int) -> None:
        while self.entries and self.entries[-1].stamp_ns + self.max_storage_ns < latest:
            self.entries.pop()

    def _closest(self, time_ns: int) -> tuple[list[Entry], str]:
        """The one or two entries around `time_ns`, or [] and the extrapolation error."""
        entries = self.entries
        if not entries:
            return [], ""
        if time_ns == 0:
            return [entries[0]], ""
        if len(entries) == 1:
            if entries[0].stamp_ns == time_ns:
                return [entries[0]], ""
            return [], (
                f"Lookup would require extrapolation at time {display_time(time_ns)}, "
                f"but only time {display_time(entries[0].stamp_ns)} is in the buffer"
            )
        latest, earliest = entries[0].stamp_ns, entries[-1].stamp_ns
        if time_ns == latest:
            return [entries[0]], ""
        if time_ns == earliest:
            return [entries[-1]], ""
        if time_ns > latest:
            return [], (
                f"Lookup would require extrapolation into the future.  Requested time {display_time(time_ns)} "
                f"but the latest data is at time {display_time(latest)}"
            )
        if time_ns < earliest:
            return [], (
                f"Lookup would require extrapolation into the past.  Requested time {display_time(time_ns)} "
                f"but the earliest data is at time {display_time(earliest)}"
            )
        i = next(i for i, e in enumerate(entries) if e.stamp_ns <= time_ns)
        return [entries[i], entries[i - 1]], ""  # older, newer

    def get(self, time_ns: int) -> tuple[Entry | None, str]:
        found, error = self._closest(time_ns)
        if not found:
            return None, error
        if len(found) == 1:
            return found[0], ""
        older, newer = found
        if older.parent != newer.parent:
            return older, ""
        ratio = (time_ns - older.stamp_ns) / (newer.stamp_ns - older.stamp_ns)
        return Entry(
            older.stamp_ns,
            older.parent,
            tm.lerp(older.translation, newer.translation, ratio),
            tm.slerp(older.rotation, newer.rotation, ratio),
        ), ""

    def parent(self, time_ns: int) -> tuple[int, str]:
        found, error = self._closest(time_ns)
        return (found[0].parent, "") if found else (_NO_PARENT, error)

    def latest(self) -> tuple[int, int]:
        """(stamp, parent) of the newest entry, (0, 0) when empty."""
        return (self.entries[0].stamp_ns, self.entries[0].parent) if self.entries else (0, _NO_PARENT)

    def oldest_ns(self) -> int:
        return self.entries[-1].stamp_ns if self.entries else 0

    def __len__(self) -> int:
        return len(self.entries)


class StaticCache:
    """A /tf_static frame: one entry, valid at every time."""

    static = True

    def __init__(self) -> None:
        self.entry: Entry | None = None

    def insert(self, entry: Entry) -> bool:
        self.entry = entry
        return True

    def get(self, time_ns: int) -> tuple[Entry | None, str]:
        if self.entry is None:
            return None, ""
        e = self.entry
        return Entry(time_ns, e.parent, e.translation, e.rotation), ""

    def parent(self, time_ns: int) -> tuple[int, str]:
        return (self.entry.parent if self.entry else _NO_PARENT), ""

    def latest(self) -> tuple[int, int]:
        return (0, self.entry.parent if self.entry else _NO_PARENT)

    def oldest_ns(self) -> int:
        return 0

    def __len__(self) -> int:
        return 1 if self.entry else 0


class _Accum:
    """Accumulates source→top and target→top while walking; the result is target←source."""

    def __init__(self, transforms: bool) -> None:
        self.transforms = transforms
        self.entry: Entry | None = None
        self.src = (tm.ZERO_V, tm.IDENTITY_Q)
        self.tgt = (tm.ZERO_V, tm.IDENTITY_Q)
        self.result = (tm.ZERO_V, tm.IDENTITY_Q)
        self.time_ns = 0

    def gather(self, cache: TimeCache | StaticCache, time_ns: int) -> tuple[int, str]:
        if not self.transforms:
            return cache.parent(time_ns)
        self.entry, error = cache.get(time_ns)
        return (self.entry.parent, "") if self.entry else (_NO_PARENT, error)

    def accum(self, source_side: bool) -> None:
        if not self.transforms or self.entry is None:
            return
        e = self.entry
        if source_side:
            self.src = tm.compose(e.translation, e.rotation, *self.src)
        else:
            self.tgt = tm.compose(e.translation, e.rotation, *self.tgt)

    def finalize(self, ending: str, time_ns: int) -> None:
        self.time_ns = time_ns
        if ending == "source_below_target":
            self.result = self.src
        elif ending == "target_below_source":
            self.result = tm.invert(*self.tgt)
        elif ending == "full":
            self.result = tm.compose(*tm.invert(*self.tgt), *self.src)


class BufferCore:
    """tf2::BufferCore: thread-safe; every frame id is a name without a leading '/'."""

    def __init__(self, cache_time_ns: int = DEFAULT_CACHE_TIME_NS) -> None:
        self.cache_time_ns = cache_time_ns
        self._lock = threading.RLock()
        self._ids: dict[str, int] = {"NO_PARENT": _NO_PARENT}
        self._names: list[str] = ["NO_PARENT"]
        self._caches: list[TimeCache | StaticCache | None] = [None]
        self._authority: dict[int, str] = {}

    # --- inserting ---------------------------------------------------------------------------------------
    def set_transform(
        self,
        frame_id: str,
        child_frame_id: str,
        stamp_ns: int,
        translation: tm.Vec,
        rotation: tm.Quat,
        authority: str = "default_authority",
        is_static: bool = False,
    ) -> str | None:
        """Store one transform; returns None, or tf2's reason for ignoring it (to be logged)."""
        parent = frame_id[1:] if frame_id.startswith("/") else frame_id
        child = child_frame_id[1:] if child_frame_id.startswith("/") else child_frame_id
        errors = []
        if child == parent:
            errors.append(
                f'TF_SELF_TRANSFORM: Ignoring transform from authority "{authority}" with frame_id and  '
                f'child_frame_id "{child}" because they are the same'
            )
        if not child:
            errors.append(f'TF_NO_CHILD_FRAME_ID: Ignoring transform from authority "{authority}" because '
                          "child_frame_id not set ")
        if not parent:
            errors.append(f'TF_NO_FRAME_ID: Ignoring transform with child_frame_id "{child}"  from authority '
                          f'"{authority}" because frame_id not set')
        values = (*translation, *rotation)
        if any(v != v for v in values):
            errors.append(f'TF_NAN_INPUT: Ignoring transform for child_frame_id "{child}" from authority '
                          f'"{authority}" because of a nan value in the transform '
                          f"({translation[0]:f} {translation[1]:f} {translation[2]:f}) "
                          f"({rotation[0]:f} {rotation[1]:f} {rotation[2]:f} {rotation[3]:f})")
        elif not tm.is_normalized(rotation):
            errors.append(f'TF_DENORMALIZED_QUATERNION: Ignoring transform for child_frame_id "{child}" from '
                          f'authority "{authority}" because of an invalid quaternion in the transform '
                          f"({rotation[0]:f} {rotation[1]:f} {rotation[2]:f} {rotation[3]:f})")
        if errors:
            return "\n".join(errors)
        with self._lock:
            cid = self._id_or_insert(child)
            cache = self._caches[cid]
            if cache is None or cache.static != is_static:
                cache = StaticCache() if is_static else TimeCache(self.cache_time_ns)
                self._caches[cid] = cache
            entry = Entry(int(stamp_ns), self._id_or_insert(parent), tuple(translation), tuple(rotation))
            if not cache.insert(entry):
                return (f"TF_OLD_DATA ignoring data from the past for frame {child} at time "
                        f"{display_time(int(stamp_ns))} according to authority {authority}\n"
                        "Possible reasons are listed at http://wiki.ros.org/tf/Errors%20explained")
            self._authority[cid] = authority
        return None

    def clear(self) -> None:
        with self._lock:
            for cache in self._caches[1:]:
                if isinstance(cache, TimeCache):
                    cache.entries.clear()
                elif isinstance(cache, StaticCache):
                    cache.entry = None

    # --- looking up ---------------------------------------------------------------------------------------
    def lookup_transform(self, target: str, source: str, time_ns: int) -> tuple[int, tm.Vec, tm.Quat]:
        """(stamp, translation, rotation) of `source` expressed in `target` at `time_ns` (0: latest)."""
        with self._lock:
            if target == source:
                stamp = time_ns
                cache = self._caches[self._ids.get(target, 0)] if time_ns == 0 else None
                if cache is not None:
                    stamp = cache.latest()[0]
                return stamp, tm.ZERO_V, tm.IDENTITY_Q
            tid = self._validate("lookupTransform argument target_frame", target)
            sid = self._validate("lookupTransform argument source_frame", source)
            acc = _Accum(True)
            code, error = self._walk(acc, time_ns, tid, sid)
            if code == _CONNECTIVITY:
                raise ConnectivityException(error)
            if code == _EXTRAPOLATION:
                raise ExtrapolationException(error)
            if code == _LOOKUP:
                raise LookupException(error)
            return acc.time_ns, acc.result[0], acc.result[1]

    def lookup_transform_full(
        self, target: str, target_time_ns: int, source: str, source_time_ns: int, fixed: str
    ) -> tuple[int, tm.Vec, tm.Quat]:
        """`source` at `source_time_ns` in `target` at `target_time_ns`, through `fixed` (constant in time)."""
        self._validate("lookupTransform argument target_frame", target)
        self._validate("lookupTransform argument source_frame", source)
        self._validate("lookupTransform argument fixed_frame", fixed)
        _, t1, q1 = self.lookup_transform(fixed, source, source_time_ns)
        stamp, t2, q2 = self.lookup_transform(target, fixed, target_time_ns)
        t, q = tm.compose(t2, q2, t1, q1)
        return stamp, t, q

    def can_transform(self, target: str, source: str, time_ns: int) -> tuple[bool, str]:
        if target == source:
            return True, ""
        with self._lock:
            for arg, frame in (("canTransform argument target_frame", target),
                               ("canTransform argument source_frame", source)):
                error = self._invalid_frame(arg, frame)
                if error:
                    return False, error
            return self._can(self._ids[target], self._ids[source], time_ns)

    def can_transform_full(
        self, target: str, target_time_ns: int, source: str, source_time_ns: int, fixed: str
    ) -> tuple[bool, str]:
        with self._lock:
            for arg, frame in (("canTransform argument target_frame", target),
                               ("canTransform argument source_frame", source),
                               ("canTransform argument fixed_frame", fixed)):
                error = self._invalid_frame(arg, frame)
                if error:
                    return False, error
            ok, error = self._can(self._ids[target], self._ids[fixed], target_time_ns)
            if not ok:
                return ok, error
            return self._can(self._ids[fixed], self._ids[source], source_time_ns)

    def latest_common_time(self, target: str, source: str) -> int:
        with self._lock:
            tid = self._validate("get_latest_common_time argument target_frame", target)
            sid = self._validate("get_latest_common_time argument source_frame", source)
            code, error, time_ns = self._latest_common_time(tid, sid)
            if code == _CONNECTIVITY:
                raise ConnectivityException(error)
            if code != _OK:
                raise LookupException(error)
            return time_ns

    def frame_names(self) -> list[str]:
        with self._lock:
            return list(self._names[1:])

    def frame_exists(self, frame: str) -> bool:
        with self._lock:
            return frame in self._ids and frame != "NO_PARENT"

    def parent_of(self, frame: str, time_ns: int = 0) -> str | None:
        with self._lock:
            cache = self._caches[self._ids[frame]] if frame in self._ids else None
            if cache is None:
                return None
            parent, _ = cache.parent(time_ns)
            return self._names[parent] if parent else None

    def all_frames_as_string(self) -> str:
        with self._lock:
            lines = []
            for cid in range(1, len(self._caches)):
                cache = self._caches[cid]
                if cache is None:
                    continue
                entry, _ = cache.get(0)
                parent = entry.parent if entry else 0
                lines.append(f"Frame {self._names[cid]} exists with parent {self._names[parent]}.\n")
            return "".join(lines)

    def all_frames_as_yaml(self, current_time_ns: int = 0) -> str:
        with self._lock:
            out = []
            for cid in range(1, len(self._caches)):
                cache = self._caches[cid]
                entry = cache.get(0)[0] if cache is not None else None
                if cache is None or entry is None:
                    continue
                latest, oldest = cache.latest()[0], cache.oldest_ns()
                span = max(latest - oldest, 100_000)
                rate = len(cache) * 1e9 / span
                out.append(f"{self._names[cid]}: \n")
                out.append(f"  parent: '{self._names[entry.parent]}'\n")
                out.append(f"  broadcaster: '{self._authority.get(cid, 'no recorded authority')}'\n")
                out.append(f"  rate: {rate:.3f}\n")
                out.append(f"  most_recent_transform: {display_time(latest)}\n")
                out.append(f"  oldest_transform: {display_time(oldest)}\n")
                if current_time_ns:
                    out.append(f"  transform_delay: {(current_time_ns - latest) / 1e9:.3f}\n")
                out.append(f"  buffer_length: {(latest - oldest) / 1e9:.3f}\n")
            return "".join(out) if out else "[]"

    # --- the walk ---------------------------------------------------------------------------------------------
    def _id_or_insert(self, name: str) -> int:
        fid = self._ids.get(name)
        if fid is None:
            fid = len(self._names)
            self._ids[name] = fid
            self._names.append(name)
            self._caches.append(None)
        return fid

    def _validate(self, arg: str, frame: str) -> int:
        if not frame:
            raise InvalidArgumentException(
                f'Invalid argument "{frame}" passed to {arg} - in tf2 frame_ids cannot be empty')
        if frame.startswith("/"):
            raise InvalidArgumentException(
                f"Invalid argument \"{frame}\" passed to {arg} - in tf2 frame_ids cannot start with a '/'")
        fid = self._ids.get(frame, 0)
        if fid == 0:
            raise LookupException(f'"{frame}" passed to {arg} does not exist. ')
        return fid

    def _invalid_frame(self, arg: str, frame: str) -> str:
        why = ""
        if not frame:
            why = "in tf2 frame_ids cannot be empty"
        elif frame.startswith("/"):
            why = "in tf2 frame_ids cannot start with a '/'"
        elif self._ids.get(frame, 0) == 0:
            why = "frame does not exist"
        return f'Invalid frame ID "{frame}" passed to {arg} - {why}' if why else ""

    def _can(self, tid: int, sid: int, time_ns: int) -> tuple[bool, str]:
        if tid == sid:
            return True, ""
        code, error = self._walk(_Accum(False), time_ns, tid, sid)
        return code == _OK, error

    def _connectivity_error(self, sid: int, tid: int) -> str:
        return (f"Could not find a connection between '{self._names[tid]}' and '{self._names[sid]}' because "
                "they are not part of the same tree.Tf has two or more unconnected trees.")

    def _loop_error(self) -> str:
        return "The tf tree is invalid because it contains a loop.\n" + self.all_frames_as_string() + "\n"

    def _walk(self, acc: _Accum, time_ns: int, tid: int, sid: int) -> tuple[int, str]:
        if sid == tid:
            acc.finalize("identity", time_ns)
            return _OK, ""
        if time_ns == 0:
            code, error, time_ns = self._latest_common_time(tid, sid)
            if code != _OK:
                return code, error
        # From the source up to its root.
        frame, top, depth = sid, sid, 0
        extrapolation_error: str | None = None  # set when the source's chain ended at missing data
        while frame != _NO_PARENT:
            cache = self._caches[frame]
            if cache is None:
                top = frame
                break
            parent, error = acc.gather(cache, time_ns)
            if parent == _NO_PARENT:
                top = frame
                extrapolation_error = error
                break
            if frame == tid:
                acc.finalize("source_below_target", time_ns)
                return _OK, ""
            acc.accum(True)
            top, frame = frame, parent
            depth += 1
            if depth > MAX_GRAPH_DEPTH:
                return _LOOKUP, self._loop_error()
        # From the target up to the source's root.
        frame, depth = tid, 0
        while frame != top:
            cache = self._caches[frame]
            if cache is None:
                break
            parent, error = acc.gather(cache, time_ns)
            if parent == _NO_PARENT:
                return _EXTRAPOLATION, (f"{error}, when looking up transform from frame [{self._names[sid]}] "
                                        f"to frame [{self._names[tid]}]")
            if frame == sid:
                acc.finalize("target_below_source", time_ns)
                return _OK, ""
            acc.accum(False)
            frame = parent
            depth += 1
            if depth > MAX_GRAPH_DEPTH:
                return _LOOKUP, self._loop_error()
        if frame != top:
            if extrapolation_error is not None:
                return _EXTRAPOLATION, (f"{extrapolation_error}, when looking up "
                                        f"transform from frame [{self._names[sid]}] to frame [{self._names[tid]}]")
            return _CONNECTIVITY, self._connectivity_error(sid, tid)
        acc.finalize("full", time_ns)
        return _OK, ""

    def _latest_common_time(self, tid: int, sid: int) -> tuple[int, str, int]:
        if sid == 0 or tid == 0:
            return _LOOKUP, "", 0
        if sid == tid:
            cache = self._caches[sid]
            return _OK, "", cache.latest()[0] if cache is not None else 0
        never = 1 << 63
        chain: list[tuple[int, int]] = []
        frame, depth, common = sid, 0, never
        while frame != _NO_PARENT:
            cache = self._caches[frame]
            if cache is None:
                break
            stamp, parent = cache.latest()
            if parent == _NO_PARENT:
                break
            if stamp != 0:
                common = min(common, stamp)
            chain.append((stamp, parent))
            frame = parent
            if frame == tid:
                return _OK, "", 0 if common == never else common
            depth += 1
            if depth > MAX_GRAPH_DEPTH:
                return _LOOKUP, self._loop_error(), 0
        frame, depth, common, common_parent = tid, 0, never, _NO_PARENT
        parents = {p for _, p in chain}
        while True:
            cache = self._caches[frame]
            if cache is None:
                break
            stamp, parent = cache.latest()
            if parent == _NO_PARENT:
                break
            if stamp != 0:
                common = min(common, stamp)
            if parent in parents:
                common_parent = parent
                break
            frame = parent
            if frame == sid:
                return _OK, "", 0 if common == never else common
            depth += 1
            if depth > MAX_GRAPH_DEPTH:
                return _LOOKUP, self._loop_error(), 0
        if common_parent == _NO_PARENT:
            return _CONNECTIVITY, self._connectivity_error(sid, tid), 0
        for stamp, parent in chain:
            if stamp != 0:
                common = min(common, stamp)
            if parent == common_parent:
                break
        return _OK, "", 0 if common == never else common
