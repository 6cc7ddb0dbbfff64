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
    # valid for rosidl_adapter, but rosidl_generator_py's class for it would be a SyntaxError
    (pkg / "msg" / "Bad.msg").write_text("float64 x\nint32 from\n")
    p = python("from bad_msgs.msg import Bad", {"DIFFCTL_WORKSPACE": str(tmp_path / "ws")})
    last = p.stderr.strip().splitlines()[-1]
    assert last.endswith("Bad.msg:2: from: bad_msgs/msg/Bad: field 'from' is a Python keyword, so its message "
                         "class cannot be generated (rename it, e.g. from_value)"), p.stderr


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
    # a package declared with .idl files installs only those
    (prefix / "share" / "tree_msgs" / "srv").mkdir(parents=True)
    (prefix / "share" / "tree_msgs" / "srv" / "Probe.idl").write_text(
        "module tree_msgs { module srv { struct Probe_Request { @default (value=3) int8 depth; };\n"
        "struct Probe_Response { string<4> answer; }; }; };\n")
    ws = tmp_path / "ws"
    pkg = ws / "src" / "my_msgs"
    (pkg / "msg").mkdir(parents=True)
    (pkg / "package.xml").write_text("<package><name>my_msgs</name></package>")
    (pkg / "CMakeLists.txt").write_text('project(my_msgs)\nrosidl_generate_interfaces(${PROJECT_NAME} msg/Level.msg)\n')
    (pkg / "msg" / "Level.msg").write_text("int8 from_source\n")
    p = python("from tree_msgs.msg import Level; print(Level())\nfrom my_msgs.msg import Level; print(Level())\n"
               "from tree_msgs.srv import Probe; print(Probe.Request(), Probe.Response.get_fields_and_field_types())",
               {"AMENT_PREFIX_PATH": str(prefix), "DIFFCTL_WORKSPACE": str(ws)})
    assert p.stdout.splitlines() == ["tree_msgs.msg.Level(level=0.25)", "my_msgs.msg.Level(from_source=0)",
                                     "tree_msgs.srv.Probe_Request(depth=3) {'answer': 'string<4>'}"], p.stderr


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


BAD_TYPE_WORKSPACE = {
    "src/robot_msgs/package.xml": "<package><name>robot_msgs</name></package>",
    "src/robot_msgs/CMakeLists.txt": 'project(robot_msgs)\nrosidl_generate_interfaces(${PROJECT_NAME} "msg/Cmd.msg")\n',
    "src/robot_msgs/msg/Cmd.msg": "# a command\nfloat64 speed\nflot64 turn\n",
    "src/driver/package.xml": "<package format=\"3\"><name>driver</name><export><build_type>ament_python"
                              "</build_type></export></package>",
    "src/driver/setup.py": "from setuptools import setup\nsetup(name='driver', packages=['driver'], entry_points="
                           "{'console_scripts': ['drive = driver.drive:main']})\n",
    "src/driver/driver/__init__.py": "",
    "src/driver/driver/drive.py": "from robot_msgs.msg import Cmd\n\n\ndef main():\n    print(Cmd())\n",
    "my_node.py": "import rclpy\nfrom robot_msgs.msg import Cmd\nprint(Cmd())\n",
}


def _write(root: Path, files: dict[str, str]) -> None:
    for rel, text in files.items():
        (root / rel).parent.mkdir(parents=True, exist_ok=True)
        (root / rel).write_text(text)


def test_a_bad_msg_is_one_line_and_exit_2_under_diffctl_run_and_python(tmp_path: Path) -> None:
    """The error of a malformed workspace .msg (a bad type here; a bad default takes the same path) is the
    user's file:line and what would be valid. `diffctl run`: that one line, exit 2, as `interface show` says it.
    `python my_node.py`: Python's own report of an uncaught ImportError (diffctl leaves a user's interpreter
    alone), but trimmed to the user's import and the finder, its text the one located line."""
    ws = tmp_path / "ws"
    _write(ws, BAD_TYPE_WORKSPACE)
    cmd = ws / "src/robot_msgs/msg/Cmd.msg"
    line = f"{cmd}:3: invalid type 'flot64': a primitive (bool, byte, char, int8"
    env = ours_env({"XDG_CACHE_HOME": str(tmp_path / "cache")})
    env.pop("PYTHONPATH", None)

    def diffctl(*args: str) -> subprocess.CompletedProcess:
        return subprocess.run([sys.executable, "-m", "diffctl", *args], env=env, cwd=ws, capture_output=True,
                              text=True, timeout=60)

    for r in (diffctl("interface", "show", "robot_msgs/msg/Cmd"), diffctl("run", "driver", "drive")):
        assert r.returncode == 2, r.stderr
        assert r.stderr.startswith(f"error: {line}") and r.stderr.count("\n") == 1, r.stderr
        assert r.stdout == ""

    p = subprocess.run([sys.executable, "my_node.py"], env=env, cwd=ws, capture_output=True, text=True, timeout=60)
    assert p.returncode == 1
    lines = p.stderr.strip().splitlines()
    assert lines[-1].startswith(f"diffctl.interfaces.idl.InterfaceError: {line}"), p.stderr
    assert len(lines) == 6 and lines[1:3] == [f'  File "{ws / "my_node.py"}", line 2, in <module>',
                                              "    from robot_msgs.msg import Cmd"], p.stderr
    cmd.write_text("float64 speed\nuint8 turn 300\n")  # a bad default
    r = diffctl("run", "driver", "drive")
    assert (r.returncode, r.stderr) == (2, f"error: {cmd}:2: turn: uint8 value 300 out of range [0, 255]\n")


def _recursive_workspace(ws: Path, files: dict[str, str]) -> None:
    listed = []
    for name, text in files.items():
        kind = name.rsplit(".", 1)[1]
        listed.append(f'"{kind}/{name}"')
        _write(ws / "src/p_msgs" / kind, {name: text})
    _write(ws / "src/p_msgs", {
        "package.xml": "<package><name>p_msgs</name></package>",
        "CMakeLists.txt": f"project(p_msgs)\nrosidl_generate_interfaces(p_msgs {' '.join(listed)})\n",
    })


@pytest.mark.parametrize("files, error", [
    ({"Tree.msg": "string name\nTree[] children\n"},
     "Tree.msg:2: children: p_msgs/msg/Tree contains itself: p_msgs/msg/Tree.children → p_msgs/msg/Tree"),
    ({"A.msg": "int32 n\nB b\n", "B.msg": "p_msgs/C[<=2] c\n", "C.msg": "A[1] a\n"},
     "A.msg:2: b: p_msgs/msg/A contains itself: p_msgs/msg/A.b → p_msgs/msg/B.c → p_msgs/msg/C.a → p_msgs/msg/A"),
    ({"Plan.srv": "Step first\n---\nbool ok\n", "Step.msg": "int8 n\nStep next\n"},
     "Step.msg:2: next: p_msgs/msg/Step contains itself: p_msgs/msg/Step.next → p_msgs/msg/Step"),
])
def test_a_recursive_interface_is_refused_where_it_is_defined(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                              files: dict[str, str], error: str) -> None:
    """rosidl cannot build a type that contains itself (directly, through others, in arrays; its type-hash
    generator fails on it): refused when its package is read, naming the cycle and the line — again on a
    second import, never half loaded."""
    from diffctl.interfaces import hook, registry, workspace
    from diffctl.interfaces.idl import InterfaceError

    ws = tmp_path / "ws"
    _recursive_workspace(ws, files)
    monkeypatch.setenv("DIFFCTL_WORKSPACE", str(ws))
    for forget in (registry.reset, workspace.reset, hook._workspace_dirs.clear):
        forget()
    try:
        for _ in range(2):
            with pytest.raises(InterfaceError) as e:
                registry.package("p_msgs")
            assert error in str(e.value) and "cannot be recursive" in str(e.value), str(e.value)
    finally:
        for forget in (registry.reset, workspace.reset, hook._workspace_dirs.clear):
            forget()


def test_a_recursive_interface_is_one_line_in_interface_show_and_an_import(tmp_path: Path) -> None:
    """Before: accepted by `interface show`, then a RecursionError of 2,995 lines at first use."""
    ws = tmp_path / "ws"
    _recursive_workspace(ws, {"Tree.msg": "string name\nTree[] children\n"})
    error = "Tree.msg:2: children: p_msgs/msg/Tree contains itself: p_msgs/msg/Tree.children → p_msgs/msg/Tree"
    env = ours_env({"DIFFCTL_WORKSPACE": str(ws), "XDG_CACHE_HOME": str(tmp_path / "cache")})
    shown = subprocess.run([sys.executable, "-m", "diffctl", "interface", "show", "p_msgs/msg/Tree"],
                           env=env, capture_output=True, text=True, timeout=60)
    assert shown.returncode == 2 and shown.stderr.count("\n") == 1 and error in shown.stderr, shown.stderr
    p = python("from p_msgs.msg import Tree\nprint(Tree())", env)
    assert error in p.stderr.strip().splitlines()[-1] and "RecursionError" not in p.stderr, p.stderr


def test_none_of_diffctls_own_interfaces_contains_itself() -> None:
    """diffctl's packages skip the recursion check when they load (they are Jazzy's definitions); this is it."""
    from diffctl.interfaces import registry, typedefs

    defs = typedefs.definitions()
    names = sorted(registry.diffctl_packages())
    for name in names:
        registry.package(name)
    own = [t for t in registry._types if t.split("/")[0] in names]
    assert len(own) > 400
    assert [t for t in own if registry._cycle_from(t, defs)] == []
