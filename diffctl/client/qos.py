"""rclpy.qos: QoSProfile, its policy enums, the preset profiles, and the compatibility check.

`to_wire` maps a profile onto what the bus declares (rmw_zenoh's adapted profile in the liveliness token,
transient local as Zenoh's advanced publisher cache); `from_wire` reads a token's profile back.
"""

from __future__ import annotations

import enum
import warnings
from typing import Any

from diffctl.bus import wire
from diffctl.client.duration import Duration
from diffctl.client.exceptions import InvalidQoSProfileException

RMW_DURATION_INFINITE = 2**63 - 1
RMW_QOS_DEADLINE_BEST_AVAILABLE = 2**63 - 2


class QoSPolicyKind(enum.IntEnum):
    INVALID = 1 << 0
    DURABILITY = 1 << 1
    DEADLINE = 1 << 2
    LIVELINESS = 1 << 3
    RELIABILITY = 1 << 4
    HISTORY = 1 << 5
    LIFESPAN = 1 << 6
    DEPTH = 1 << 7
    LIVELINESS_LEASE_DURATION = 1 << 8
    AVOID_ROS_NAMESPACE_CONVENTIONS = 1 << 9


def qos_policy_name_from_kind(policy_kind: QoSPolicyKind | int) -> str:
    return QoSPolicyKind(policy_kind).name


class QoSPolicyEnum(enum.IntEnum):
    @classmethod
    def short_keys(cls) -> list[str]:
        return [k.lower() for k in cls.__members__ if not k.startswith("RMW")]

    @classmethod
    def get_from_short_key(cls, name: str) -> int:
        return cls[name.upper()].value

    @property
    def short_key(self) -> str:
        return self.name.lower()


class HistoryPolicy(QoSPolicyEnum):
    SYSTEM_DEFAULT = 0
    KEEP_LAST = 1
    KEEP_ALL = 2
    UNKNOWN = 3


class ReliabilityPolicy(QoSPolicyEnum):
    SYSTEM_DEFAULT = 0
    RELIABLE = 1
    BEST_EFFORT = 2
    UNKNOWN = 3
    BEST_AVAILABLE = 4


class DurabilityPolicy(QoSPolicyEnum):
    SYSTEM_DEFAULT = 0
    TRANSIENT_LOCAL = 1
    VOLATILE = 2
    UNKNOWN = 3
    BEST_AVAILABLE = 4


class LivelinessPolicy(QoSPolicyEnum):
    SYSTEM_DEFAULT = 0
    AUTOMATIC = 1
    MANUAL_BY_TOPIC = 3
    UNKNOWN = 4
    BEST_AVAILABLE = 5


QoSHistoryPolicy = HistoryPolicy
QoSReliabilityPolicy = ReliabilityPolicy
QoSDurabilityPolicy = DurabilityPolicy
QoSLivelinessPolicy = LivelinessPolicy

_SLOTS = ("_history", "_depth", "_reliability", "_durability", "_lifespan", "_deadline", "_liveliness",
          "_liveliness_lease_duration", "_avoid_ros_namespace_conventions")


class QoSProfile:
    """A QoS profile; `QoSProfile(depth=10)` or the keyword form, unset policies as rmw's default profile."""

    __slots__ = _SLOTS

    def __init__(self, **kwargs: Any) -> None:
        assert all("_" + key in _SLOTS for key in kwargs), f"Invalid arguments passed to constructor: {kwargs.keys()!r}"
        if "history" not in kwargs:
            if "depth" not in kwargs:
                raise InvalidQoSProfileException("History and/or depth settings are required.")
            kwargs["history"] = HistoryPolicy.KEEP_LAST
        self.history = kwargs["history"]
        if self.history == HistoryPolicy.KEEP_LAST and "depth" not in kwargs:
            raise InvalidQoSProfileException("History set to KEEP_LAST without a depth setting.")
        self.depth = kwargs.get("depth", 10)
        self.reliability = kwargs.get("reliability", ReliabilityPolicy.RELIABLE)
        self.durability = kwargs.get("durability", DurabilityPolicy.VOLATILE)
        self.lifespan = kwargs.get("lifespan", Duration())
        self.deadline = kwargs.get("deadline", Duration())
        self.liveliness = kwargs.get("liveliness", LivelinessPolicy.SYSTEM_DEFAULT)
        self.liveliness_lease_duration = kwargs.get("liveliness_lease_duration", Duration())
        self.avoid_ros_namespace_conventions = kwargs.get("avoid_ros_namespace_conventions", False)

    @property
    def history(self) -> HistoryPolicy:
        return self._history

    @history.setter
    def history(self, value: Any) -> None:
        assert isinstance(value, (HistoryPolicy, int))
        self._history = HistoryPolicy(value)

    @property
    def reliability(self) -> ReliabilityPolicy:
        return self._reliability

    @reliability.setter
    def reliability(self, value: Any) -> None:
        assert isinstance(value, (ReliabilityPolicy, int))
        self._reliability = ReliabilityPolicy(value)

    @property
    def durability(self) -> DurabilityPolicy:
        return self._durability

    @durability.setter
    def durability(self, value: Any) -> None:
        assert isinstance(value, (DurabilityPolicy, int))
        self._durability = DurabilityPolicy(value)

    @property
    def depth(self) -> int:
        return self._depth

    @depth.setter
    def depth(self, value: int) -> None:
        assert isinstance(value, int)
        if self.history == HistoryPolicy.KEEP_LAST and value == 0:
            warnings.warn("A zero depth with KEEP_LAST doesn't make sense; no data could be stored. "
                          "This will be interpreted as SYSTEM_DEFAULT", stacklevel=2)
        self._depth = value

    @property
    def lifespan(self) -> Duration:
        return self._lifespan

    @lifespan.setter
    def lifespan(self, value: Duration) -> None:
        assert isinstance(value, Duration)
        self._lifespan = value

    @property
    def deadline(self) -> Duration:
        return self._deadline

    @deadline.setter
    def deadline(self, value: Duration) -> None:
        assert isinstance(value, Duration)
        self._deadline = value

    @property
    def liveliness(self) -> LivelinessPolicy:
        return self._liveliness

    @liveliness.setter
    def liveliness(self, value: Any) -> None:
        assert isinstance(value, (LivelinessPolicy, int))
        self._liveliness = LivelinessPolicy(value)

    @property
    def liveliness_lease_duration(self) -> Duration:
        return self._liveliness_lease_duration

    @liveliness_lease_duration.setter
    def liveliness_lease_duration(self, value: Duration) -> None:
        assert isinstance(value, Duration)
        self._liveliness_lease_duration = value

    @property
    def avoid_ros_namespace_conventions(self) -> bool:
        return self._avoid_ros_namespace_conventions

    @avoid_ros_namespace_conventions.setter
    def avoid_ros_namespace_conventions(self, value: bool) -> None:
        assert isinstance(value, bool)
        self._avoid_ros_namespace_conventions = value

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, QoSProfile):
            return False
        return all(getattr(self, s) == getattr(other, s) for s in _SLOTS)

    __hash__ = None  # type: ignore[assignment]

    def __str__(self) -> str:
        return f"{type(self).__name__}(" + ", ".join(f"{s[1:]}={getattr(self, s)}" for s in _SLOTS) + ")"

    __repr__ = __str__


def _profile(history: int, depth: int, reliability: int, durability: int, *, liveliness: int = 0,
             deadline_ns: int = 0, lease_ns: int = 0) -> QoSProfile:
    return QoSProfile(history=history, depth=depth, reliability=reliability, durability=durability,
                      liveliness=liveliness, deadline=Duration(nanoseconds=deadline_ns),
                      liveliness_lease_duration=Duration(nanoseconds=lease_ns))


with warnings.catch_warnings():
    warnings.simplefilter("ignore")  # the system-default and unknown profiles have depth 0 by definition
    qos_profile_unknown = _profile(3, 0, 3, 3, liveliness=4)
    qos_profile_default = _profile(1, 10, 1, 2)
    qos_profile_system_default = _profile(0, 0, 0, 0)
    qos_profile_sensor_data = _profile(1, 5, 2, 2)
    qos_profile_services_default = _profile(1, 10, 1, 2)
    qos_profile_parameters = _profile(1, 1000, 1, 2)
    qos_profile_parameter_events = _profile(1, 1000, 1, 2)
    qos_profile_best_available = _profile(1, 10, 4, 4, liveliness=5, deadline_ns=RMW_QOS_DEADLINE_BEST_AVAILABLE,
                                          lease_ns=RMW_QOS_DEADLINE_BEST_AVAILABLE)
    qos_profile_action_status_default = _profile(1, 1, 1, 1)
    qos_profile_rosout_default = QoSProfile(history=1, depth=1000, reliability=1, durability=1,
                                            lifespan=Duration(seconds=10))
DeadlineBestAvailable = Duration(nanoseconds=RMW_QOS_DEADLINE_BEST_AVAILABLE)
LivelinessLeaseDurationeBestAvailable = Duration(nanoseconds=RMW_QOS_DEADLINE_BEST_AVAILABLE)


class QoSPresetProfiles(enum.Enum):
    UNKNOWN = qos_profile_unknown
    DEFAULT = qos_profile_default
    SYSTEM_DEFAULT = qos_profile_system_default
    SENSOR_DATA = qos_profile_sensor_data
    SERVICES_DEFAULT = qos_profile_services_default
    PARAMETERS = qos_profile_parameters
    PARAMETER_EVENTS = qos_profile_parameter_events
    ACTION_STATUS_DEFAULT = qos_profile_action_status_default
    BEST_AVAILABLE = qos_profile_best_available

    @classmethod
    def short_keys(cls) -> list[str]:
        return [k.lower() for k in cls.__members__]

    @classmethod
    def get_from_short_key(cls, name: str) -> QoSProfile:
        return cls[name.upper()].value


class QoSCompatibility(enum.IntEnum):
    OK = 0
    WARNING = 1
    ERROR = 2


def _finite(d: Duration) -> bool:
    return 0 < d.nanoseconds < RMW_QOS_DEADLINE_BEST_AVAILABLE


def incompatible_policies(pub: QoSProfile, sub: QoSProfile) -> list[tuple[QoSPolicyKind, str]]:
    """The policies that make `pub` and `sub` incompatible, with rmw's reason for each."""
    out: list[tuple[QoSPolicyKind, str]] = []
    if pub.reliability == ReliabilityPolicy.BEST_EFFORT and sub.reliability == ReliabilityPolicy.RELIABLE:
        out.append((QoSPolicyKind.RELIABILITY, "ERROR: Best effort publisher and reliable subscription;"))
    if pub.durability == DurabilityPolicy.VOLATILE and sub.durability == DurabilityPolicy.TRANSIENT_LOCAL:
        out.append((QoSPolicyKind.DURABILITY, "ERROR: Volatile publisher and transient local subscription;"))
    if _finite(sub.deadline) and not _finite(pub.deadline):
        out.append((QoSPolicyKind.DEADLINE, "ERROR: Subscription has a deadline, but publisher does not;"))
    elif _finite(sub.deadline) and _finite(pub.deadline) and sub.deadline < pub.deadline:
        out.append((QoSPolicyKind.DEADLINE, "ERROR: Subscription deadline is less than publisher deadline;"))
    if pub.liveliness == LivelinessPolicy.AUTOMATIC and sub.liveliness == LivelinessPolicy.MANUAL_BY_TOPIC:
        out.append((QoSPolicyKind.LIVELINESS,
                    "ERROR: Publisher's liveliness is automatic and subscription's is manual by topic;"))
    # rmw checks the lease as its own policy; DDS (and so the event's kind) counts it under LIVELINESS.
    pub_lease, sub_lease = _lease_ns(pub), _lease_ns(sub)
    if sub_lease and not pub_lease:
        out.append((QoSPolicyKind.LIVELINESS,
                    "ERROR: Subscription has a liveliness lease duration, but publisher does not;"))
    elif sub_lease and pub_lease and sub_lease < pub_lease:
        out.append((QoSPolicyKind.LIVELINESS, "ERROR: Subscription liveliness lease duration is less than publisher;"))
    return out


def _lease_ns(profile: QoSProfile) -> int:
    """The lease in ns, 0 when left to the default (rmw's "no lease duration")."""
    ns = profile.liveliness_lease_duration.nanoseconds
    return 0 if ns == RMW_QOS_DEADLINE_BEST_AVAILABLE else ns


def _unknown(policy: Any) -> bool:
    return policy.name in ("SYSTEM_DEFAULT", "UNKNOWN")


def _warnings(pub: QoSProfile, sub: QoSProfile) -> str:
    """rmw_qos_profile_check_compatible's warnings: policies left to the system (or unknown) on either side."""
    out = []
    pr, sr = pub.reliability, sub.reliability
    if _unknown(pr) and _unknown(sr):
        out.append(f"WARNING: Publisher reliability is {pr.short_key} and subscription reliability is "
                   f"{sr.short_key};")
    elif _unknown(pr) and sr == ReliabilityPolicy.RELIABLE:
        out.append(f"WARNING: Reliable subscription, but publisher is {pr.short_key};")
    elif pr == ReliabilityPolicy.BEST_EFFORT and _unknown(sr):
        out.append(f"WARNING: Best effort publisher, but subscription is {sr.short_key};")
    pd, sd = pub.durability, sub.durability
    if _unknown(pd) and _unknown(sd):
        out.append(f"WARNING: Publisher durabilty is {pd.short_key} and subscription durability is {sd.short_key};")
    elif _unknown(pd) and sd == DurabilityPolicy.TRANSIENT_LOCAL:
        out.append(f"WARNING: Transient local subscription, but publisher is {pd.short_key};")
    elif pd == DurabilityPolicy.VOLATILE and _unknown(sd):
        out.append(f"WARNING: Volatile publisher, but subscription is {sd.short_key};")
    pl, sl = pub.liveliness, sub.liveliness
    if _unknown(pl) and _unknown(sl):
        out.append(f"WARNING: Publisher liveliness is {pl.short_key} and subscription liveliness is {sl.short_key};")
    elif _unknown(pl) and sl == LivelinessPolicy.MANUAL_BY_TOPIC:
        out.append(f"WARNING: Subscription's liveliness is manual by topic, but publisher's is {pl.short_key};")
    elif pl == LivelinessPolicy.AUTOMATIC and _unknown(sl):
        out.append(f"WARNING: Publisher's liveliness is automatic, but subscription's is {sl.short_key};")
    return "".join(out)


def qos_check_compatible(publisher_qos: QoSProfile, subscription_qos: QoSProfile) -> tuple[QoSCompatibility, str]:
    errors = incompatible_policies(publisher_qos, subscription_qos)
    if errors:
        return QoSCompatibility.ERROR, "".join(reason for _, reason in errors)
    warnings_text = _warnings(publisher_qos, subscription_qos)
    if warnings_text:
        return QoSCompatibility.WARNING, warnings_text
    return QoSCompatibility.OK, ""


def as_profile(qos_or_depth: Any) -> QoSProfile:
    """A create_* argument as a profile: an int is a KEEP_LAST depth; anything else is a TypeError."""
    if isinstance(qos_or_depth, QoSProfile):
        return qos_or_depth
    if isinstance(qos_or_depth, int) and not isinstance(qos_or_depth, bool):
        if qos_or_depth < 0:
            raise ValueError("history depth must be greater than or equal to zero")
        return QoSProfile(depth=qos_or_depth)
    raise TypeError(f"Expected QoSProfile or int, but received {type(qos_or_depth)!r}")


def _ns(d: Duration) -> int | None:
    return d.nanoseconds if _finite(d) else None


def to_wire(profile: QoSProfile) -> wire.QoS:
    """The profile rmw_zenoh would declare: system defaults become reliable, volatile, keep-last 42."""
    return wire.QoS(
        reliable=profile.reliability != ReliabilityPolicy.BEST_EFFORT,
        transient_local=profile.durability == DurabilityPolicy.TRANSIENT_LOCAL,
        keep_all=profile.history == HistoryPolicy.KEEP_ALL,
        depth=profile.depth if profile.history != HistoryPolicy.SYSTEM_DEFAULT else 0,
        deadline_ns=_ns(profile.deadline), lifespan_ns=_ns(profile.lifespan),
        manual_liveliness=profile.liveliness == LivelinessPolicy.MANUAL_BY_TOPIC,
        liveliness_lease_ns=_ns(profile.liveliness_lease_duration),
    )


def from_wire(q: wire.QoS | None) -> QoSProfile:
    if q is None:
        return QoSProfile(depth=10)
    return QoSProfile(
        history=HistoryPolicy.KEEP_ALL if q.keep_all else HistoryPolicy.KEEP_LAST, depth=q.depth,
        reliability=ReliabilityPolicy.RELIABLE if q.reliable else ReliabilityPolicy.BEST_EFFORT,
        durability=DurabilityPolicy.TRANSIENT_LOCAL if q.transient_local else DurabilityPolicy.VOLATILE,
        deadline=Duration(nanoseconds=q.deadline_ns or 0), lifespan=Duration(nanoseconds=q.lifespan_ns or 0),
        liveliness=LivelinessPolicy.MANUAL_BY_TOPIC if q.manual_liveliness else LivelinessPolicy.AUTOMATIC,
        liveliness_lease_duration=Duration(nanoseconds=q.liveliness_lease_ns or 0),
    )
