"""A .msg file's types, defaults and constants are read as rosidl_adapter reads them (the oracle venv's parser runs on
the same lines): in string arrays quoted elements keep their commas and unescape their own quote, unquoted
ones run to the next comma and are trimmed, a trailing comma adds nothing; a quoted string refuses an
unescaped inner quote of its kind; another package's type is package/Name, not package/msg/Name;
constant names take single underscores; and what rosidl refuses is refused."""

from __future__ import annotations

import json

from diffctl.interfaces import idl
from tests.interfaces.programs import run_oracle

LINES = [
    r'''string[] a ["What", "a", "world", "!"]''',
    r'''string[] b ["H\"el'lo", 'Wo\'r"ld']''',
    r'''string[] c ["Hel,lo", ',World', abcd , "!,",]''',
    r'''string[3] d ['x', "y,z" ,  w  ]''',
    r'''string<=5[<=3] e ["abc", 'de']''',
    r'''string[] f []''',
    r'''string[] g ["a\\b", 'c\"d', "e'f"]''',
    r'''string[] h [ "spaced" , 'also' ,bare words ]''',
    r'''wstring[] i ["ä,ö", 'ü']''',
    r'''string[] j [,"a"]''',
    r'''string[] k ["a",,"b"]''',
    r'''string[] l ["unclosed]''',
    r'''string[2] m ["one", "two", "three"]''',
    r'''string<=2[] n ["abc"]''',
    r'''string[] o ["'quoted'", '"dq"']''',
    r"string a 'it''s'",
    r'''string a "dq\"inner"''',
    r'''string S="a"b"''',
    r'''string a "'x'"''',
    r'''string a hello world''',
    r'''string a "a#b"''',
    r'''string S='a' ''',
    r'''float64 a -.5''',
    r'''int32 a 0x10''',
    r'''bool a TRUE''',
    r'''uint8 a 256''',
    r'''int32 A=5 # c''',
    r'''geometry_msgs/msg/Point p''',
    r'''geometry_msgs/Point p''',
    r'''string<=0 a''',
    r'''int32 C__A=1''',
    r'''int32 C_=1''',
    r'''int32 C_1=1''',
]

ORACLE = r'''
from rosidl_adapter.parser import parse_message_string
for i, line in enumerate(LINES):
    def read(line=line):
        spec = parse_message_string('pkg', 'M', line)
        return [f.default_value for f in spec.fields], [(c.name, c.value) for c in spec.constants]
    obs(str(i), read)
'''


def test_defaults_and_constants_as_rosidl_adapter() -> None:
    real = run_oracle(f"LINES = {json.dumps(LINES)}\n" + ORACLE)
    ours = {}
    for i, line in enumerate(LINES):
        try:
            td = idl.parse_message(line, "pkg/msg/M")
            fields = [td.defaults.get(n) for n, _ in td.fields if n != idl.EMPTY_MEMBER]
            ours[str(i)] = ["ok", repr((fields, [(c[0], c[2]) for c in td.constants]))]
        except idl.InterfaceError:
            ours[str(i)] = ["raise"]
    # rosidl's exception types differ (InvalidValue, ValueError, …): that both refuse is what matters
    assert ours == {k: v if v[0] == "ok" else ["raise"] for k, v in real.items()}, (ours, real)


SERVICES = ["int32 a\n---\nint32 b", "int32 a\n--- \nint32 b", "int32 a\n  ---\nint32 b", "int32 a\n---  # c\nint32 b",
            "---", "int32 a\n---\nint32 b\n---\nint32 c", "# only\n---\n# comment"]

SERVICE_ORACLE = r'''
from rosidl_adapter.parser import parse_service_string
for i, text in enumerate(SERVICES):
    def read(text=text):
        s = parse_service_string('pkg', 'S', text)
        return [f.name for f in s.request.fields], [f.name for f in s.response.fields]
    obs(str(i), read)
'''


def test_service_separator_as_rosidl_adapter() -> None:
    """Only a line that is exactly `---` separates request from response."""
    real = run_oracle(f"SERVICES = {json.dumps(SERVICES)}\n" + SERVICE_ORACLE)
    ours = {}
    for i, text in enumerate(SERVICES):
        try:
            req, resp = idl.interface_defs("pkg/srv/S", text)[:2]
            ours[str(i)] = ["ok", repr(tuple([n for n, _ in t.fields if n != idl.EMPTY_MEMBER] for t in (req, resp)))]
        except idl.InterfaceError:
            ours[str(i)] = ["raise"]
    assert ours == {k: v if v[0] == "ok" else ["raise"] for k, v in real.items()}, (ours, real)
