"""`diffctl test --init` on the tutorial car as a user's workspace package: the smoke test it writes passes;
with a wrong wheel_radius in the controller YAML it fails with a readable message and leaves artifacts (the
processes' logs, an MCAP bag the mcap library reads, a PNG of the scene)."""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
import textwrap
from pathlib import Path
from xml.etree import ElementTree as ET

import pytest
from mcap.reader import make_reader
from PIL import Image

REPO = Path(__file__).resolve().parent.parent.parent


def tutorial_workspace(root: Path) -> Path:
    """The tutorial's package as a user has it: launch/ and config/ installed by CMake, in ws/src/."""
    pkg = root / "ws" / "src" / "diffctl_demo"
    (pkg / "launch").mkdir(parents=True)
    shutil.copytree(REPO / "config", pkg / "config")
    shutil.copy(REPO / "launch" / "sim_control.launch.py", pkg / "launch")
    (pkg / "package.xml").write_text(textwrap.dedent("""\
        <?xml version="1.0"?>
        <package format="3"><name>diffctl_demo</name><version>0.1.0</version><description>car</description>
        <maintainer email="me@example.com">me</maintainer><license>Apache-2.0</license>
        <buildtool_depend>ament_cmake</buildtool_depend><test_depend>launch_testing_ament_cmake</test_depend>
        <export><build_type>ament_cmake</build_type></export></package>
        """))
    (pkg / "CMakeLists.txt").write_text(
        "cmake_minimum_required(VERSION 3.8)\nproject(diffctl_demo)\nfind_package(ament_cmake REQUIRED)\n"
        "install(DIRECTORY launch config DESTINATION share/${PROJECT_NAME})\nament_package()\n"
    )
    return root / "ws"


def _diffctl(*args: str, cwd: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "diffctl", *args], cwd=cwd, capture_output=True, text=True,
                          timeout=120, start_new_session=True)


@pytest.mark.slow
def test_init_smoke_test_passes_and_a_wrong_wheel_radius_fails_with_artifacts(tmp_path: Path) -> None:
    ws = tutorial_workspace(tmp_path)
    r = _diffctl("test", "--init", "diffctl_demo", cwd=ws)
    assert r.returncode == 0, r.stderr
    test_file = ws / "src" / "diffctl_demo" / "test" / "test_diffctl_demo_smoke.launch.py"
    text = test_file.read_text()
    for line in ('LAUNCH_FILE = "launch/sim_control.launch.py"', 'CONTROLLER = "diffbot_base_controller"',
                 'LEFT_WHEEL_JOINT = "base_link_to_left_wheel"', "WHEEL_RADIUS_M = 0.04"):
        assert line in text
    r = _diffctl("test", "--init", "diffctl_demo", cwd=ws)
    assert r.returncode == 2 and "exists already" in r.stderr

    r = _diffctl("test", "--packages-select", "diffctl_demo", cwd=ws)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "Summary: 1 test files, 1 passed, 0 failed" in r.stdout

    yaml_file = ws / "src" / "diffctl_demo" / "config" / "diff_drive_controller.yaml"
    yaml_file.write_text(yaml_file.read_text().replace("wheel_radius: 0.04", "wheel_radius: 0.08"))
    art = tmp_path / "artifacts"
    r = _diffctl("test", "--artifacts", str(art), "--junit-xml", str(tmp_path / "r.xml"), cwd=ws)
    assert r.returncode == 1, r.stdout + r.stderr
    assert "does wheel_radius in diff_drive_controller.yaml match the wheels of the robot (0.04 m)?" in r.stdout
    rolled = re.search(r"the wheels rolled ([0-9.]+) m but odometry says ([0-9.]+) m", r.stdout)
    assert rolled and abs(float(rolled[1]) - float(rolled[2]) / 2) < 0.05  # half what odometry claims
    failures = [c for c in ET.parse(tmp_path / "r.xml").getroot().iter("testcase") if c.find("failure") is not None]
    assert [c.get("name") for c in failures] == ["test_drives_on_cmd_vel"]
    (run_dir,) = art.iterdir()
    logs = {p.name for p in (run_dir / "logs").iterdir()}
    assert {"launch.log", "gz_sim.log", "robot_state_publisher.log"} <= logs
    (mcap_file,) = (run_dir / "bag").glob("*.mcap")
    with mcap_file.open("rb") as f:
        reader = make_reader(f)
        topics = {channel.topic for _, channel, _ in reader.iter_messages(topics=["/diffbot_base_controller/odom"])}
    assert topics == {"/diffbot_base_controller/odom"}
    with Image.open(run_dir / "scene.png") as img:
        assert img.format == "PNG" and img.size == (800, 800)
        assert len(img.getcolors(100000) or []) > 3  # a picture, not a blank page
