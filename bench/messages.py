"""Message (de)serialization: diffctl's generated classes and compiled codecs against the real rclpy's
`serialize_message` / `deserialize_message` (Jazzy wheels, Fast CDR, run in the oracle venv) on the same
messages, in the same run.

Keys (`msgs_*` ours, `msgs_real_*` the real one), microseconds per call, best of 5 timeit repeats:
`*_twist_serialize_us`, `*_twist_deserialize_us` (geometry_msgs/Twist), `*_scan_serialize_us`,
`*_scan_deserialize_us` (sensor_msgs/LaserScan with 720 ranges and intensities), `*_twist_new_us`
(constructing a Twist() with its two Vector3s); `msgs_twist_serialize_vs_real` and
`msgs_twist_deserialize_vs_real` are ours ÷ the real one's (budget rows).
"""

from __future__ import annotations

import json
import subprocess
import sys
import tempfile

PROGRAM = r'''
import json, sys, timeit
from geometry_msgs.msg import Twist
from sensor_msgs.msg import LaserScan
if sys.argv[1] == "real":
    from rclpy.serialization import serialize_message as ser, deserialize_message as de
else:
    from diffctl.interfaces import serialize as ser, deserialize as de
t = Twist(); t.linear.x = 0.5; t.angular.z = 0.1
s = LaserScan(ranges=[1.0] * 720, intensities=[0.5] * 720); s.header.frame_id = "laser"
tb, sb = ser(t), ser(s)
def best(fn, n):
    return min(timeit.repeat(fn, number=n, repeat=5)) / n * 1e6
print(json.dumps({
    "twist_serialize_us": best(lambda: ser(t), 20000),
    "twist_deserialize_us": best(lambda: de(tb, Twist), 20000),
    "scan_serialize_us": best(lambda: ser(s), 2000),
    "scan_deserialize_us": best(lambda: de(sb, LaserScan), 2000),
    "twist_new_us": best(Twist, 20000),
}))
'''


def _ours() -> dict:
    from diffctl.workspace import PYTHON_PATH

    with tempfile.TemporaryDirectory() as cwd:
        p = subprocess.run([sys.executable, "-c", PROGRAM, "ours"], capture_output=True, text=True, cwd=cwd,
                           env={"PATH": "/usr/bin:/bin", "PYTHONPATH": str(PYTHON_PATH)}, timeout=300, check=True)
    return json.loads(p.stdout.strip().splitlines()[-1])


def _real() -> dict:
    from tests.oracle import jazzy_venv

    return json.loads(jazzy_venv.run_python(PROGRAM.replace("sys.argv[1]", '"real"'), timeout_s=300)
                      .stdout.strip().splitlines()[-1])


def run() -> dict:
    ours, real = _ours(), _real()
    out = {f"msgs_{k}": round(v, 3) for k, v in ours.items()}
    out.update({f"msgs_real_{k}": round(v, 3) for k, v in real.items()})
    for k in ("twist_serialize_us", "twist_deserialize_us"):
        out[f"msgs_{k.removesuffix('_us')}_vs_real"] = round(ours[k] / real[k], 3)
    return out


if __name__ == "__main__":
    print(json.dumps(run(), indent=1))
