"""Bad input on the surfaces added last, property-based as tests/reliability/test_fuzz_inputs.py does for the older
ones: workspace interface definitions (.msg/.srv/.action texts, and packages whose types refer to each other),
environment hooks (.dsv and shell), Fuel URIs (as includes of a world) and `gz` command-line arguments. Each
input works or fails with the project's own error and a one-line message — never another exception (a
traceback), a RecursionError, a hang or a native crash. Each fuzz is a few seconds (CI budget).
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import pytest
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

from diffctl.errors import DiffctlError
from diffctl.interfaces import idl
from tests.reliability.test_fuzz_inputs import mutated, works_or_project_error

REPO = Path(__file__).resolve().parents[2]
JAZZY = REPO / "diffctl" / "interfaces" / "jazzy"
FUZZ = settings(max_examples=60, deadline=None,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture])


def one_line(e: DiffctlError) -> None:
    text = str(e)
    assert text.strip() and "\n" not in text.strip() and "Traceback" not in text, text


# ------------------------------------------------------------------------------------------------ interface texts

INTERFACE_TEXTS = {
    "msg": (JAZZY / "example_interfaces/msg/MultiArrayLayout.msg").read_text()
    + "uint8 KIND=3\nstring<=8 label \"cone\"\nfloat64[3] xyz [1, 2, 3]\nint8[<=4] small\n",
    "srv": (JAZZY / "example_interfaces/srv/AddTwoInts.srv").read_text(),
    "action": (JAZZY / "example_interfaces/action/Fibonacci.action").read_text(),
}
IDL_WORDS = ("float64", "flot64", "int8", "uint8 300", "string<=", "<=0", "[0]", "[<=", "[", "]", "=", " = 1",
             "---", "\n---\n", "#", "geometry_msgs/Pose", "Self", "p/msg/Self", "std_msgs/Header", "bool maybe",
             "'", '"', "\\", "\t", "0x1F", "1e400", "nan", "X", "a__b", "_a", "structure_needs_at_least_one_member")


@FUZZ
@given(kind=st.sampled_from(sorted(INTERFACE_TEXTS)), data=st.data())
def test_interface_texts_parse_or_say_where(kind: str, data: st.DataObject) -> None:
    text = data.draw(mutated(INTERFACE_TEXTS[kind], IDL_WORDS))
    try:
        idl.interface_defs(f"p_msgs/{kind}/T", text, "T." + kind)
    except DiffctlError as e:
        one_line(e)
        assert isinstance(e, ImportError), "an import of the package must be able to raise it"


# A package of a few message types that refer to each other (arrays, bounded sequences, other packages): it loads,
# or is refused in one line — a cycle included — and never recurses without end at first use.
field_types = st.sampled_from(["A", "B", "C", "p_msgs/A", "A[]", "B[2]", "C[<=3]", "geometry_msgs/Point",
                               "std_msgs/Header[]", "int32", "Nope", "nope_msgs/X", "string"])


@FUZZ
@given(fields=st.fixed_dictionaries({n: st.lists(field_types, max_size=3) for n in "ABC"}))
def test_interface_packages_load_or_are_refused_in_one_line(fields: dict[str, list[str]], tmp_path: Path,
                                                           monkeypatch: pytest.MonkeyPatch) -> None:
    import sys

    from diffctl.client.serialization import serialize_message
    from diffctl.interfaces import classes, hook, registry, typedefs, workspace

    ws = tmp_path / f"ws{abs(hash(repr(fields)))}"
    pkg = ws / "src" / "p_msgs"
    (pkg / "msg").mkdir(parents=True)
    (pkg / "package.xml").write_text("<package><name>p_msgs</name></package>")
    (pkg / "CMakeLists.txt").write_text('rosidl_generate_interfaces(p_msgs "msg/A.msg" "msg/B.msg" "msg/C.msg")\n')
    for name, types in fields.items():
        (pkg / "msg" / f"{name}.msg").write_text("".join(f"{t} f{i}\n" for i, t in enumerate(types)))
    monkeypatch.setenv("DIFFCTL_WORKSPACE", str(ws))
    defs = typedefs.definitions()
    before = dict(defs)

    def forget() -> None:
        for f in (registry.reset, workspace.reset, hook._workspace_dirs.clear):
            f()
        for module in [m for m in sys.modules if m == "p_msgs" or m.startswith("p_msgs.")]:
            del sys.modules[module]

    forget()
    try:
        try:
            registry.package("p_msgs")
        except DiffctlError as e:
            one_line(e)
            return
        for name in "ABC":  # loaded: every class builds, and its default instance serializes
            serialize_message(classes.interface_class(f"p_msgs/msg/{name}")())
    finally:
        defs.clear()
        defs.update(before)
        forget()


# ------------------------------------------------------------------------------------------------ environment hooks

DSV_TEXT = ("prepend-non-duplicate;GZ_SIM_RESOURCE_PATH;share/p/models;share\n"
            "prepend-non-duplicate-if-exists;GZ_SIM_RESOURCE_PATH;share/p/nowhere\n"
            "append-non-duplicate;SDF_PATH;share/p/models\nset;P_HOME;share/p\nset-if-unset;P_MODE;sim\n"
            "source;share/p/environment/more.sh\n")
DSV_WORDS = (";", ";;", "prepend-non-duplicate", "prepend-unique", "set", "source", "source;", "source;x.dsv",
             "source;/etc/passwd.sh", "\n", "#", "@PROJECT_NAME@", "$HOME", "..", "/", "\x00", "é")
SH_TEXT = 'export P_SH=1\nament_prepend_unique_value GZ_SIM_RESOURCE_PATH "$AMENT_CURRENT_PREFIX/share"\n'
SH_WORDS = ("if [", "fi", "then", "(", ")", "'", '"', "`", "$(", "exit 3", "return 1", "\n", "export A=", ";",
            "unset PATH", "ament_append_value")


@FUZZ
@given(data=st.data())
def test_environment_hooks_apply_or_say_where(data: st.DataObject, tmp_path: Path) -> None:
    from diffctl.workspace.env_hooks import HookEnv, process_dsv

    prefix = tmp_path / "prefix"
    state = HookEnv({"PATH": os.environ.get("PATH", "")})
    dsv = str(prefix / "share/p/environment/p.dsv")
    state.files[dsv] = data.draw(mutated(DSV_TEXT, DSV_WORDS))
    state.origins[dsv] = str(tmp_path / "src/p/hooks/p.dsv.in")
    with_shell = data.draw(st.booleans())
    if with_shell:  # a shell hook costs a bash: a few of them per run
        state.files[str(prefix / "share/p/environment/more.sh")] = data.draw(mutated(SH_TEXT, SH_WORDS))
    try:
        process_dsv(state, dsv, str(prefix))
    except DiffctlError as e:
        one_line(e)
        assert str(prefix) not in str(e) or "hooks/p.dsv.in" in str(e) or ".sh" in str(e), str(e)


# ------------------------------------------------------------------------------------------------ Fuel URIs

FUEL_URI = "https://fuel.gazebosim.org/1.0/OpenRobotics/models/Ground Plane/2/files/meshes/plane.dae"
URI_WORDS = ("/", "//", "models", "worlds", "tip", "files", "%20", " ", "0", "-1", "99999999999999999999", "?",
             "#", "http://", "fuel://", ":", "@", "..", "\x00", "ünï", "Sun", "Ground Plane")
WORLD = ('<?xml version="1.0"?>\n<sdf version="1.9"><world name="w">\n<include><uri>{uri}</uri></include>\n'
         "</world></sdf>\n")


@FUZZ
@given(data=st.data())
def test_fuel_uris_resolve_or_say_why(data: st.DataObject, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    from xml.sax.saxutils import escape

    from diffctl.description.sdf_loader import load_world
    from diffctl.fuel import resolve
    from diffctl.fuel.uri import parse_fuel_uri

    monkeypatch.setenv("DIFFCTL_FUEL_OFFLINE", "1")
    monkeypatch.setenv("GZ_FUEL_CACHE_PATH", str(tmp_path / "fuel-cache"))
    monkeypatch.setattr(resolve, "_failed", {})
    uri = data.draw(mutated(FUEL_URI, URI_WORDS))
    parse_fuel_uri(uri)  # a URL or not, never an exception
    works_or_project_error(resolve.resolve_fuel, uri)
    for strict in ("0", "1"):
        monkeypatch.setenv("DIFFCTL_FUEL_SKIP_MISSING", strict)
        path = tmp_path / "w.sdf"
        path.write_text(WORLD.format(uri=escape(uri)), encoding="utf-8")
        try:
            load_world(path)
        except DiffctlError as e:
            one_line(e)


# ------------------------------------------------------------------------------------------------ gz arguments

GZ_WORDS = ["sim", "topic", "service", "model", "fuel", "download", "-r", "-s", "-g", "-v", "-v4", "-rs", "-z",
            "--iterations", "--iterations=-1", "--seed", "--seed=x", "--rtf", "--gui", "--levels", "--it", "-l",
            "-i", "-e", "-p", "-t", "/clock", "-m", "gz.msgs.Twist", "-n", "x", "-d", "--json-output",
            "--reqtype", "--reptype", "--timeout", "--req", "-u", "--list", "-j", "empty.sdf", "'", '"',
            "linear: {x: 0.5}", "--", "-", "1e400", "nan", ""]


@FUZZ
@given(args=st.lists(st.sampled_from(GZ_WORDS) | st.text(max_size=8), max_size=7))
@example(args=["topic", "\n"])  # found by this fuzz: argparse named the argument as it was, a newline
def test_gz_arguments_parse_or_say_why(args: list[str], monkeypatch: pytest.MonkeyPatch, capsys) -> None:
    from diffctl.errors import NoRouterError
    from diffctl.gz import cli
    from diffctl.sim.cli import parse_gz_args

    def no_router() -> Any:
        raise NoRouterError("no Zenoh router answers (the fuzz runs none)")

    monkeypatch.setattr(cli, "_session", no_router)
    monkeypatch.setattr(cli, "_gui_client", lambda: 0)
    monkeypatch.setattr(os, "execv", lambda *a: (_ for _ in ()).throw(AssertionError("parsed: would run")))
    works_or_project_error(parse_gz_args, args)
    if args and args[0] in ("sim", "gazebo"):
        return  # a parse that succeeds would start the simulator: parse_gz_args above is that parse
    capsys.readouterr()
    try:
        cli.dispatch(args)
    except DiffctlError as e:
        one_line(e)
        assert capsys.readouterr().err == "", "the error is the one line diffctl prints"
    except SystemExit as e:  # -h/--help
        assert e.code == 0, args
