"""Per-type CDR (de)serializers compiled to flat Python: the bus's hot path.

rosbags generates one function per type too, but each primitive is its own `unpack_from` call, each nested
message a `get_msgdef` lookup and a call, and the message is built from a list. Here a type's whole tree is
inlined into one function: neighbouring fixed-size fields (across nested messages) become a single
precompiled `struct.Struct`, and each message object is filled attribute by attribute exactly as its
dataclass `__init__` would, without the call (most of a small message's cost on Python 3.11). Only
sequences and arrays of messages call a helper per element.

With `classes` given (a typename → class function), the code reads and builds rosidl-style classes
instead (diffctl.interfaces): fields are read from and written to their slots (`_x`, no property
call), `byte` is a 1-byte `bytes`, fixed numeric arrays are writable numpy arrays, numeric sequences
`array.array`, and bool and byte collections lists, as rosidl_generator_py's C conversions give them.

Alignment is XCDR1's, as ROS 2 uses it: every primitive aligns to its own size, relative to the byte after
the 4-byte encapsulation header; structs add no alignment of their own, so alignment is tracked
statically where the position is known modulo 8 and computed at run time only where it is not (after a
string or a sequence). The output is byte for byte what rosbags writes and reads (tests check it on every
type of the store); big-endian input is left to rosbags.
"""

from __future__ import annotations

import array
import dataclasses
import struct
from collections.abc import Callable
from typing import Any

import numpy
from rosbags.serde.utils import ndtype
from rosbags.typesys.base import Nodetype, normalize_fieldname

from diffctl.interfaces.bytecode import compiled

# The struct codes rosbags uses for each ROS primitive (note `byte` is signed there), size = alignment.
_CODE = {
    "bool": "?", "byte": "b", "char": "B", "int8": "b", "uint8": "B", "int16": "h", "uint16": "H",
    "int32": "i", "uint32": "I", "int64": "q", "uint64": "Q", "float32": "f", "float64": "d", "wchar": "H",
}
_SIZE = {name: struct.calcsize(code) for name, code in _CODE.items()}
# array.array type codes rosidl_generator_py uses for numeric sequences.
_TYPECODE = {"int8": "b", "uint8": "B", "char": "B", "int16": "h", "uint16": "H", "int32": "i", "uint32": "I",
             "int64": "q", "uint64": "Q", "float32": "f", "float64": "d", "wchar": "H"}
# An .idl char or wchar (a .msg char is uint8 by then) is a 1-character str in the classes. A char is sent as
# rosidl's C conversion takes it, the first byte of the str's UTF-8 (0 for ''); a wchar as its code point in
# 2 bytes (Fast CDR writes a wchar_t as a uint16; collections of wchar the same way, though rosidl's C type
# support has no working code for them).
_CHARACTERS = ("char", "wchar")
_TO_CODE = {"char": "CHARBYTE", "wchar": "ORD"}


def _char_byte(text: str) -> int:
    return text.encode()[0] if text else 0
_HEADER_LE = b"\x00\x01\x00\x00"
_EMPTY = "structure_needs_at_least_one_member"


class Unsupported(Exception):
    """A field kind this compiler does not handle (e.g. wstring): the type stays with rosbags."""


class _Emitter:
    """Code lines of one generated function plus the names its namespace must provide."""

    def __init__(self, ns: dict[str, Any]) -> None:
        self.ns = ns
        self.lines: list[str] = []
        self.counter = 0

    def var(self, prefix: str = "v") -> str:
        self.counter += 1
        return f"{prefix}{self.counter}"

    def const(self, value: Any, prefix: str) -> str:
        name = f"{prefix}{len(self.ns)}"
        self.ns[name] = value
        return name

    def struct(self, fmt: str) -> str:
        """The name of a precompiled little-endian `struct.Struct` for `fmt`, shared within the function."""
        name = self.ns.get(("struct", fmt))
        if name is None:
            name = f"S{len(self.ns)}"
            self.ns[name] = struct.Struct("<" + fmt)
            self.ns[("struct", fmt)] = name
        return name


def _fields(ts: Any, typename: str) -> list[tuple[str, tuple]]:
    # The field list as `get_msgdef(...).fields` gives it, without `get_msgdef`: that also generates and compiles
    # rosbags' own twelve (de)serializers and converters for the type, 4 ms a type none of which is used here
    # (60 ms of the fork server's start-up).
    return [(normalize_fieldname(name), desc) for name, desc in ts.fielddefs[typename][1]]


def _plain_fields(cls: type, names: list[str]) -> list[tuple[str, Any]] | None:
    """The fields besides `names` (with their defaults) that a plain dataclass __init__ of `cls` sets, or None
    when building it attribute by attribute would differ from calling it (slots, frozen, __post_init__,
    a default factory, other field order)."""
    if not dataclasses.is_dataclass(cls) or cls.__dataclass_params__.frozen or hasattr(cls, "__post_init__") \
            or "__slots__" in cls.__dict__:
        return None
    fields = dataclasses.fields(cls)
    if [f.name for f in fields if f.name in names] != names:
        return None
    extra = []
    for f in fields:
        if f.name in names:
            continue
        if not f.init or f.default is dataclasses.MISSING:
            return None
        extra.append((f.name, f.default))
    return extra


# ----------------------------------------------------------------------------- decoder


class _Decoder(_Emitter):
    """Emits `pos`-advancing code; positions are indices into the whole sample, aligned relative to byte 4."""

    def __init__(self, ts: Any, ns: dict[str, Any], helpers: dict[str, str], pending: list[str],
                 classes: Callable[[str], type] | None = None) -> None:
        super().__init__(ns)
        self.ts = ts
        self.classes = classes
        self.helpers = helpers  # typename → helper function name
        self.pending = pending  # helper types still to generate
        # Messages are built after every field is read (runs are unpacked late), children first.
        self.builds: list[str] = []
        self.known = 8  # the position is known to be ≡ 4 (mod known) — i.e. aligned to `known` in the payload
        self.run_fmt = ""
        self.run_vars: list[str] = []
        self.run_bools: list[str] = []  # the run's bool fields, read as bytes: Fast-CDR takes only 0 and 1
        self.run_size = 0
        self.run_base = 8

    def _align(self, size: int) -> None:
        if size > self.known:
            self.lines.append(f"pos = ((pos + {size - 5}) & -{size}) + 4")
            self.known = size

    def flush(self) -> None:
        if self.run_vars:
            s = self.struct(self.run_fmt)
            self.lines.append(f"{', '.join(self.run_vars)}{',' if len(self.run_vars) == 1 else ''} = "
                              f"{s}.unpack_from(buf, pos)")
            for b in self.run_bools:
                self.lines += [f"if {b} > 1:",
                               f"    raise ValueError(f'invalid bool byte {{{b}}} near offset {{pos - 4}}')",
                               f"{b} = {b} == 1"]
            self.lines.append(f"pos += {self.run_size}")
            low = self.run_size & -self.run_size
            self.known = min(self.run_base, low) if self.run_size else self.run_base
        self.run_fmt, self.run_vars, self.run_bools, self.run_size = "", [], [], 0

    def primitive(self, base: str) -> str:
        size = _SIZE[base]
        if self.run_vars and size <= self.run_base:
            pad = -self.run_size % size
            self.run_fmt += "x" * pad
            self.run_size += pad
        else:
            self.flush()
            self._align(size)
            self.run_base = self.known
        v = self.var()
        if base == "bool":
            self.run_fmt += "B"
            self.run_bools.append(v)
        else:
            self.run_fmt += "c" if base == "byte" and self.classes is not None else _CODE[base]
        self.run_vars.append(v)
        self.run_size += size
        return v

    def _length(self) -> str:
        """A string's or sequence's uint32 length, read by the run before it (a Header's stamp and its
        frame_id's length are one unpack), or by a run of its own; `pos` is left just after it."""
        n = self.primitive("uint32")
        self.flush()
        return n

    def string(self) -> str:
        n, v = self._length(), self.var("s")
        self.lines += [
            f"if {n} < 1 or pos + {n} > blen or buf[pos + {n} - 1] != 0:",
            f"    raise ValueError(f'invalid string length {{{n}}} at offset {{pos - 8}}')",
            f"{v} = buf[pos:pos + {n} - 1].decode()",
            f"pos += {n}",
        ]
        self.known = 1
        return v

    def wstring(self) -> str:
        n, v = self._length(), self.var("w")
        self.lines += [
            f"if pos + 4 * {n} > blen:",
            f"    raise ValueError(f'invalid wstring length {{{n}}} at offset {{pos - 8}}')",
            f"{v} = WDEC(buf, pos, {n})",
            f"pos += 4 * {n}",
        ]
        self.known = 4
        return v

    def count(self, minimum: int) -> str:
        n = self._length()
        self.lines += [
            f"if pos + {n} * {minimum} > blen or {n} > MAXSEQ:",
            f"    raise ValueError(f'invalid sequence length {{{n}}} at offset {{pos - 8}}')",
        ]
        return n

    def value(self, desc: tuple) -> str:
        """Code reading one field; returns the expression of its value (valid once flushed)."""
        kind, spec = desc
        if kind == Nodetype.BASE:
            if spec[0] == "string":
                return self.string()
            if spec[0] == "wstring":
                return self.wstring()
            if spec[0] not in _CODE:
                raise Unsupported(spec[0])
            if self.classes is not None and spec[0] in _CHARACTERS:
                return f"CHR({self.primitive(spec[0])})"
            return self.primitive(spec[0])
        if kind == Nodetype.NAME:
            names = [n for n, _ in _fields(self.ts, spec)]
            args = [self.value(d) for _, d in _fields(self.ts, spec)]
            if self.classes is not None:
                cls = self.classes(spec)
                c, o = self.const(cls, "C"), self.var("o")
                check = self.const(_check_fields_of(cls), "K")
                self.builds += [f"{o} = NEW({c})", f"{o}._check_fields = {check}"]
                self.builds += [f"{o}._{n} = {a}" for n, a in zip(names, args, strict=True) if n != _EMPTY]
                return o
            cls = self.ts.types[spec]
            c, o = self.const(cls, "C"), self.var("o")
            extra = _plain_fields(cls, names)
            if extra is None:
                self.builds.append(f"{o} = {c}({', '.join(args)})")
            else:
                # What the dataclass __init__ would do, without its call: half the cost of a message on 3.11.
                self.builds.append(f"{o} = NEW({c})")
                self.builds += [f"{o}.{n} = {a}" for n, a in zip(names, args, strict=True)]
                self.builds += [f"{o}.{n} = {self.const(v, 'K')}" for n, v in extra]
            return o
        sub, length = spec
        fixed = kind == Nodetype.ARRAY
        if self.classes is not None and sub[0] == Nodetype.BASE and sub[1][0] in ("bool", "byte"):
            # rosidl keeps these as lists: of bools, and of 1-byte bytes
            n = str(length) if fixed else self.count(1)
            self.flush()
            v = self.var("l")
            if sub[1][0] == "bool":
                self.lines += [f"if {n} and max(buf[pos:pos + {n}]) > 1:",
                               "    raise ValueError(f'invalid bool byte near offset {pos - 4}')",
                               f"{v} = list(map(bool, buf[pos:pos + {n}]))"]
            else:
                self.lines.append(f"{v} = [buf[i_:i_ + 1] for i_ in range(pos, pos + {n})]")
            self.lines.append(f"pos += {n}")
            self.known = 1
            return v
        if sub[0] == Nodetype.BASE and sub[1][0] in _CODE:
            size = _SIZE[sub[1][0]]
            dtype = self.const(numpy.dtype("<u2" if sub[1][0] == "wchar" else ndtype(sub[1][0])), "D")
            if fixed:
                self.flush()
                n = str(length)
            else:
                n = self.count(size)
            v = self.var("a")
            if size > self.known:
                guard = "" if fixed else "    "
                if not fixed:
                    self.lines.append(f"if {n}:")
                self.lines.append(f"{guard}pos = ((pos + {size - 5}) & -{size}) + 4")
            if self.classes is None:
                self.lines.append(f"{v} = frombuffer(buf, dtype={dtype}, count={n}, offset=pos)")
            elif sub[1][0] in _CHARACTERS:
                code = self.const(_TYPECODE[sub[1][0]], "T")
                self.lines.append(f"{v} = list(map(CHR, ARRAY({code}, buf[pos:pos + {n} * {size}])))")
            elif fixed:
                self.lines.append(f"{v} = frombuffer(buf, dtype={dtype}, count={n}, offset=pos).copy()")
            else:
                code = self.const(_TYPECODE[sub[1][0]], "T")
                self.lines.append(f"{v} = ARRAY({code}, buf[pos:pos + {n} * {size}])")
            self.lines.append(f"pos += {n} * {size}")
            if fixed and length:
                nbytes = length * size
                self.known = min(max(self.known, size), nbytes & -nbytes)
            elif not fixed:
                self.known = 1  # the data's length is only known at run time
            return v
        n = str(length) if fixed else self.count(5 if sub[0] == Nodetype.BASE and sub[1][0] == "string" else 1)
        self.flush()
        v = self.var("l")
        if sub[0] == Nodetype.BASE and sub[1][0] == "wstring":
            self.lines += [
                f"{v} = []",
                f"for _ in range({n}):",
                "    pos = ((pos - 1) & -4) + 4",
                "    n_ = U32(buf, pos)[0]",
                "    if pos + 4 + 4 * n_ > blen:",
                "        raise ValueError(f'invalid wstring length {n_} at offset {pos - 4}')",
                f"    {v}.append(WDEC(buf, pos + 4, n_))",
                "    pos += 4 + 4 * n_",
            ]
        elif sub[0] == Nodetype.BASE and sub[1][0] == "string":
            self.lines += [
                f"{v} = []",
                f"for _ in range({n}):",
                "    pos = ((pos - 1) & -4) + 4",
                "    n_ = U32(buf, pos)[0]",
                "    if n_ < 1 or pos + 4 + n_ > blen or buf[pos + 3 + n_] != 0:",
                "        raise ValueError(f'invalid string length {n_} at offset {pos - 4}')",
                f"    {v}.append(buf[pos + 4:pos + 3 + n_].decode())",
                "    pos += 4 + n_",
            ]
        elif sub[0] == Nodetype.BASE:
            raise Unsupported(sub[1][0])
        elif sub[0] == Nodetype.NAME:
            helper = self.helpers.get(sub[1])
            if helper is None:
                helper = self.helpers[sub[1]] = f"d_{len(self.helpers)}"
                self.pending.append(sub[1])
            self.lines += [f"{v} = []", f"for _ in range({n}):",
                           f"    o_, pos = {helper}(buf, pos, blen)", f"    {v}.append(o_)"]
        else:
            raise Unsupported(str(sub))
        self.known = 1
        return v


def _check_fields_of(cls: type) -> bool:
    """What a rosidl class's constructor sets `_check_fields` to: its module's ROS_PYTHON_CHECK_FIELDS."""
    import sys

    module = sys.modules.get(cls.__module__)
    return getattr(module, "ros_python_check_fields", "") == "1"


def _decoder_source(ts: Any, typename: str, ns: dict[str, Any], wrap: bool = False,
                    classes: Callable[[str], type] | None = None) -> str:
    helpers: dict[str, str] = {}
    pending: list[str] = []
    out: list[str] = []

    def body(name: str, em: _Decoder) -> list[str]:
        expr = em.value((Nodetype.NAME, name))
        em.flush()
        return [*em.lines, *em.builds, f"return {expr}, pos"]

    top = _Decoder(ts, ns, helpers, pending, classes)
    top_expr = top.value((Nodetype.NAME, typename))
    top.flush()
    # One frame per message: the header check, the body and the size check are all in `decode`.
    top_body = [
        "if type(buf) is not bytes:",
        "    buf = bytes(buf)",
        "blen = len(buf)",
        # The representation identifier 00 01 (CDR_LE) as two byte reads: cheaper than slicing and comparing.
        "if blen < 4 or buf[1] != 1 or buf[0]:  # big-endian or no header: rosbags decides",
        "    return FALLBACK(buf, TYPENAME)",
        "pos = 4",
        *top.lines,
        *([] if classes is not None else [
            "if pos + 3 < blen:  # CDR pads to 4 at most; more left over means a sample of another type",
            "    raise ValueError(f'CDR message size mismatch for {TYPENAME!r}')"]),
        *top.builds,
        f"return {top_expr}",
    ]
    out.append("def decode(buf):")
    if wrap:
        # The caller's error type raised from this very frame: no wrapper call per sample.
        out += ["    try:", *[f"        {line}" for line in top_body], "    except Exception as e:",
                "        raise ERROR(f'cannot decode {TYPENAME}: {type(e).__name__}: {e}') from None"]
    else:
        out += [f"    {line}" for line in top_body]
    while pending:
        name = pending.pop()
        em = _Decoder(ts, ns, helpers, pending, classes)
        em.known = 1  # elements of a sequence start wherever the previous one ended
        out.append(f"def {helpers[name]}(buf, pos, blen):")
        out += [f"    {line}" for line in body(name, em)]
    return "\n".join(out) + "\n"


def compile_decoder(
    ts: Any, typename: str, error: type[Exception] | None = None, classes: Callable[[str], type] | None = None
) -> Callable[[bytes | bytearray | memoryview], Any]:
    """`decode(raw)` for one type: raw is a whole CDR sample (header included). With `classes`, bytes left
    over are ignored, as rclpy's deserialize_message ignores them (Fast DDS's serialize_message leaves up to
    7 bytes of padding per empty sequence at the end). Raises ValueError,
    struct.error or UnicodeDecodeError on malformed input — or, given `error`, that type with the type name
    and the cause in its message; big-endian samples go through rosbags.
    Only the representation bytes of the header are checked: the two option bytes may count padding."""
    ns: dict[str, Any] = {"U32": struct.Struct("<I").unpack_from, "frombuffer": numpy.frombuffer, "NEW": object.__new__,
                          "MAXSEQ": getattr(ts, "max_sequence_length", 2**32 - 1),
                          "FALLBACK": ts.deserialize_cdr, "TYPENAME": typename, "ERROR": error,
                          "ARRAY": array.array, "WDEC": _wstring_decode, "CHR": chr}
    if classes is not None:
        ns["FALLBACK"] = _big_endian_unsupported
    src = _decoder_source(ts, typename, ns, wrap=error is not None, classes=classes)
    ns = {k: v for k, v in ns.items() if isinstance(k, str)}
    exec(compiled(src, f"<cdr decoder {typename}>"), ns)
    return ns["decode"]


def _wstring_decode(buf: bytes, pos: int, n: int) -> str:
    # rosidl's wstrings are UTF-16 code units, each sent as a 4-byte wchar (Fast CDR), with no terminator
    return array.array("H", array.array("I", buf[pos:pos + 4 * n])).tobytes().decode("utf-16-le")


def _wstring_encode(text: str) -> tuple[int, bytes]:
    units = array.array("H")
    units.frombytes(text.encode("utf-16-le"))
    return len(units), array.array("I", units).tobytes()


def _big_endian_unsupported(buf: bytes, typename: str) -> Any:
    raise ValueError(f"not a little-endian CDR sample (header {bytes(buf[:4])!r})")


# ----------------------------------------------------------------------------- encoder


class _Encoder(_Emitter):
    """Emits code appending to `parts`; `pos` is the offset in the payload (after the header)."""

    def __init__(self, ts: Any, ns: dict[str, Any], helpers: dict[str, str], pending: list[str],
                 prefix: str = "") -> None:
        super().__init__(ns)
        self.ts = ts
        self.prefix = prefix  # attribute prefix: "_" reads rosidl classes' slots
        self.helpers = helpers
        self.pending = pending
        self.known = 8
        self.run_fmt = ""
        self.run_exprs: list[str] = []
        self.run_size = 0
        self.run_base = 8

    def _align(self, size: int, indent: str = "") -> None:
        if size > self.known:
            self.lines += [f"{indent}p_ = -pos & {size - 1}", f"{indent}parts.append(ZEROS[p_])", f"{indent}pos += p_"]
            self.known = size

    def flush(self) -> None:
        if self.run_exprs:
            s = self.struct(self.run_fmt)
            self.lines.append(f"parts.append({s}.pack({', '.join(self.run_exprs)}))")
            self.lines.append(f"pos += {self.run_size}")
            low = self.run_size & -self.run_size
            self.known = min(self.run_base, low)
        self.run_fmt, self.run_exprs, self.run_size = "", [], 0

    def primitive(self, base: str, expr: str) -> None:
        size = _SIZE[base]
        if self.run_exprs and size <= self.run_base:
            pad = -self.run_size % size
            self.run_fmt += "x" * pad
            self.run_size += pad
        else:
            self.flush()
            self._align(size)
            self.run_base = self.known
        self.run_fmt += "c" if base == "byte" and self.prefix else _CODE[base]
        # rosidl's C conversion reads a bool field as `field == Py_True`: 1, "x" or numpy.True_ send false
        if self.prefix and base in _CHARACTERS:
            expr = f"{_TO_CODE[base]}({expr})"
        self.run_exprs.append(f"({expr} is True)" if base == "bool" and self.prefix else expr)
        self.run_size += size

    def string(self, expr: str) -> None:
        self.flush()
        self._align(4)
        b = self.var("b")
        self.lines += [f"{b} = {expr}.encode()", f"parts.append(U32({b}.__len__() + 1))", f"parts.append({b})",
                       "parts.append(NUL)", f"pos += {b}.__len__() + 5"]
        self.known = 1

    def wstring(self, expr: str) -> None:
        self.flush()
        self._align(4)
        n, b = self.var("n"), self.var("b")
        self.lines += [f"{n}, {b} = WENC({expr})", f"parts.append(U32({n}))", f"parts.append({b})",
                       f"pos += 4 + 4 * {n}"]
        self.known = 4

    def value(self, desc: tuple, expr: str) -> None:
        kind, spec = desc
        if kind == Nodetype.BASE:
            if spec[0] == "wstring":
                self.wstring(expr)
            elif spec[0] == "string":
                self.string(expr)
            elif spec[0] in _CODE:
                self.primitive(spec[0], expr)
            else:
                raise Unsupported(spec[0])
            return
        if kind == Nodetype.NAME:
            m = self.var("m")
            self.lines.append(f"{m} = {expr}")  # evaluated now: the run packs it later, when `m` is still bound
            for fname, d in _fields(self.ts, spec):
                # rosidl classes of empty messages have no slot for the placeholder byte IDL requires
                self.value(d, "0" if self.prefix and fname == _EMPTY else f"{m}.{self.prefix}{fname}")
            return
        sub, length = spec
        fixed = kind == Nodetype.ARRAY
        self.flush()
        v = self.var("a")
        self.lines.append(f"{v} = {expr}")
        if fixed:
            self.lines += [f"if len({v}) != {length}:", "    raise ValueError('Unexpected array length')"]
            n = str(length)
        else:
            self._align(4)
            self.lines += [f"parts.append(U32(len({v})))", "pos += 4"]
            self.known = 4
            n = f"len({v})"
        if self.prefix and sub[0] == Nodetype.BASE and sub[1][0] == "byte":
            self.lines += [f"parts.append({v} if {v}.__class__ in BYTESLIKE else b''.join({v}))", f"pos += {n}"]
        elif sub[0] == Nodetype.BASE and sub[1][0] in _CODE:
            size = _SIZE[sub[1][0]]
            dtype = self.const(numpy.dtype("<u2" if sub[1][0] == "wchar" else ndtype(sub[1][0])), "D")
            if size > self.known:
                self.lines.append(f"if {n}:")
                self._align(size, "    ")
            items = v
            if self.prefix and sub[1][0] in _CHARACTERS:
                items = f"[{_TO_CODE[sub[1][0]]}(c_) for c_ in {v}]"
            self.lines += [f"parts.append(asarray({items}, dtype={dtype}).tobytes())", f"pos += {n} * {size}"]
        elif sub[0] == Nodetype.BASE and sub[1][0] == "wstring":
            self.lines += [f"for i_ in {v}:", "    p_ = -pos & 3", "    parts.append(ZEROS[p_])",
                           "    n_, b_ = WENC(i_)", "    parts.append(U32(n_))", "    parts.append(b_)",
                           "    pos += p_ + 4 + 4 * n_"]
        elif sub[0] == Nodetype.BASE and sub[1][0] == "string":
            self.lines += [f"for i_ in {v}:", "    p_ = -pos & 3", "    parts.append(ZEROS[p_])",
                           "    b_ = i_.encode()", "    parts.append(U32(b_.__len__() + 1))", "    parts.append(b_)",
                           "    parts.append(NUL)", "    pos += p_ + b_.__len__() + 5"]
        elif sub[0] == Nodetype.NAME:
            helper = self.helpers.get(sub[1])
            if helper is None:
                helper = self.helpers[sub[1]] = f"e_{len(self.helpers)}"
                self.pending.append(sub[1])
            self.lines += [f"for i_ in {v}:", f"    pos = {helper}(i_, parts, pos)"]
        else:
            raise Unsupported(str(sub))
        self.known = 1


def _encoder_source(ts: Any, typename: str, ns: dict[str, Any], prefix: str = "") -> str:
    helpers: dict[str, str] = {}
    pending: list[str] = []
    out = ["def encode(msg, parts, pos):"]
    top = _Encoder(ts, ns, helpers, pending, prefix)
    top.value((Nodetype.NAME, typename), "msg")
    top.flush()
    out += [f"    {line}" for line in [*top.lines, "return pos"]]
    while pending:
        name = pending.pop()
        em = _Encoder(ts, ns, helpers, pending, prefix)
        em.known = 1
        em.value((Nodetype.NAME, name), "msg")
        em.flush()
        out.append(f"def {helpers[name]}(msg, parts, pos):")
        out += [f"    {line}" for line in [*em.lines, "return pos"]]
    return "\n".join(out) + "\n"


def compile_encoder(ts: Any, typename: str, rosidl: bool = False) -> Callable[[Any], bytes]:
    """`encode(msg) -> bytes`: the little-endian CDR sample, header included, padded as rosbags pads it.
    `rosidl`: the message is of a rosidl-style class (fields read from their `_name` slots)."""
    ns: dict[str, Any] = {"U32": struct.Struct("<I").pack, "NUL": b"\x00", "asarray": numpy.asarray,
                          "ZEROS": tuple(bytes(i) for i in range(8)), "BYTESLIKE": (bytes, bytearray),
                          "WENC": _wstring_encode, "ORD": ord,
                          "CHARBYTE": _char_byte}
    src = _encoder_source(ts, typename, ns, "_" if rosidl else "")
    ns = {k: v for k, v in ns.items() if isinstance(k, str)}
    exec(compiled(src, f"<cdr encoder {typename}>"), ns)
    inner = ns["encode"]

    def encode(msg: Any) -> bytes:
        parts = [_HEADER_LE]
        inner(msg, parts, 0)
        return b"".join(parts)

    return encode
