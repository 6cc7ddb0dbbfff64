""".idl interface files (the OMG IDL subset rosidl_parser reads, Jazzy) → type definitions.

What rosidl_adapter writes from .msg/.srv/.action files and what people write by hand: nested `module`s
naming the package and the kind, `struct`s whose members may carry `@default (value=…)`, `typedef`s of
arrays, and constants in a `module <Struct>_Constants`. Unlike a .msg `char` (uint8), an IDL `char` is a
character (a 1-character str in Python, 1 byte on the wire) and `wchar` a wide one. `#include` lines are
ignored, as every referenced type is found by its package. Errors name the file and line.
"""

from __future__ import annotations

import ast
import re
from dataclasses import dataclass, field
from typing import Any

from rosbags.typesys.base import Nodetype

from diffctl.interfaces.idl import EMPTY_MEMBER, InterfaceError, TypeDef

# IDL type spellings → the definitions' primitive names (rosbags' names, as the .msg reader gives them)
_BASIC = {
    "boolean": "bool", "octet": "byte", "char": "char", "wchar": "wchar", "float": "float32",
    "double": "float64", "short": "int16", "long": "int32", "long long": "int64", "unsigned short": "uint16",
    "unsigned long": "uint32", "unsigned long long": "uint64",
    **{t: t for t in ("int8", "uint8", "int16", "uint16", "int32", "uint32", "int64", "uint64")},
}
_INT_RANGE = {t: ((0, 2**b - 1) if t[0] == "u" or t == "byte" else (-(2 ** (b - 1)), 2 ** (b - 1) - 1))
              for t, b in (("int8", 8), ("uint8", 8), ("int16", 16), ("uint16", 16), ("int32", 32),
                           ("uint32", 32), ("int64", 64), ("uint64", 64), ("byte", 8))}
_SECTIONS = {"msg": ("",), "srv": ("_Request", "_Response"), "action": ("_Goal", "_Result", "_Feedback")}

_TOKEN = re.compile(r"""
    (?P<space>\s+)
  | (?P<comment>//[^\n]*|/\*.*?\*/)
  | (?P<directive>\#[^\n]*)
  | (?P<string>L?"(?:[^"\\\n]|\\.)*")
  | (?P<char>L?'(?:[^'\\\n]|\\.)+')
  | (?P<number>(?:0[xX][0-9a-fA-F]+|(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)[dDlLuU]*)
  | (?P<name>[A-Za-z_][A-Za-z0-9_]*(?:::[A-Za-z_][A-Za-z0-9_]*)*)
  | (?P<scope>::)
  | (?P<punct>[{}();,<>\[\]=@+\-])
""", re.VERBOSE | re.DOTALL)
_ESCAPES = {"n": "\n", "t": "\t", "v": "\v", "b": "\b", "r": "\r", "f": "\f", "a": "\a", "\\": "\\", "?": "?",
            "'": "'", '"': '"'}


@dataclass
class _Tok:
    kind: str
    text: str
    line: int


@dataclass
class _Scope:
    """What one module holds: its typedefs, the constants of its `X_Constants` modules, its structs."""

    path: list[str]
    typedefs: dict[str, tuple] = field(default_factory=dict)
    constants: dict[str, list[tuple[str, str, Any]]] = field(default_factory=dict)
    structs: list[TypeDef] = field(default_factory=list)


def _unescape(body: str) -> str:
    def one(m: re.Match[str]) -> str:
        s = m.group(1)
        if s[0] in _ESCAPES:
            return _ESCAPES[s[0]]
        if s[0] in "xX":
            return chr(int(s[1:], 16))
        if s[0] in "uU":
            return chr(int(s[1:], 16))
        return chr(int(s, 8))

    return re.sub(r"\\([ntvbrfa\\?'\"]|[0-7]{1,3}|[xX][0-9a-fA-F]{1,2}|[uU][0-9a-fA-F]{1,4})", one, body)


class _Reader:
    def __init__(self, text: str, source: str | None) -> None:
        self.source = source
        self.toks: list[_Tok] = []
        line, pos = 1, 0
        while pos < len(text):
            m = _TOKEN.match(text, pos)
            if m is None:
                self.fail(f"unexpected character {text[pos]!r}", line)
            kind = m.lastgroup or ""
            if kind not in ("space", "comment", "directive"):
                self.toks.append(_Tok(kind, m.group(), line))
            line += m.group().count("\n")
            pos = m.end()
        self.i = 0
        self.last_line = line

    def fail(self, what: str, line: int | None = None, **extra: Any) -> None:
        if line is None:
            line = self.toks[self.i].line if self.i < len(self.toks) else self.last_line
        raise InterfaceError(what, source=self.source, line=line, **extra)

    def peek(self, ahead: int = 0) -> _Tok | None:
        j = self.i + ahead
        return self.toks[j] if j < len(self.toks) else None

    def take(self, expected: str | None = None) -> _Tok:
        tok = self.peek()
        if tok is None:
            self.fail(f"unexpected end of file{f', expected {expected!r}' if expected else ''}")
        assert tok is not None
        if expected is not None and tok.text != expected:
            self.fail(f"expected {expected!r}, found {tok.text!r}")
        self.i += 1
        return tok

    def accept(self, text: str) -> bool:
        tok = self.peek()
        if tok is not None and tok.text == text and tok.kind in ("punct", "name"):
            self.i += 1
            return True
        return False

    def name(self) -> str:
        tok = self.take()
        if tok.kind != "name":
            self.fail(f"expected a name, found {tok.text!r}", tok.line)
        return tok.text

    # -- annotations and constant expressions ---------------------------------------------------------

    def annotations(self) -> dict[str, Any]:
        found: dict[str, Any] = {}
        while self.accept("@"):
            name = self.name()
            params: dict[str, Any] = {}
            if self.accept("("):
                while not self.accept(")"):
                    nxt = self.peek(1)
                    key = "value"
                    if self.peek() is not None and self.peek().kind == "name" and nxt is not None and nxt.text == "=":
                        key = self.name()
                        self.take("=")
                    params[key] = self.literal()
                    self.accept(",")
            found[name] = params
        return found

    def literal(self) -> Any:
        tok = self.take()
        if tok.kind == "string":
            text = _unescape(tok.text[tok.text.index('"') + 1:-1])
            while self.peek() is not None and self.peek().kind == "string":  # "a" "b" is one string
                nxt = self.take().text
                text += _unescape(nxt[nxt.index('"') + 1:-1])
            return text
        if tok.kind == "char":
            return _unescape(tok.text[tok.text.index("'") + 1:-1])
        if tok.text in ("-", "+"):
            value = self.literal()
            if not isinstance(value, (int, float)) or isinstance(value, bool):
                self.fail(f"{tok.text!r} before a non-number", tok.line)
            return -value if tok.text == "-" else value
        if tok.kind == "number":
            digits = tok.text.rstrip("dDlLuU")
            if digits.lower().startswith("0x"):
                return int(digits, 16)
            if any(c in digits for c in ".eE"):
                return float(digits)
            return int(digits, 8) if len(digits) > 1 and digits[0] == "0" else int(digits)
        if tok.text in ("TRUE", "FALSE"):
            return tok.text == "TRUE"
        self.fail(f"expected a literal value, found {tok.text!r}", tok.line)
        return None

    # -- types -------------------------------------------------------------------------------------------

    def type_spec(self, scope: _Scope, pkg: str) -> tuple:
        tok = self.take()
        word = tok.text
        if word == "sequence":
            self.take("<")
            inner = self.type_spec(scope, pkg)
            bound = 0
            if self.accept(","):
                bound = self.positive("sequence bound")
            self.take(">")
            if inner[0] in (Nodetype.ARRAY, Nodetype.SEQUENCE):
                self.fail("a sequence of arrays or sequences is not a ROS 2 type", tok.line)
            return (Nodetype.SEQUENCE, (inner, bound))
        if word in ("string", "wstring"):
            bound = 0
            if self.accept("<"):
                bound = self.positive("string bound")
                self.take(">")
            return (Nodetype.BASE, (word, bound))
        if word == "unsigned":
            word += " " + self.name()
            if word == "unsigned long" and self.accept("long"):
                word += " long"
        elif word == "long" and self.peek() is not None and self.peek().text in ("long", "double"):
            word += " " + self.name()
        if word in _BASIC:
            return (Nodetype.BASE, (_BASIC[word], 0))
        if word == "long double":
            self.fail("'long double' has no ROS 2 Python or wire form in diffctl", tok.line,
                      hint="use double")
        if tok.kind != "name":
            self.fail(f"expected a type, found {word!r}", tok.line)
        if word in scope.typedefs:
            return scope.typedefs[word]
        parts = word.split("::")
        if len(parts) == 1 and word[:1].isupper():
            parts = [*scope.path, word]
        if len(parts) != 3:
            self.fail(f"unknown type {word!r}: a basic type, a typedef or package::msg::Name", tok.line)
        return (Nodetype.NAME, "/".join(parts))

    def positive(self, what: str) -> int:
        value = self.literal()
        if not isinstance(value, int) or isinstance(value, bool) or value <= 0:
            self.fail(f"the {what} must be a positive integer, not {value!r}")
        return value

    def declarator(self, desc: tuple) -> tuple[str, tuple]:
        name = self.name()
        dims = []
        while self.accept("["):
            dims.append(self.positive("array size"))
            self.take("]")
        if len(dims) > 1 or (dims and desc[0] in (Nodetype.ARRAY, Nodetype.SEQUENCE)):
            self.fail(f"{name!r}: arrays of arrays or of sequences are not ROS 2 types")
        if dims:
            desc = (Nodetype.ARRAY, (desc, dims[0]))
        return name, desc

    # -- definitions --------------------------------------------------------------------------------------

    def definitions(self, scope: _Scope, pkg: str, scopes: list[_Scope]) -> None:
        while True:
            tok = self.peek()
            if tok is None or tok.text == "}":
                return
            notes = self.annotations()
            word = self.name()
            if word == "module":
                self.module(scope, pkg, scopes)
            elif word == "struct":
                self.struct(scope, pkg, notes)
            elif word == "typedef":
                desc = self.type_spec(scope, pkg)
                name, desc = self.declarator(desc)
                scope.typedefs[name] = desc
                self.take(";")
            elif word == "const":
                self.fail("constants belong in a module named <Struct>_Constants, as rosidl expects")
            else:
                self.fail(f"unexpected {word!r}: expected module, struct, typedef or const", tok.line)

    def module(self, outer: _Scope, pkg: str, scopes: list[_Scope]) -> None:
        line = self.peek().line if self.peek() else None
        name = self.name()
        self.take("{")
        if name.endswith("_Constants") and len(outer.path) == 2:
            consts = outer.constants.setdefault(name[: -len("_Constants")], [])
            while not self.accept("}"):
                self.annotations()
                self.take("const")
                desc = self.type_spec(outer, pkg)
                cname = self.name()
                self.take("=")
                value_line = self.peek().line if self.peek() else None
                value = self.literal()
                if desc[0] != Nodetype.BASE:
                    self.fail(f"constant {cname!r} must be of a basic or string type", value_line)
                base, bound = desc[1]
                consts.append((cname, base, self.checked(base, bound, value, cname, value_line)))
                self.take(";")
            self.take(";")
            return
        if len(outer.path) >= 2:
            self.fail(f"module {name!r} inside {'::'.join(outer.path)}: rosidl expects package::kind only", line)
        inner = _Scope([*outer.path, name])
        scopes.append(inner)
        self.definitions(inner, pkg, scopes)
        self.take("}")
        self.take(";")

    def struct(self, scope: _Scope, pkg: str, notes: dict[str, Any]) -> None:
        line = self.peek().line if self.peek() else None
        name = self.name()
        if len(scope.path) != 2:
            self.fail(f"struct {name!r} must be inside module {pkg} {{ module msg|srv|action {{ … }} }}", line)
        td = TypeDef("/".join([*scope.path, name]))
        self.take("{")
        while not self.accept("}"):
            member_notes = self.annotations()
            desc = self.type_spec(scope, pkg)
            while True:
                fline = self.peek().line if self.peek() else None
                fname, fdesc = self.declarator(desc)
                if fname in td.lines:
                    self.fail(f"duplicate member {fname!r}", fline, field=fname)
                td.fields.append((fname, fdesc))
                td.lines[fname] = fline or 0
                if "default" in member_notes:
                    td.defaults[fname] = self.default(fdesc, member_notes["default"].get("value"), fname, fline)
                if not self.accept(","):
                    break
            self.take(";")
        self.take(";")
        if not td.fields:
            td.fields.append((EMPTY_MEMBER, (Nodetype.BASE, ("uint8", 0))))
        scope.structs.append(td)

    def checked(self, base: str, bound: int, value: Any, name: str, line: int | None) -> Any:
        """A constant or default value as rosidl accepts it for `base`, range-checked."""
        where = {"field": name}
        if base == "bool":
            if not isinstance(value, bool):
                self.fail(f"{name}: {value!r} is not TRUE or FALSE", line, **where)
            return value
        if base in _INT_RANGE:
            if isinstance(value, bool) or not isinstance(value, int):
                self.fail(f"{name}: {value!r} is not an integer", line, **where)
            lo, hi = _INT_RANGE[base]
            if not lo <= value <= hi:
                self.fail(f"{name}: {base} value {value} out of range [{lo}, {hi}]", line, **where)
            return value
        if base in ("float32", "float64"):
            if isinstance(value, bool) or not isinstance(value, (int, float)):
                self.fail(f"{name}: {value!r} is not a number", line, **where)
            return float(value)
        if base in ("char", "wchar"):
            code = ord(value) if isinstance(value, str) and len(value) == 1 else value
            top = 255 if base == "char" else 0xFFFF
            if isinstance(code, bool) or not isinstance(code, int) or not 0 <= code <= top:
                self.fail(f"{name}: {value!r} is not a {base} (one character, code 0..{top})", line, **where)
            return chr(code)
        if not isinstance(value, str):
            self.fail(f"{name}: {value!r} is not a string", line, **where)
        if bound and len(value) > bound:
            self.fail(f"{name}: string value {value!r} longer than its bound {bound}", line, **where)
        return value

    def default(self, desc: tuple, value: Any, name: str, line: int | None) -> Any:
        kind, spec = desc
        if kind == Nodetype.BASE:
            return self.checked(spec[0], spec[1], value, name, line)
        if kind == Nodetype.NAME or spec[0][0] != Nodetype.BASE:
            self.fail(f"{name}: message members take no default value", line, field=name)
        # rosidl reads a collection's default as a Python literal in the annotation's string
        try:
            items = ast.literal_eval(value) if isinstance(value, str) else None
        except (ValueError, SyntaxError):
            items = None
        if not isinstance(items, (tuple, list)):
            self.fail(f"{name}: default {value!r} is not a tuple of values, e.g. \"(1, 2, 3)\"", line, field=name)
        values = [self.checked(spec[0][1][0], spec[0][1][1], v, name, line) for v in items]
        if kind == Nodetype.ARRAY and len(values) != spec[1]:
            self.fail(f"{name}: the default has {len(values)} values, the array {spec[1]}", line, field=name)
        if kind == Nodetype.SEQUENCE and spec[1] and len(values) > spec[1]:
            self.fail(f"{name}: the default has {len(values)} values, more than the bound {spec[1]}", line,
                      field=name)
        return values


def idl_defs(name: str, text: str, source: str | None = None) -> list[TypeDef]:
    """The structures interface `pkg/kind/Name` takes from its .idl text: the message; a service's Request and
    Response; an action's Goal, Result and Feedback (their wrappers are added as for .msg files)."""
    pkg, kind, _ = name.split("/")
    reader = _Reader(text, source)
    top = _Scope([])
    scopes: list[_Scope] = []
    reader.definitions(top, pkg, scopes)
    if reader.peek() is not None:
        reader.fail(f"unexpected {reader.peek().text!r}")
    structs: dict[str, TypeDef] = {}
    for scope in scopes:
        for td in scope.structs:
            short = td.name.split("/")[-1]
            td.constants = scope.constants.get(short, [])
            structs[td.name] = td
    wanted = [f"{name}{suffix}" for suffix in _SECTIONS[kind]]
    missing = [w for w in wanted if w not in structs]
    if missing:
        raise InterfaceError(
            f"defines no struct {', '.join(m.split('/')[-1] for m in missing)} in module {pkg}::{kind}"
            f" (found: {', '.join(sorted(structs)) or 'none'})", source=source)
    return [structs[w] for w in wanted]
