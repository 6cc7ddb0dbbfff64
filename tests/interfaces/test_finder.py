"""The import hook: active in every interpreter of the venv, after sys.path (a real ROS package wins), clear
about what is not there, and exact about malformed interface files."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from tests.interfaces.programs import OVERLAY as OVERLAY_PATH
from tests.interfaces.programs import ours_env, run_ours


def python(code: str, env: dict[str, str] | None = None, cwd: Path | None = None) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-c", code], env=ours_env(env), cwd=cwd, capture_output=True, text=True,
                          timeout=60)


def test_hook_is_installed_by_the_pth_after_the_path_finder() -> None:
    p = python("import sys; names = [getattr(f, '__name__', type(f).__name__) for f in sys.meta_path]; print(names); "
               "print('diffctl.interfaces.registry' in sys.modules, 'rosbags' in sys.modules)")
    names, loaded = p.stdout.splitlines()
    assert names.index("InterfaceFinder") > names.index("PathFinder"), names
    assert loaded == "False False", "the hook must not import the message machinery before it is needed"


def test_unknown_package_names_where_it_looked(tmp_path: Path) -> None:
    ws = tmp_path / "ws"
    (ws / "src" / "demo").mkdir(parents=True)
    (ws / "src" / "demo" / "package.xml").write_text("<package><name>demo</name></package>")
    p = python("import robot_msgs", {"DIFFCTL_WORKSPACE": str(ws), "AMENT_PREFIX_PATH": str(tmp_path)})
    err = p.stderr.strip().splitlines()[-1]
    assert err.startswith("ModuleNotFoundError: No module named 'robot_msgs': no interface package of that name")
    assert f"workspace {ws}/src" in err and f"install trees {tmp_path}/share/robot_msgs" in err
    assert "diffctl's types (" in err
    p = python("import geometry_msg")
    assert "did you mean 'geometry_msgs'" in p.stderr
    # a name that is no interface package keeps Python's own message
    p = python("import surely_not_a_module_xyz")
    assert p.stderr.strip().splitlines()[-1] == "ModuleNotFoundError: No module named 'surely_not_a_module_xyz'"


def test_unknown_type_in_a_known_package() -> None:
    out = run_ours(r'''
obs('msg', lambda: __import__('geometry_msgs.msg', fromlist=['Twistt']).Twistt)
def imp():
    from std_srvs.srv import Triger  # noqa
obs('from', imp)
from diffctl.interfaces import get_interface
obs('get', lambda: get_interface('geometry_msgs/msg/Twistt'))
obs('short', lambda: get_interface('geometry_msgs/Twist'))
obs('action', lambda: get_interface('example_interfaces/action/Fibonacci').Impl.SendGoalService.Request())
''')
    assert out["msg"] == ["raise", "AttributeError", "module 'geometry_msgs.msg' has no attribute 'Twistt'"]
    assert out["from"][:2] == ["raise", "ImportError"] and "Triger" in out["from"][2]
    assert out["get"][:2] == ["raise", "ImportError"] and "did you mean 'Twist'" in out["get"][2]
    assert out["short"] == ["ok", "<class 'geometry_msgs.msg._twist.Twist'>"]
    assert out["action"][1].startswith("example_interfaces.action.Fibonacci_SendGoal_Request(goal_id=")


def test_a_real_package_on_sys_path_wins(tmp_path: Path) -> None:
    real = tmp_path / "ros" / "std_msgs" / "msg"
    real.mkdir(parents=True)
    (real.parent / "__init__.py").write_text("")
    (real / "__init__.py").write_text("String = 'the real one'\n")
    p = python("from std_msgs.msg import String; print(String)\nfrom geometry_msgs.msg import Twist; print(Twist)",
               {"PYTHONPATH": f"{tmp_path / 'ros'}"})
    assert p.stdout.splitlines() == ["the real one", "<class 'geometry_msgs.msg._twist.Twist'>"], p.stderr


def test_malformed_interface_file_is_located(tmp_path: Path) -> None:
    pkg = tmp_path / "ws" / "src" / "bad_msgs"
    (pkg / "msg").mkdir(parents=True)
    (pkg / "package.xml").write_text("<package><name>bad_msgs</name></package>")
    (pkg / "CMakeLists.txt").write_text(
        'project(bad_msgs)\nrosidl_generate_interfaces(${PROJECT_NAME} "msg/Bad.msg")\n')
    (pkg / "msg" / "Bad.msg").write_text("# ok\nfloat64 x\nint8 small 300\n")
    p = python("from bad_msgs.msg import Bad", {"DIFFCTL_WORKSPACE": str(tmp_path / "ws")})
    last = p.stderr.strip().splitlines()[-1]
    assert last.endswith(f"{pkg / 'msg' / 'Bad.msg'}:3: small: int8 value 300 out of range [-128, 127]"), last
    (pkg / "msg" / "Bad.msg").write_text("Vector3 v\n")
    p = python("from bad_msgs.msg import Bad", {"DIFFCTL_WORKSPACE": str(tmp_path / "ws")})
    last = p.stderr.strip().splitlines()[-1]
    assert last.endswith("Bad.msg: bad_msgs/msg/Bad: field 'v' has type bad_msgs/msg/Vector3, which package "
                         "bad_msgs does not define (did you mean 'geometry_msgs/msg/Vector3'?)"), p.stderr


@pytest.mark.parametrize("text, error", [
    ("floatt64 x", "invalid type 'floatt64'"),
    ("float64 X", "invalid field name 'X'"),
    ("int32 a\nint32 a", "duplicate field 'a'"),
    ("int32 lower=1", "invalid constant name 'lower'"),
    ("int32[0] a", "the size must be > 0"),
    ("string<=3 s \"toolong\"", "longer than its bound 3"),
])
def test_parser_errors(text: str, error: str) -> None:
    from diffctl.interfaces.idl import InterfaceError, parse_message

    with pytest.raises(InterfaceError, match=error.replace("[", r"\[")):
        parse_message(text, "p/msg/T", "T.msg")


def test_the_hooks_list_of_packages_is_the_registrys() -> None:
    from diffctl.interfaces import hook, registry

    assert set(registry.diffctl_packages()) == hook.KNOWN


def test_install_trees_and_the_workspace_before_them(tmp_path: Path) -> None:
    prefix = tmp_path / "install"
    (prefix / "share" / "tree_msgs" / "msg").mkdir(parents=True)
    (prefix / "share" / "tree_msgs" / "msg" / "Level.msg").write_text("float32 level 0.25\n")
    (prefix / "share" / "my_msgs" / "msg").mkdir(parents=True)
    (prefix / "share" / "my_msgs" / "msg" / "Level.msg").write_text("int8 installed\n")
    ws = tmp_path / "ws"
    pkg = ws / "src" / "my_msgs"
    (pkg / "msg").mkdir(parents=True)
    (pkg / "package.xml").write_text("<package><name>my_msgs</name></package>")
    (pkg / "CMakeLists.txt").write_text('project(my_msgs)\nrosidl_generate_interfaces(${PROJECT_NAME} msg/Level.msg)\n')
    (pkg / "msg" / "Level.msg").write_text("int8 from_source\n")
    p = python("from tree_msgs.msg import Level; print(Level())\nfrom my_msgs.msg import Level; print(Level())",
               {"AMENT_PREFIX_PATH": str(prefix), "DIFFCTL_WORKSPACE": str(ws)})
    assert p.stdout.splitlines() == ["tree_msgs.msg.Level(level=0.25)", "my_msgs.msg.Level(from_source=0)"], p.stderr


def test_a_package_with_python_code_and_interfaces(tmp_path: Path) -> None:
    """ament_cmake_python packages install their Python package and the generated msg/ beside each other:
    `mixed_pkg` is the user's own code (first on sys.path) and `mixed_pkg.msg` is generated."""
    pkg = tmp_path / "ws" / "src" / "mixed_pkg"
    (pkg / "msg").mkdir(parents=True)
    (pkg / "mixed_pkg").mkdir()
    (pkg / "mixed_pkg" / "__init__.py").write_text("WHO = 'user code'\n")
    (pkg / "package.xml").write_text("<package><name>mixed_pkg</name></package>")
    (pkg / "CMakeLists.txt").write_text("project(mixed_pkg)\nament_python_install_package(${PROJECT_NAME})\n"
                                        'rosidl_generate_interfaces(${PROJECT_NAME} "msg/Status.msg")\n')
    (pkg / "msg" / "Status.msg").write_text("uint8 OK=0\nuint8 level\nstring message\n")
    p = python("import mixed_pkg\nfrom mixed_pkg.msg import Status\nprint(mixed_pkg.WHO, Status(level=2), Status.OK)",
               {"DIFFCTL_WORKSPACE": str(tmp_path / "ws"), "PYTHONPATH": f"{OVERLAY_PATH}:{pkg}"})
    assert p.stdout.strip() == "user code mixed_pkg.msg.Status(level=2, message='') 0", p.stderr


def test_workspace_found_from_inside_a_package_with_its_own_src(tmp_path: Path) -> None:
    """`python my_node.py` run inside a package whose C++ sources are in src/: the workspace is further up."""
    pkg = tmp_path / "ws" / "src" / "robot_msgs"
    (pkg / "msg").mkdir(parents=True)
    (pkg / "src").mkdir()
    (pkg / "src" / "node.cpp").write_text("int main() {}\n")
    (pkg / "package.xml").write_text("<package><name>robot_msgs</name></package>")
    (pkg / "CMakeLists.txt").write_text(
        'project(robot_msgs)\nrosidl_generate_interfaces(${PROJECT_NAME} "msg/Ping.msg")\n')
    (pkg / "msg" / "Ping.msg").write_text("uint32 seq\n")
    p = python("from robot_msgs.msg import Ping; print(Ping(seq=3))", cwd=pkg)
    assert p.stdout.strip() == "robot_msgs.msg.Ping(seq=3)", p.stderr


def test_a_misspelt_type_of_another_package_is_located(tmp_path: Path) -> None:
    pkg = tmp_path / "ws" / "src" / "nav_extra_msgs"
    (pkg / "msg").mkdir(parents=True)
    (pkg / "package.xml").write_text("<package><name>nav_extra_msgs</name></package>")
    (pkg / "CMakeLists.txt").write_text(
        'project(nav_extra_msgs)\nrosidl_generate_interfaces(${PROJECT_NAME} "msg/Goal.msg")\n')
    (pkg / "msg" / "Goal.msg").write_text("geometry_msgs/PoseStampd pose\n")
    p = python("from nav_extra_msgs.msg import Goal", {"DIFFCTL_WORKSPACE": str(tmp_path / "ws")})
    last = p.stderr.strip().splitlines()[-1]
    assert last.endswith("Goal.msg: nav_extra_msgs/msg/Goal: field 'pose' has type geometry_msgs/msg/PoseStampd, "
                         "which package geometry_msgs does not define (did you mean "
                         "'geometry_msgs/msg/PoseStamped' or 'geometry_msgs/msg/PointStamped' or "
                         "'geometry_msgs/msg/Pose'?)"), last
