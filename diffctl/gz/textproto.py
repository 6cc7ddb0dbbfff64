"""Protobuf text format for gz messages held as dicts: what `gz topic -e` prints and `gz topic -p` reads.

Printing follows protobuf's DebugString for proto3: nested messages as `name {…}` indented two spaces,
repeated fields one line per element, fields at their default (0, "", false, empty) left out, strings quoted
with C escapes, enums bare. Parsing takes what `gz topic -p` users write: `data: "hi"`,
`linear: {x: 0.5}, angular {z: 0.2}`, `<…>` blocks, `,`/`;` separators, `#` comments; a field given twice
becomes a list.
"""

from __future__ import annotations

import math
import re
from typing import Any

import numpy as np

from diffctl.errors import MessageError

# gz.msgs enum fields diffctl's messages carry as NAME strings (printed bare, as protobuf prints enums)
ENUM_FIELDS = frozenset({"pixel_format_type", "datatype", "type", "status", "power_supply_status"})


def _scalar(name: str, value: Any) -> str:
    if isinstance(value, bool | np.bool_):
        return "true" if value else "false"
    if isinstance(value, int | np.integer):
        return str(int(value))
    if isinstance(value, float | np.floating):
        v = float(value)
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v).removesuffix(".0") if v.is_integer() and abs(v) < 1e16 else repr(v)
    if isinstance(value, bytes | bytearray | memoryview):
        return '"' + "".join(_byte(b) for b in bytes(value)) + '"'
    text = str(value)
    if name in ENUM_FIELDS and re.fullmatch(r"[A-Z][A-Z0-9_]*", text):
        return text
    return '"' + "".join(_byte(b) for b in text.encode()) + '"'


def _byte(b: int) -> str:
    special = {0x0A: "\\n", 0x0D: "\\r", 0x09: "\\t", 0x22: '\\"', 0x27: "\\'", 0x5C: "\\\\"}
    if b in special:
        return special[b]
    return chr(b) if 0x20 <= b < 0x7F else f"\\{b:03o}"


def _is_default(value: Any) -> bool:
    if isinstance(value, np.ndarray):
        return value.size == 0
    if isinstance(value, bool | int | float | np.number):
        return not value
    return isinstance(value, str | bytes | list | tuple | dict) and len(value) == 0


def format_message(fields: dict[str, Any], indent: int = 0) -> str:
    """The text format of one message (a trailing newline after each field)."""
    pad = " " * indent
    out: list[str] = []
    for name, value in fields.items():
        if value is None or _is_default(value):
            continue
        items = list(value) if isinstance(value, list | tuple | np.ndarray) else [value]
        for item in items:
            if isinstance(item, dict):
                out.append(f"{pad}{name} {{\n{format_message(item, indent + 2)}{pad}}}\n")
            else:
                out.append(f"{pad}{name}: {_scalar(name, item)}\n")
    return "".join(out)


_TOKEN = re.compile(
    r"""\s+|\#[^\n]*|(?P<str>"(?:[^"\\\n]|\\.)*"|'(?:[^'\\\n]|\\.)*')|(?P<num>[-+]?(?:\d+\.?\d*(?:[eE][-+]?\d+)?|\.\d+(?:[eE][-+]?\d+)?|inf(?:inity)?|nan)(?![\w.]))|(?P<id>[A-Za-z_][\w.]*)|(?P<p>[{}<>:\[\],;])""",
    re.IGNORECASE,
)
_ESCAPES = {"n": "\n", "r": "\r", "t": "\t", '"': '"', "'": "'", "\\": "\\", "a": "\a", "b": "\b", "f": "\f", "v": "\v"}


def _tokens(text: str) -> list[tuple[str, str, int]]:
    out: list[tuple[str, str, int]] = []
    i = 0
    while i < len(text):
        m = _TOKEN.match(text, i)
        if m is None:
            raise MessageError(f"text format: unexpected {text[i]!r} at column {i + 1} of {text!r}")
        for kind in ("str", "num", "id", "p"):
            if m.group(kind) is not None:
                out.append((kind, m.group(kind), i + 1))
        i = m.end()
    return out


def _unquote(token: str) -> str:
    body = token[1:-1]
    out = []
    i = 0
    while i < len(body):
        c = body[i]
        if c == "\\" and i + 1 < len(body):
            n = body[i + 1]
            if n in _ESCAPES:
                out.append(_ESCAPES[n])
                i += 2
                continue
            if n.isdigit():
                digits = re.match(r"[0-7]{1,3}", body[i + 1 :]).group(0)  # type: ignore[union-attr]
                out.append(chr(int(digits, 8)))
                i += 1 + len(digits)
                continue
        out.append(c)
        i += 1
    return "".join(out)


def parse_message(text: str) -> dict[str, Any]:
    """The fields `text` gives (nested messages as dicts, repeated fields as lists)."""
    tokens = _tokens(text)
    pos = 0

    def peek() -> tuple[str, str, int] | None:
        return tokens[pos] if pos < len(tokens) else None

    def take() -> tuple[str, str, int]:
        nonlocal pos
        if pos >= len(tokens):
            raise MessageError(f"text format: {text!r} ends too early")
        pos += 1
        return tokens[pos - 1]

    def value(tok: tuple[str, str, int]) -> Any:
        kind, raw, col = tok
        if kind == "str":
            return _unquote(raw)
        if kind == "num":
            low = raw.lower().lstrip("+")
            if low in ("inf", "infinity", "-inf", "-infinity", "nan"):
                return float(low)
            return float(raw) if any(c in raw for c in ".eE") else int(raw)
        if kind == "id":
            return {"true": True, "false": False, "True": True, "False": False}.get(raw, raw)
        raise MessageError(f"text format: expected a value at column {col}, got {raw!r}")

    def block(closer: str | None) -> dict[str, Any]:
        fields: dict[str, Any] = {}
        while True:
            tok = peek()
            if tok is None:
                if closer is not None:
                    raise MessageError(f"text format: missing {closer!r} in {text!r}")
                return fields
            if tok[0] == "p" and tok[1] in ",;":
                take()
                continue
            if closer is not None and tok == ("p", closer, tok[2]):
                take()
                return fields
            kind, name, col = take()
            if kind != "id":
                raise MessageError(f"text format: expected a field name at column {col}, got {name!r}")
            nxt = peek()
            if nxt is not None and nxt[0] == "p" and nxt[1] == ":":
                take()
                nxt = peek()
            if nxt is not None and nxt[0] == "p" and nxt[1] in "{<":
                take()
                item: Any = block("}" if nxt[1] == "{" else ">")
            elif nxt is not None and nxt[0] == "p" and nxt[1] == "[":
                take()
                item = []
                while True:
                    t = take()
                    if t[0] == "p" and t[1] == "]":
                        break
                    if t[0] == "p" and t[1] == ",":
                        continue
                    if t[0] == "p" and t[1] in "{<":
                        item.append(block("}" if t[1] == "{" else ">"))
                    else:
                        item.append(value(t))
            else:
                item = value(take())
            if name in fields:
                prev = fields[name]
                fields[name] = [*prev, item] if isinstance(prev, list) else [prev, item]
            else:
                fields[name] = item

    return block(None)


def _camel(name: str) -> str:
    head, *rest = name.split("_")
    return head + "".join(part[:1].upper() + part[1:] for part in rest)


def json_value(value: Any, name: str = "") -> Any:
    """Protobuf's JSON mapping of a gz message held as a dict (what `gz topic -e --json-output` prints):
    lowerCamelCase names, defaults left out, bytes as base64, non-finite floats as "Infinity"/"NaN"."""
    import base64

    if isinstance(value, dict):
        return {_camel(k): json_value(v, k) for k, v in value.items() if v is not None and not _is_default(v)}
    if isinstance(value, list | tuple | np.ndarray):
        return [json_value(v, name) for v in value]
    if isinstance(value, bytes | bytearray | memoryview):
        return base64.b64encode(bytes(value)).decode()
    if isinstance(value, bool | np.bool_):
        return bool(value)
    if isinstance(value, np.integer):
        value = int(value)
    if isinstance(value, int):
        return str(value) if abs(value) >= 2**53 else value  # int64 beyond a double travels as a string
    if isinstance(value, float | np.floating):
        v = float(value)
        if math.isnan(v):
            return "NaN"
        if math.isinf(v):
            return "Infinity" if v > 0 else "-Infinity"
        return v
    return value
