# Values users print or compare: QoS profiles and the compatibility check (every reliability, durability and
# liveliness pairing), durations, times, clocks, parameter types, logging severities, init/shutdown order.
import json

import rclpy
import rclpy.logging as logging
from rclpy.clock import Clock, ClockType, ROSClock
from rclpy.duration import Duration, Infinite
from rclpy.parameter import Parameter
from rclpy.qos import (
    DurabilityPolicy,
    HistoryPolicy,
    LivelinessPolicy,
    QoSPresetProfiles,
    QoSProfile,
    ReliabilityPolicy,
    qos_check_compatible,
    qos_profile_best_available,
    qos_profile_default,
    qos_profile_sensor_data,
    qos_profile_system_default,
)
from rclpy.time import Time

out = []


def obs(label, fn):
    try:
        out.append([label, "ok", fn()])
    except Exception as e:
        out.append([label, type(e).__name__, str(e)])


def compat(pub, sub):
    verdict, reason = qos_check_compatible(pub, sub)
    return [int(verdict), reason]


obs("str profile", lambda: str(QoSProfile(depth=3)))
obs("system default", lambda: str(qos_profile_system_default))
obs("sensor", lambda: str(qos_profile_sensor_data))
obs("best available", lambda: str(qos_profile_best_available))
obs("short key", lambda: str(QoSPresetProfiles.get_from_short_key("sensor_data")))
obs("short keys", lambda: QoSPresetProfiles.short_keys())
obs("policy short keys", lambda: [p.short_keys() for p in (ReliabilityPolicy, HistoryPolicy, DurabilityPolicy,
                                                           LivelinessPolicy)])
obs("policy short key", lambda: ReliabilityPolicy.BEST_EFFORT.short_key)
obs("from short", lambda: DurabilityPolicy.get_from_short_key("transient_local"))
obs("qos eq", lambda: [QoSProfile(depth=10) == qos_profile_default, QoSProfile(depth=10) == 10])
obs("compat deadline", lambda: compat(QoSProfile(depth=1, deadline=Duration(seconds=2)),
                                      QoSProfile(depth=1, deadline=Duration(seconds=1))))
obs("compat lease", lambda: [compat(QoSProfile(depth=1, liveliness_lease_duration=Duration(seconds=a)),
                                     QoSProfile(depth=1, liveliness_lease_duration=Duration(seconds=b)))
                              for a, b in ((2, 1), (0, 1), (1, 0), (1, 2), (1e9, 1), (0, 1e9))])
obs("compat system default", lambda: compat(qos_profile_system_default, QoSProfile(depth=1)))
profiles = [QoSProfile(depth=1, reliability=r, durability=d, liveliness=lv)
            for r in (0, 1, 2) for d in (0, 1, 2) for lv in (0, 1, 3)]
obs("compat every pairing", lambda: [compat(a, b) for a in profiles for b in profiles])
obs("infinite", lambda: [str(Infinite), repr(Infinite)])
obs("duration negative", lambda: repr(Duration(seconds=-1.5)))
obs("duration msg", lambda: repr(Duration.from_msg(Duration(seconds=1.25).to_msg())))
obs("time str", lambda: str(Time(seconds=2)))
obs("clock repr", lambda: [repr(Clock()), repr(ROSClock()), repr(Clock(clock_type=ClockType.STEADY_TIME))])
obs("clock types", lambda: [int(c) for c in ClockType])
for text in ("debug", "WARN", "warning", "Error", "unset", "Info", "loud"):
    obs("severity " + text, lambda text=text: int(logging.get_logging_severity_from_string(text)))
obs("param type str", lambda: [str(Parameter.Type.DOUBLE), repr(Parameter.Type.DOUBLE)])
obs("param bad", lambda: Parameter("x", value={"a": 1}))
obs("param mixed list", lambda: Parameter("x", value=[1, 2.0]))
obs("param msg", lambda: str(Parameter("x", value=[1.5]).to_parameter_msg()))
obs("param from msg", lambda: (lambda p: [p.name, p.type_.name, list(p.value)])(
    Parameter.from_parameter_msg(Parameter("y", value=[1, 2]).to_parameter_msg())))
obs("ok before init", lambda: rclpy.ok())
obs("shutdown before init", lambda: rclpy.shutdown())
obs("try_shutdown before init", lambda: rclpy.try_shutdown())
print(json.dumps(out))
