"""Interface packages declared with .idl files (rosidl_generate_interfaces takes them as it takes .msg files):
a workspace test_msgs made of the real package's .idl files behaves and hashes as the real generated
test_msgs, and a hand-written .idl (IDL-only spellings: char and wchar, typedefs, unsigned/long names,
constants modules, annotations, comments) gives the classes rosidl_generator_py gives."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from tests.interfaces.programs import assert_same, run_oracle, run_ours
from tests.interfaces.test_workspace_interfaces import MSGS, PROGRAM
from tests.oracle import jazzy_venv

PACKAGE_XML = """<?xml version="1.0"?>
<package format="3">
  <name>{name}</name>
  <version>0.0.1</version>
  <description>interfaces from .idl files</description>
  <maintainer email="a@b.c">a</maintainer>
  <license>Apache-2.0</license>
  <buildtool_depend>ament_cmake</buildtool_depend>
  <buildtool_depend>rosidl_default_generators</buildtool_depend>
  <member_of_group>rosidl_interface_packages</member_of_group>
  <export><build_type>ament_cmake</build_type></export>
</package>
"""


def _package(ws: Path, name: str, files: dict[str, str]) -> None:
    pkg = ws / "src" / name
    for rel, text in files.items():
        (pkg / rel).parent.mkdir(parents=True, exist_ok=True)
        (pkg / rel).write_text(text, encoding="utf-8")
    (pkg / "package.xml").write_text(PACKAGE_XML.format(name=name))
    listed = "\n".join(f'  "{rel}"' for rel in sorted(files))
    (pkg / "CMakeLists.txt").write_text(
        f"cmake_minimum_required(VERSION 3.8)\nproject({name})\nfind_package(rosidl_default_generators REQUIRED)\n"
        f"rosidl_generate_interfaces(${{PROJECT_NAME}}_custom\n{listed}\n  DEPENDENCIES builtin_interfaces\n)\n"
        "ament_package()\n")


@pytest.fixture(scope="module")
def idl_workspace(tmp_path_factory: pytest.TempPathFactory) -> Path:
    ws = tmp_path_factory.mktemp("idlws")
    share = jazzy_venv.share("test_msgs")
    _package(ws, "test_msgs", {f"{f.parent.name}/{f.name}": f.read_text(encoding="utf-8")
                               for f in sorted(share.glob("*/*.idl"))})
    return ws


def test_idl_declared_package_behaves_and_hashes_as_the_real_build(idl_workspace: Path) -> None:
    program = PROGRAM % MSGS
    env = {"ROS_PYTHON_CHECK_FIELDS": "1"}
    real_hashes = {}
    for path in sorted(jazzy_venv.share("test_msgs").glob("*/*.json")):
        for entry in json.loads(path.read_text())["type_hashes"]:
            real_hashes[entry["type_name"]] = entry["hash_string"]
    ours = run_ours(program + f"NAMES = {sorted(real_hashes)!r}\n" + r'''
from diffctl.interfaces import types
for n in NAMES:
    obs('hash ' + n, lambda n=n: types.type_hash(n))
''', {**env, "DIFFCTL_WORKSPACE": str(idl_workspace)})
    hashes = {k[5:]: ours.pop(k) for k in list(ours) if k.startswith("hash ")}
    assert hashes == {k: ["ok", v] for k, v in real_hashes.items()}
    assert_same(ours, run_oracle(program, env))


HAND_WRITTEN = r"""
// A message written in IDL by hand, with what a .msg file cannot say.
#include "geometry_msgs/msg/Point.idl"

module idl_only {
  module msg {
    module Chars_Constants {
      const char LETTER = 120;
      const uint64 BIG = 18446744073709551615;
      const string GREETING = "hi" " there";
      const double RATIO = -2.5e-3;
    };
    typedef char char__4[4];
    /* typedefs name arrays, as rosidl_adapter writes them */
    typedef geometry_msgs::msg::Point Points__2[2];
    @verbatim (language="comment", text=
      "Characters" "\n" "and the rest")
    struct Chars {
      char c;  // one character
      @default (value=65)
      char c_default;
      wchar w;
      char__4 four;
      sequence<char> cs;
      sequence<char, 3> cs3;
      sequence<wchar> ws;
      @default (value="(1.5, -2.0)")
      sequence<double, 4> ds;
      long l;
      unsigned short us;
      long long ll, ll2;
      @unit (value="m")
      float f;
      geometry_msgs::msg::Point p;
      Points__2 ps;
    };
  };
};
"""

GENERATE_REAL = r'''
import os, pathlib, tempfile
from rosidl_generator_py.cli import GeneratePython
from rosidl_generator_type_description import generate_type_hash
tmp = pathlib.Path(tempfile.mkdtemp())
(tmp / "src" / "msg").mkdir(parents=True)
(tmp / "src" / "msg" / "Chars.idl").write_text(IDL, encoding="utf-8")
GeneratePython("py").generate("idl_only", [f"{tmp}/src:msg/Chars.idl"], [], tmp / "gen" / "idl_only")
(tmp / "gen" / "idl_only" / "__init__.py").write_text("")
share = pathlib.Path(os.environ["AMENT_PREFIX_PATH"]) / "share"
(tmp / "args.json").write_text(json.dumps({
    "package_name": "idl_only", "output_dir": str(tmp / "td"), "idl_tuples": [f"{tmp}/src:msg/Chars.idl"],
    "include_paths": [f"geometry_msgs:{share / 'geometry_msgs'}"]}))
generate_type_hash(str(tmp / "args.json"))
HASH = json.loads((tmp / "td" / "msg" / "Chars.json").read_text())["type_hashes"][0]["hash_string"]
sys.path.insert(0, str(tmp / "gen"))
'''

OBSERVE = r'''
from idl_only.msg import Chars as C
obs('hash', lambda: HASH)
obs('fields', C.get_fields_and_field_types)
obs('slot types', lambda: [slot(t) for t in C.SLOT_TYPES])
obs('constants', lambda: (C.LETTER, C.BIG, C.GREETING, C.RATIO))
obs('defaults', lambda: (C.C_DEFAULT__DEFAULT, C.DS__DEFAULT))
obs('repr', C)
obs('kinds', lambda: [kind(getattr(C(), f)) for f in C.get_fields_and_field_types()])
obs('eq', lambda: (C() == C(), C(c='a') == C()))
obs('doc', lambda: C.__doc__)
VALUES = {"a": "a", "ab": "ab", "65": 65, "e-acute": "\u00e9", "zhe": "\u0436", "chars": ["a", "b"],
          "wide chars": ["\u0436"], "str": "abc", "four": ["1", "2", "3", "4"], "three": ["1", "2", "3"],
          "ints": [1, 2], "floats5": [1.0] * 5, "big": 2**40}
for field in ("c", "w", "four", "cs", "cs3", "ws", "ds", "l", "us"):
    for label, value in VALUES.items():
        for check in (False, True):
            def set_it(field=field, value=value, check=check):
                m = C()
                m._check_fields = check  # C(check_fields=True) itself fails: rosidl refuses every wchar
                setattr(m, field, value)
                return getattr(m, field)
            obs(f"{field}={label} check={check}", set_it)
obs('constructed', lambda: C(c='z', cs=['x', 'y'], ws=['\u0436'], four=['a', 'b', 'c', 'd']))
obs('checked construction', lambda: C(check_fields=True))
'''


WIRE = r'''
from diffctl.interfaces import serialize, deserialize
m = C(c='\u00e9', cs=['a', 'bc', ''], w='\u0436')
raw = serialize(m)[4:]
obs('wire c', lambda: raw[:1].hex())
obs('wire cs', lambda: raw[8:12].hex() + ' ' + raw[12:15].hex(' '))
obs('wire w', lambda: raw[2:4].hex())
obs('wire back', lambda: f"{deserialize(serialize(m), C).cs} {deserialize(serialize(m), C).w}")
'''


def test_hand_written_idl_as_rosidl_generator_py(tmp_path: Path) -> None:
    """Classes and type hash of an .idl only a hand can write: rosidl_generator_py and rosidl's type
    description generator (the oracle venv's) against diffctl's workspace finder."""
    oracle = run_oracle(f"IDL = {HAND_WRITTEN!r}\n" + GENERATE_REAL + OBSERVE)
    assert oracle["hash"][1].startswith("RIHS01_") and oracle["repr"][0] == "ok", oracle
    _package(tmp_path, "idl_only", {"msg/Chars.idl": HAND_WRITTEN})
    ours = run_ours("from diffctl.interfaces import type_hash\nfrom idl_only.msg import Chars\n"
                    "HASH = type_hash(Chars)\n" + OBSERVE + WIRE, {"DIFFCTL_WORKSPACE": str(tmp_path)})
    wire = {k: ours.pop(k)[1] for k in list(ours) if k.startswith("wire ")}
    assert_same(ours, oracle)
    # The oracle venv has no compiled type support for a new package: the wire is checked against what
    # rosidl's C conversion and Fast CDR do (a char is the first UTF-8 byte of its str, a wchar a uint16),
    # bytes once compared with rosidl_typesupport_fastrtps_c's code for such a type, built by hand.
    assert wire == {"wire c": "c3", "wire cs": "03000000 61 62 00", "wire w": "3604",
                    "wire back": "['a', 'b', '\\x00'] ж"}, wire


def test_every_installed_idl_reads_as_its_ros_file() -> None:
    """rosidl installs each interface's .idl (rosidl_adapter's translation) beside its .msg/.srv/.action: for
    every one in the oracle venv (about 200, all field kinds, defaults and constants of Jazzy's packages) the
    definitions read from the .idl equal those read from the ROS file."""
    from diffctl.interfaces import idl

    checked = 0
    for path in sorted(jazzy_venv.share("").glob("*/*/*.idl")):
        pkg, kind = path.parent.parent.name, path.parent.name
        ros = path.with_suffix("." + kind)
        name = f"{pkg}/{kind}/{path.stem}"
        from_ros = idl.interface_defs(name, ros.read_text(encoding="utf-8"), str(ros))
        from_idl = idl.interface_defs(name, path.read_text(encoding="utf-8"), str(path))
        assert [(t.name, t.constants, t.fields, t.defaults) for t in from_idl] == \
            [(t.name, t.constants, t.fields, t.defaults) for t in from_ros], name
        checked += 1
    assert checked > 150


@pytest.mark.parametrize("body, line, error", [
    ("struct T { floatt64 x; };", 2, "unknown type 'floatt64'"),
    ("struct T { int8 a; int8 a; };", 2, "duplicate member 'a'"),
    ("struct T {\n  @default (value=300)\n  int8 small;\n};", 4, "small: int8 value 300 out of range [-128, 127]"),
    ("struct T {\n  @default (value=\"(1, 2)\")\n  int32 a[3];\n};", 4, "the default has 2 values, the array 3"),
    ("struct T { sequence<int32[3]> a; };", 2, "expected '>', found '['"),
    ("struct T { string<0> s; };", 2, "the string bound must be a positive integer"),
    ("struct T { long double d; };", 2, "'long double' has no ROS 2 Python or wire form"),
    ("struct Other { int8 a; };", None, "defines no struct T in module p::msg (found: p/msg/Other)"),
    ("module T_Constants { const int8 C = 1.5; };\nstruct T { int8 a; };", 2, "C: 1.5 is not an integer"),
    ("struct T { int8 a; }", 3, "expected ';', found '}'"),
    ("struct T { int8 a; };\n}; };\n};", 4, "unexpected '}'"),
])
def test_malformed_idl_names_file_and_line(body: str, line: int | None, error: str) -> None:
    from diffctl.interfaces.idl import InterfaceError, interface_defs

    with pytest.raises(InterfaceError) as e:
        interface_defs("p/msg/T", "module p { module msg {\n" + body + "\n}; };\n", "p/msg/T.idl")
    assert str(e.value).startswith(f"p/msg/T.idl{'' if line is None else f':{line}'}: "), str(e.value)
    assert error in str(e.value), str(e.value)
