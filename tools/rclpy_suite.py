"""Run rclpy's own unit tests (ros2/rclpy, Jazzy, rclpy/test) against diffctl's rclpy, and beside it the real one.

    python tools/rclpy_suite.py --mirror GITDIR [--real] [--tests "test_node.py test_qos.py"] [--keep]
    python tools/rclpy_suite.py --source RCLPY_CHECKOUT ...

The tests are upstream's, read at run time from a bare git repository of ros2/rclpy (`--mirror`, its `jazzy`
branch) or a checkout (`--source`); nothing of them is kept in this repository. They need the `test_msgs`
interface package: its interface files and its two Python helper modules are taken from the oracle venv
(`make jazzy-oracle`: .venv-jazzy holds ros-jazzy-test-msgs) into a scratch colcon workspace, where diffctl's
interface finder generates the package as it does a user's. `tests/__init__.py` is emptied: it loads rpyutils'
DLL helper and `test_rclpy`, a C extension that only rclpy's CMake build makes.

Ours: the project's .venv python, on a `diffctl router` of its own on a free loopback port, in a ROS domain of
its own. `--real`: the same tests under .venv-jazzy (the real rclpy on Fast DDS, loopback), with pytest installed
with `--target` into a folder of its own. The summary counts passed/failed/errors on each side and lists the
tests that fail under diffctl but pass under the real rclpy.
"""

from __future__ import annotations

import argparse
import os
import random
import re
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
OURS_PY = REPO / ".venv" / "bin" / "python"
REAL_PY = REPO / ".venv-jazzy" / "bin" / "python"
PYTEST_REQS = ["pytest>=7.4,<9", "pytest-timeout"]
SUMMARY = re.compile(r"^=*\s*(\d+ (?:passed|failed|errors?|skipped|deselected).*?) in [0-9.]+s", re.M)
OUTCOME = re.compile(r"^(FAILED|ERROR) (\S+)")


def _upstream_tests(args: argparse.Namespace, into: Path) -> Path:
    if args.source:
        shutil.copytree(Path(args.source) / "rclpy" / "test", into / "tests")
    else:
        archive = subprocess.run(["git", f"--git-dir={args.mirror}", "archive", args.branch, "rclpy/test"],
                                 capture_output=True, check=True).stdout
        subprocess.run(["tar", "-x", "-C", str(into)], input=archive, check=True)
        (into / "rclpy" / "test").rename(into / "tests")
        shutil.rmtree(into / "rclpy")
    (into / "tests" / "__init__.py").write_text("")
    return into / "tests"


def _test_msgs_workspace(into: Path) -> Path:
    """A colcon workspace holding test_msgs as its CMakeLists names its files, from the oracle venv's install."""
    share = REPO / ".venv-jazzy" / "share" / "test_msgs"
    site = next((REPO / ".venv-jazzy" / "lib").glob("python3*/site-packages/test_msgs"), None)
    if not share.is_dir() or site is None:
        sys.exit("error: .venv-jazzy has no test_msgs: run `make jazzy-oracle` first")
    pkg = into / "ws" / "src" / "test_msgs"
    files = []
    for kind in ("msg", "srv", "action"):
        (pkg / kind).mkdir(parents=True)
        for f in sorted((share / kind).glob(f"*.{kind}")):
            shutil.copy(f, pkg / kind / f.name)
            files.append(f"{kind}/{f.name}")
    (pkg / "package.xml").write_text(
        '<?xml version="1.0"?>\n<package format="3"><name>test_msgs</name><version>0.0.0</version>'
        "<description>test interfaces</description><maintainer email=\"x@example.com\">x</maintainer>"
        "<license>Apache-2.0</license><buildtool_depend>ament_cmake</buildtool_depend>"
        "<member_of_group>rosidl_interface_packages</member_of_group>"
        "<export><build_type>ament_cmake</build_type></export></package>\n")
    listed = "\n".join(f'  "{f}"' for f in files)
    (pkg / "CMakeLists.txt").write_text(
        "cmake_minimum_required(VERSION 3.5)\nproject(test_msgs)\nfind_package(ament_cmake REQUIRED)\n"
        f"rosidl_generate_interfaces(${{PROJECT_NAME}}\n{listed}\n  DEPENDENCIES builtin_interfaces\n)\n"
        "ament_package()\n")
    helpers = pkg / "src" / "test_msgs"
    helpers.mkdir(parents=True)
    (helpers / "__init__.py").write_text("")
    for name in ("message_fixtures.py", "service_fixtures.py"):
        shutil.copy(site / name, helpers / name)
    return into / "ws"


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _pytest(python: Path, tests: Path, selected: list[str], cwd: Path, env: dict[str, str], log: Path) -> str:
    targets = [str(tests / name) for name in selected] or [str(tests)]
    cmd = [str(python), "-m", "pytest", "-p", "no:cacheprovider", "-q", "-rfE", "--timeout", "60",
           "--continue-on-collection-errors", "--rootdir", str(tests.parent), *targets]
    with log.open("w") as out:
        subprocess.run(cmd, cwd=cwd, env=env, stdout=out, stderr=subprocess.STDOUT, check=False)
    return log.read_text()


def _ours(tests: Path, ws: Path, selected: list[str], log: Path) -> str:
    port = _free_port()
    env = {**os.environ, "DIFFCTL_ROUTER": f"tcp/127.0.0.1:{port}", "ROS_DOMAIN_ID": str(random.randint(120, 160)),
           "PYTHONPATH": str(ws / "src" / "test_msgs" / "src")}
    router_log = log.with_name("router.log")
    with router_log.open("w") as out:
        router = subprocess.Popen([str(OURS_PY), "-m", "diffctl", "router", "--listen", env["DIFFCTL_ROUTER"]],
                                  env=env, stdout=out, stderr=subprocess.STDOUT, start_new_session=True)
    try:
        while "listening" not in router_log.read_text():
            if router.poll() is not None:
                sys.exit(f"error: diffctl router exited: {router_log.read_text().strip()}")
            time.sleep(0.1)
        return _pytest(OURS_PY, tests, selected, ws, env, log)
    finally:
        os.killpg(router.pid, signal.SIGINT)
        try:
            router.wait(10)
        except subprocess.TimeoutExpired:
            os.killpg(router.pid, signal.SIGKILL)
            router.wait()


def _real(tests: Path, selected: list[str], scratch: Path, log: Path) -> str:
    target = Path.home() / ".cache" / "diffctl" / "rclpy-suite-pytest"
    if not (target / "pytest").is_dir():
        subprocess.run([str(REAL_PY), "-m", "pip", "install", "-q", "--target", str(target), *PYTEST_REQS],
                       check=True)
    env = {k: v for k, v in os.environ.items() if not k.startswith(("DIFFCTL_", "ZENOH_"))}
    env.update(PYTHONPATH=str(target), ROS_DOMAIN_ID=str(random.randint(161, 200)),
               ROS_AUTOMATIC_DISCOVERY_RANGE="LOCALHOST")
    return _pytest(REAL_PY, tests, selected, scratch, env, log)


def _outcomes(text: str) -> tuple[str, set[str]]:
    found = SUMMARY.findall(text)
    # Test ids relative to where each side ran: keep what follows the tests folder.
    bad = {re.sub(r"^(?:.*/)?tests/", "", m.group(2)) for line in text.splitlines() if (m := OUTCOME.match(line))}
    return (found[-1] if found else "no summary (see the log)"), bad


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    where = parser.add_mutually_exclusive_group(required=True)
    where.add_argument("--mirror", help="a bare git repository of ros2/rclpy")
    where.add_argument("--source", help="a checkout of ros2/rclpy")
    parser.add_argument("--branch", default="jazzy", help="the branch of --mirror (default: jazzy)")
    parser.add_argument("--real", action="store_true", help="run the same tests under the real rclpy too")
    parser.add_argument("--tests", default="", help="test files to run, space-separated (default: all)")
    parser.add_argument("--keep", action="store_true", help="keep the scratch folder and its logs")
    args = parser.parse_args(argv)
    if not OURS_PY.exists() or (args.real and not REAL_PY.exists()):
        sys.exit("error: run `make test-deps` (the .venv) and `make jazzy-oracle` (.venv-jazzy) first")
    scratch = Path(tempfile.mkdtemp(prefix="rclpy-suite-"))
    try:
        tests = _upstream_tests(args, scratch)
        ws = _test_msgs_workspace(scratch)
        selected = args.tests.split()
        started = time.monotonic()
        ours_summary, ours_bad = _outcomes(_ours(tests, ws, selected, scratch / "ours.log"))
        print(f"diffctl:    {ours_summary} ({time.monotonic() - started:.0f} s)")
        if args.real:
            started = time.monotonic()
            real_summary, real_bad = _outcomes(_real(tests, selected, scratch, scratch / "real.log"))
            print(f"real rclpy: {real_summary} ({time.monotonic() - started:.0f} s)")
            only_ours = sorted(ours_bad - real_bad)
            print(f"{len(only_ours)} fail under diffctl and pass under the real rclpy:")
            for test in only_ours:
                print(f"  {test}")
        if args.keep:
            print(f"logs: {scratch}")
    finally:
        if not args.keep:
            shutil.rmtree(scratch, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
