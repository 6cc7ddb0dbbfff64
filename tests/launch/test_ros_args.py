"""`--ros-args` resolution (diffctl.ros_args) against what ROS 2 Jazzy's real rclpy does with the same arguments.

data/rclpy_ros_args/cases.json holds, for each command line, the name, namespace, parameter overrides and the
resolved `chatter` topic that rclpy 7.1.6 (rcl 9.2.8) gave each node, recorded by running
data/rclpy_ros_args/rclpy_probe.py in a venv with the ros-jazzy-rclpy wheels from PyPI: parameter files'
wildcard keys (`/**`, `**`, `/*`, `/**/name`, `/ns/**`, `/ns/*/name`, nested `ns: {name: …}`), bare keys
(`talker` is `/talker` only), the order of keys across files and `-p` (a key keeps its first place; `-p`
does not beat a file's node-specific key), node-prefixed `-p`, and remapping (first rule wins; `talker:` rules
for that node only, matched against its remapped name for topics and its given name for `__node`/`__ns`), and
a node's own arguments (rclpy's cli_args) over the process's. The last test runs the cases through the real
rclpy of the oracle venv again.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from diffctl import ros_args
from diffctl.errors import ConfigError

DATA = Path(__file__).parent / "data" / "rclpy_ros_args"
CASES = json.loads((DATA / "cases.json").read_text())["cases"]


def _resolve_chatter(ra: ros_args.RosArgs, namespace: str) -> str:
    from tests.probe import Probe

    # Node's own expansion and remapping, without a session: the unbound method on a bare instance.
    n = Probe.__new__(Probe)
    n.name, n.namespace = "x", namespace
    n._remaps = {}
    for k, v in ra.remaps.items():
        n._remaps.setdefault(n._expand(k), n._expand(v))
    return n.resolve("chatter")


@pytest.mark.parametrize("case", CASES, ids=[" ".join(c["ros_args"])[:60] for c in CASES])
def test_resolution_matches_rclpy(case: dict) -> None:
    argv = [a.replace("{data}", str(DATA)) for a in case["ros_args"]]
    got = []
    for name, ns in case["nodes"]:
        local = [a.replace("{data}", str(DATA)) for a in case.get("local", [])]
        ra = ros_args.parse(argv, name, ns, local_argv=local)
        namespace = ra.namespace or ns
        got.append({"name": ra.node_name or name, "ns": namespace, "params": ra.params,
                    "chatter": _resolve_chatter(ra, namespace)})
    assert got == case["rclpy"]


def test_local_arguments_override_global_ones_and_their_rules_come_first() -> None:
    ra = ros_args.parse(["-p", "a:=1", "-r", "chatter:=g"], "ctrl", "/r1",
                        local_argv=["-p", "a:=2", "-r", "chatter:=l"])
    assert ra.params == {"a": 2} and ra.remaps["chatter"] == "l"


def test_load_params_file_takes_a_fully_qualified_name() -> None:
    f1 = DATA / "f1.yaml"
    assert ros_args.load_params_file(f1, "/robot1/talker")["c"] == 3
    assert ros_args.load_params_file(f1, "/robot2/talker")["c"] == 4
    assert "c" not in ros_args.load_params_file(f1, "talker")  # a bare name is a node at the root


def test_bad_rules_are_errors_naming_the_form() -> None:
    with pytest.raises(ConfigError, match=r"\[NODE:\]FROM:=TO"):
        ros_args.parse(["-r", "chatter"])
    with pytest.raises(ConfigError, match=r"\[NODE:\]NAME:=VALUE"):
        ros_args.parse(["-p", "talker:"])


@pytest.mark.parametrize(("key", "fqn", "matches"), [
    ("/**", "/a/b/c", True), ("/*", "/a", True), ("/*", "/a/b", False), ("/a/**", "/a/b/c", True),
    ("/a/**", "/a", True), ("/**/c", "/a/b/c", True), ("/**/c", "/c", True), ("c", "/a/c", False),
    ("/a.b", "/axb", False),
])
def test_node_key_patterns(key: str, fqn: str, matches: bool) -> None:
    assert ros_args.node_key_matches(key, fqn) is matches


def test_the_recorded_cases_are_what_rclpy_does_now() -> None:
    # The same cases run through the real rclpy of the oracle venv (`make jazzy-oracle`): the recorded results
    # above are rclpy's, not a copy of diffctl's.
    from tests.oracle import jazzy_venv

    probe = (DATA / "rclpy_probe.py").read_text()
    code = f"import sys; sys.argv = ['probe', {str(DATA / 'cases.json')!r}, {str(DATA)!r}]\n{probe}"
    live = json.loads(jazzy_venv.run_python(code, timeout_s=120).stdout.strip().splitlines()[-1])
    assert live == [c["rclpy"] for c in CASES]


def test_a_repeated_ros_args_flag_continues_the_ros_arguments() -> None:
    # launch_ros writes a Node's ros_arguments and then its own `--ros-args …` (no `--` between): rcl reads one run
    # of ROS arguments (the last recorded case above is that command line, through the real rclpy).
    argv = ["talker", "pos1", "--ros-args", "--log-level", "info", "--ros-args", "-r", "__node:=t", "--", "tail"]
    plain, ros = ros_args.split_argv(argv)
    assert plain == ["talker", "pos1", "tail"]
    assert ros == ["--log-level", "info", "-r", "__node:=t"]
