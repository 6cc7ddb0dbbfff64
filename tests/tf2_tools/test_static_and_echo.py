"""tf2_ros's static_transform_publisher and tf2_echo: their argument forms and messages as the C++ programs have
them (tf2_ros, jazzy), the rotation math against Bullet's (PyBullet: tf2's LinearMath is Bullet's), and the two
programs over a real router, started as launch_ros starts `Node(package='tf2_ros', executable=…)`."""

from __future__ import annotations

import math
import subprocess
import sys
import time

import pybullet
import pytest

from diffctl.tf2_tools.args import (
    OLD_STYLE_WARNING,
    ArgsError,
    EchoUsage,
    parse_echo,
    parse_static,
    quaternion_from_rpy,
)
from diffctl.tf2_tools.echo_format import echo_block, euler_ypr, matrix_from_quaternion
from diffctl.workspace.package_index import executable_argv


def test_new_style_flags() -> None:
    st = parse_static(["--x", "1", "--y", "-2", "--z", "0.5", "--yaw", "1.57", "--frame-id", "a",
                       "--child-frame-id", "b"])
    assert st.translation == (1.0, -2.0, 0.5) and (st.frame_id, st.child_frame_id) == ("a", "b")
    assert st.rotation == pytest.approx(quaternion_from_rpy(0.0, 0.0, 1.57)) and not st.old_style
    q = parse_static(["--qz", "1", "--qw", "0", "--frame-id", "a", "--child-frame-id", "b"]).rotation
    assert q == (0.0, 0.0, 1.0, 0.0)
    assert parse_static(["--frame-id", "a", "--child-frame-id", "b"]).rotation == (0.0, 0.0, 0.0, 1.0)
    assert parse_static(["-h"]).help


def test_old_positional_forms_warn_as_deprecated() -> None:
    said: list[str] = []
    st = parse_static(["1", "2", "3", "0.5", "0.25", "0.125", "a", "b"], warn=said.append)  # x y z yaw pitch roll
    assert said == [OLD_STYLE_WARNING] and st.old_style
    assert st.translation == (1.0, 2.0, 3.0)
    assert st.rotation == pytest.approx(quaternion_from_rpy(0.125, 0.25, 0.5))
    st = parse_static(["0", "0", "0", "0", "0", "0.7071", "0.7071", "odom", "laser"])  # x y z qx qy qz qw
    assert st.rotation == (0.0, 0.0, 0.7071, 0.7071) and (st.frame_id, st.child_frame_id) == ("odom", "laser")


@pytest.mark.parametrize(("argv", "message"), [
    (["--x"], "Not enough arguments for --x"),
    (["--x", "one", "--frame-id", "a", "--child-frame-id", "b"], "Failed to parse --x argument as float"),
    (["--roll", "1", "--qw", "1", "--frame-id", "a", "--child-frame-id", "b"],
     "Cannot specify both quaternion and Euler rotations"),
    (["--x", "1", "0", "0", "0", "0", "0", "0", "a", "b"], "Cannot specify both new-style (flags) and old-style"),
    (["1", "2", "--frame-id", "a", "--child-frame-id", "b"], "Extra unparsed arguments on command-line"),
    (["--child-frame-id", "b"], "Frame id must not be empty"),
    (["--frame-id", "a"], "Child frame id must not be empty"),
    (["x", "0", "0", "0", "0", "0", "a", "b"], "Failed to parse x argument as float"),
])
def test_refusals_carry_the_programs_messages(argv: list[str], message: str) -> None:
    with pytest.raises(ArgsError) as e:
        parse_static(argv)
    assert str(e.value).startswith(message)


def test_numbers_convert_as_stod_does() -> None:
    # std::stod reads the leading number and ignores what follows; hex, inf and nan are numbers
    assert parse_static(["--x", "1.5m", "--y", "0x10", "--z", "-inf", "--frame-id", "a",
                         "--child-frame-id", "b"]).translation == (1.5, 16.0, -math.inf)


def test_echo_arguments_and_exit_codes() -> None:
    assert parse_echo(["odom", "base"]).rate_hz == 1.0
    assert parse_echo(["odom", "base", "10"]).rate_hz == 10.0
    for argv, code in ((["odom"], 1), (["a", "b", "fast"], 2), (["a", "b", "1.0foo"], 3)):
        with pytest.raises(EchoUsage) as e:
            parse_echo(argv)
        assert e.value.code == code


@pytest.mark.parametrize("rpy", [(0.1, -0.2, 0.3), (1.0, 0.5, -2.5), (0.0, 0.0, math.pi), (-3.0, 1.2, 0.7)])
def test_rotation_math_is_bullets(rpy: tuple[float, float, float]) -> None:
    q = quaternion_from_rpy(*rpy)
    assert q == pytest.approx(pybullet.getQuaternionFromEuler(rpy), abs=1e-12)
    m = matrix_from_quaternion(q)
    assert [v for row in m for v in row] == pytest.approx(pybullet.getMatrixFromQuaternion(q), abs=1e-12)
    yaw, pitch, roll = euler_ypr(m)
    assert matrix_from_quaternion(quaternion_from_rpy(roll, pitch, yaw)) == [pytest.approx(r) for r in m]


def test_echo_block_layout() -> None:
    text = echo_block(12, 5000, (1.0, -2.0, 0.5), quaternion_from_rpy(0.0, 0.0, math.pi / 2))
    assert text.splitlines() == [
        "At time 12.5000",
        "- Translation: [1.000, -2.000, 0.500]",
        "- Rotation: in Quaternion [0.000, 0.000, 0.707, 0.707]",
        "- Rotation: in RPY (radian) [0.000, -0.000, 1.571]",
        "- Rotation: in RPY (degree) [0.000, -0.000, 90.000]",
        "- Matrix:",
        "  0.000 -1.000  0.000  1.000",
        "  1.000  0.000  0.000 -2.000",
        "  0.000  0.000  1.000  0.500",
        "  0.000  0.000  0.000  1.000",
    ]


def test_the_executables_belong_to_package_tf2_ros() -> None:
    assert executable_argv("tf2_ros", "static_transform_publisher")[-2:] == ["tf2", "static_transform_publisher"]
    assert executable_argv("tf2_ros", "tf2_echo")[-2:] == ["tf2", "tf2_echo"]


def _read_until(p: subprocess.Popen, needle: str, timeout_s: float = 20.0) -> str:
    out = []
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        line = p.stdout.readline()
        if not line:
            break
        out.append(line)
        if needle in "".join(out[-12:]):
            return "".join(out)
    raise AssertionError(f"never printed {needle!r}:\n{''.join(out)}")


def test_published_and_echoed_over_the_bus(router: str, procs) -> None:
    exe = executable_argv("tf2_ros", "static_transform_publisher")
    new = procs.start([*exe, "--x", "1", "--y", "2", "--yaw", "1.5707963267948966", "--frame-id", "a",
                       "--child-frame-id", "b"])
    old = procs.start([*exe, "0", "0", "0.5", "0", "0", "0", "b", "c"])
    echo = procs.start([*executable_argv("tf2_ros", "tf2_echo"), "a", "c", "5"])
    text = _read_until(echo, "- Matrix:")
    assert "- Translation: [1.000, 2.000, 0.500]" in text, text
    assert "- Rotation: in RPY (degree) [0.000, -0.000, 90.000]" in text, text
    assert procs.stop(echo) == 0
    assert procs.stop(new) == 0
    assert procs.stop(old) == 0
    out = old.stdout.read()
    assert OLD_STYLE_WARNING in out and "Spinning until stopped - publishing transform" in out, out
    assert "from 'b' to 'c'" in out


def test_bad_arguments_exit_1_with_the_usage() -> None:
    r = subprocess.run([sys.executable, "-m", "diffctl", "tf2", "static_transform_publisher", "--frame-id", "a"],
                       capture_output=True, text=True, timeout=60)
    assert r.returncode == 1
    assert "error parsing command line arguments: Child frame id must not be empty" in r.stderr
    assert r.stdout.startswith("usage: static_transform_publisher")
