# ruff: noqa: UP031  (rosidl formats its values and messages with %; the same formatting gives the same text)
"""Python source of interface modules that behave as rosidl_generator_py's (Jazzy, 0.22) generated ones.

One module per interface, `<pkg>.<kind>._<snake>`, as rosidl lays them out: a message's class; a service's
Request, Response, Event and service class; an action's Goal, Result, Feedback, SendGoal and GetResult
services, FeedbackMessage and action class. Each message class has its metaclass (constants and .msg
defaults as read-only properties), `__slots__`, `_fields_and_field_types`, `SLOT_TYPES`, the keyword
constructor, `__repr__`, `__eq__` and one property per field whose setter checks types and ranges only when
`ROS_PYTHON_CHECK_FIELDS=1` (read once at import, as in Jazzy), with rosidl's assertion messages.
The metaclass's typesupport attributes stay None until `__import_type_support__()`: diffctl's bus
(de)serializes these classes with its own compiled codecs (`codec.py`), so the type support it records is
only the type's name.
"""

from __future__ import annotations

import functools
import re
from dataclasses import dataclass
from typing import Any

from rosbags.typesys.base import Nodetype

from diffctl.interfaces.idl import TypeDef

# Definition primitive → IDL basic type name, as rosidl_adapter converts them. A .msg `char` is uint8 by
# then (idl.py); a "char" or "wchar" here comes from an .idl file and is a character.
IDL_NAME = {"bool": "boolean", "byte": "octet", "char": "char", "wchar": "wchar", "float32": "float",
            "float64": "double",
            **{t: t for t in ("int8", "uint8", "int16", "uint16", "int32", "uint32", "int64", "uint64")}}
SPECIAL = {"float": ("numpy.float32", "f"), "double": ("numpy.float64", "d"), "int8": ("numpy.int8", "b"),
           "uint8": ("numpy.uint8", "B"), "int16": ("numpy.int16", "h"), "uint16": ("numpy.uint16", "H"),
           "int32": ("numpy.int32", "i"), "uint32": ("numpy.uint32", "I"), "int64": ("numpy.int64", "q"),
           "uint64": ("numpy.uint64", "Q")}
CHARACTERS = ("char", "wchar")
SPECIAL_ORDER = ["float", "double", "int8", "uint8", "int16", "uint16", "int32", "uint32", "int64", "uint64"]
_BUILTIN_NAMES = set(dir(__import__("builtins")))


@functools.cache  # a few hundred names, asked for again by every generated module that refers to them
def snake(name: str) -> str:
    """rosidl_pycommon.convert_camel_case_to_lower_case_underscore: TFMessage → tf_message."""
    value = re.sub(r"(.)([A-Z][a-z]+)", r"\1_\2", name)
    value = re.sub(r"([a-z0-9])([A-Z])", r"\1_\2", value)
    return value.lower()


@dataclass(frozen=True)
class Member:
    name: str
    nest: str | None  # None, "array", "bseq" (bounded sequence), "useq" (unbounded)
    size: int  # array size or sequence bound
    vt: str  # "basic", "string", "wstring", "named"
    typename: str = ""  # IDL basic name for "basic"
    sbound: int = 0  # string bound
    ref: str = ""  # pkg/kind/Name for "named"

    @property
    def seq(self) -> bool:
        return self.nest in ("bseq", "useq")

    @property
    def special(self) -> bool:
        return self.nest is not None and self.vt == "basic" and self.typename in SPECIAL


def member(name: str, desc: tuple) -> Member:
    nest, size = None, 0
    kind, spec = desc
    if kind in (Nodetype.ARRAY, Nodetype.SEQUENCE):
        nest = "array" if kind == Nodetype.ARRAY else ("bseq" if spec[1] else "useq")
        size = spec[1]
        kind, spec = spec[0]
    if kind == Nodetype.NAME:
        return Member(name, nest, size, "named", ref=spec)
    base, bound = spec
    if base in ("string", "wstring"):
        return Member(name, nest, size, base, sbound=bound)
    return Member(name, nest, size, "basic", typename=IDL_NAME[base])


def python_type(m: Member) -> str:
    """rosidl_generator_py's get_python_type for the member's (element) type."""
    if m.vt == "named":
        return m.ref.split("/")[-1]
    if m.vt in ("string", "wstring") or m.typename in CHARACTERS:
        return "str"
    if m.typename == "boolean":
        return "bool"
    if m.typename == "octet":
        return "bytes"
    if m.typename in ("float", "double"):
        return "float"
    return "int"


def quoted(s: str) -> str:
    """rosidl_generator_py's quoted_string."""
    s = s.replace("\\", "\\\\")
    if "'" in s and '"' not in s:
        return f'"{s}"'
    return "'%s'" % s.replace("'", "\\'")


def primitive_py(m: Member, value: Any) -> str:
    if m.vt in ("string", "wstring"):
        return quoted(str(value))
    if m.typename == "boolean":
        return "True" if value else "False"
    if m.typename == "octet":
        return repr(bytes([value]))
    if m.typename in CHARACTERS:
        return repr(value)
    if m.typename in ("float", "double"):
        return "%s" % float(value)
    return str(int(value))


def value_py(m: Member, value: Any) -> str:
    """rosidl_generator_py's value_to_py for a field default."""
    if m.nest is None:
        return primitive_py(m, value)
    items = [primitive_py(m, v) for v in value]
    if m.special:
        dtype, code = SPECIAL[m.typename]
        if m.nest == "array":
            return "numpy.array((%s, ), dtype=%s)" % (", ".join(items), dtype)
        return "array.array('%s', (%s, ))" % (code, ", ".join(items))
    return "[%s]" % ", ".join(items)


def constant_py(ctype: str, value: Any) -> str:
    if ctype == "bool":
        return "True" if value else "False"
    if ctype == "byte":
        return repr(bytes([value]))
    if ctype in ("float32", "float64"):
        return "%s" % float(value)
    if ctype in ("string", "wstring"):
        return quoted(str(value))
    if ctype in CHARACTERS:
        return repr(value)
    return str(int(value))


def field_type_text(m: Member) -> str:
    """The `_fields_and_field_types` value: 'double', 'string<10>', 'sequence<int32, 5>', 'double[36]'."""
    if m.vt == "basic":
        inner = m.typename
    elif m.vt in ("string", "wstring"):
        inner = ("w" if m.vt == "wstring" else "") + "string" + (f"<{m.sbound}>" if m.sbound else "")
    else:
        pkg, _, name = m.ref.split("/")
        inner = f"{pkg}/{name}"
    if m.seq:
        return f"sequence<{inner}, {m.size}>" if m.nest == "bseq" else f"sequence<{inner}>"
    if m.nest == "array":
        return f"{inner}[{m.size}]"
    return inner


def slot_type(m: Member) -> str:
    d = "rosidl_parser.definition."
    if m.vt == "basic":
        inner = f"{d}BasicType('{m.typename}')"
    elif m.vt in ("string", "wstring"):
        w = "WString" if m.vt == "wstring" else "String"
        inner = f"{d}Bounded{w}({m.sbound})" if m.sbound else f"{d}Unbounded{w}()"
    else:
        pkg, kind, name = m.ref.split("/")
        inner = f"{d}NamespacedType(['{pkg}', '{kind}'], '{name}')"
    if m.nest == "array":
        return f"{d}Array({inner}, {m.size})"
    if m.nest == "bseq":
        return f"{d}BoundedSequence({inner}, {m.size})"
    if m.nest == "useq":
        return f"{d}UnboundedSequence({inner})"
    return inner


_ACTION_PARTS = ("_Goal", "_Result", "_Feedback")


def import_of(ref: str) -> str:
    """The import statement rosidl generates for a nested type (action parts come from their module)."""
    pkg, kind, name = ref.split("/")
    if name.endswith(_ACTION_PARTS):
        return f"from {pkg}.{kind}._{snake(name.rsplit('_', 1)[0])} import {name}"
    return f"from {pkg}.{kind} import {name}"


def _int_bounds(typename: str) -> tuple[int, int, bool]:
    bits = int(typename.lstrip("uint"))
    if typename.startswith("u"):
        return 0, 2**bits, False
    return -(2 ** (bits - 1)), 2 ** (bits - 1), True


_FLOAT_BOUND = {"float": 3.402823466e38, "double": 1.7976931348623157e308}


def _setter(m: Member) -> list[str]:
    n = m.name
    out = ["        if self._check_fields:"]
    i = "            "
    if m.special:
        dtype, code = SPECIAL[m.typename]
        if m.nest == "array":
            out += [f"{i}if isinstance(value, numpy.ndarray):",
                    f"{i}    assert value.dtype == {dtype}, \\",
                    f"{i}        \"The '{n}' numpy.ndarray() must have the dtype of '{dtype}'\"",
                    f"{i}    assert value.size == {m.size}, \\",
                    f"{i}        \"The '{n}' numpy.ndarray() must have a size of {m.size}\"",
                    f"{i}    self._{n} = value", f"{i}    return"]
        else:
            out += [f"{i}if isinstance(value, array.array):",
                    f"{i}    assert value.typecode == '{code}', \\",
                    f"{i}        \"The '{n}' array.array() must have the type code of '{code}'\""]
            if m.nest == "bseq":
                out += [f"{i}    assert len(value) <= {m.size}, \\",
                        f"{i}        \"The '{n}' array.array() must have a size <= {m.size}\""]
            out += [f"{i}    self._{n} = value", f"{i}    return"]
    if m.vt == "named":
        out.append(i + import_of(m.ref))
    if m.nest is not None:
        out += [f"{i}from collections.abc import Sequence", f"{i}from collections.abc import Set",
                f"{i}from collections import UserList", f"{i}from collections import UserString"]
    elif m.vt in ("string", "wstring") and m.sbound:
        out.append(f"{i}from collections import UserString")
    elif m.vt == "basic" and m.typename == "octet":
        out.append(f"{i}from collections.abc import ByteString")
    elif m.vt == "basic" and m.typename in CHARACTERS:
        out.append(f"{i}from collections import UserString")
    out.append(f"{i}assert \\")
    j = i + "    "
    if m.nest is not None:
        out += [f"{j}((isinstance(value, Sequence) or", f"{j}  isinstance(value, Set) or",
                f"{j}  isinstance(value, UserList)) and", f"{j} not isinstance(value, str) and",
                f"{j} not isinstance(value, UserString) and"]
        msgs = ["a set or sequence"]
        if m.vt in ("string", "wstring") and m.sbound:
            out.append(f"{j} all(len(val) <= {m.sbound} for val in value) and")
            msgs.append("and each string value not longer than %d" % m.sbound)
        if m.nest == "bseq":
            out.append(f"{j} len(value) <= {m.size} and")
            msgs.insert(1, "with length <= %d" % m.size)
        elif m.nest == "array":
            out.append(f"{j} len(value) == {m.size} and")
            msgs.insert(1, "with length %d" % m.size)
        pt = python_type(m)
        out.append(f"{j} all(isinstance(v, {pt}) for v in value) and")
        msgs.append(f"and each value of type '{pt}'")
        t = m.typename if m.vt == "basic" else ""
        if t.startswith("int"):
            lo, hi, _ = _int_bounds(t)
            out.append(f"{j} all(val >= {lo} and val < {hi} for val in value)), \\")
            msgs.append("and each integer in [%d, %d]" % (lo, hi - 1))
        elif t.startswith("uint"):
            lo, hi, _ = _int_bounds(t)
            out.append(f"{j} all(val >= 0 and val < {hi} for val in value)), \\")
            msgs.append("and each unsigned integer in [0, %d]" % (hi - 1))
        elif t == "char":
            out.append(f"{j} all(ord(val) >= 0 and ord(val) < 256 for val in value)), \\")
            msgs.append("and each char in [0, 255]")
        elif t in _FLOAT_BOUND:
            b = _FLOAT_BOUND[t]
            out.append(f"{j} all(not (val < -{b!r} or val > {b!r}) or math.isinf(val) for val in value)), \\")
            msgs.append("and each %s in [%f, %f]" % (t, -b, b))
        else:
            out.append(f"{j} True), \\")
        out.append(f"{j}\"The '{n}' field must be {' '.join(msgs)}\"")
    elif m.vt in ("string", "wstring") and m.sbound:
        out += [f"{j}(isinstance(value, (str, UserString)) and", f"{j} len(value) <= {m.sbound}), \\",
                f"{j}\"The '{n}' field must be string value \" \\", f"{j}'not longer than {m.sbound}'"]
    elif m.vt == "named":
        cls = m.ref.split("/")[-1]
        out += [f"{j}isinstance(value, {cls}), \\", f"{j}\"The '{n}' field must be a sub message of type '{cls}'\""]
    elif m.vt == "basic" and m.typename == "octet":
        out += [f"{j}(isinstance(value, (bytes, ByteString)) and", f"{j} len(value) == 1), \\",
                f"{j}\"The '{n}' field must be of type 'bytes' or 'ByteString' with length 1\""]
    elif m.vt == "basic" and m.typename == "char":
        out += [f"{j}(isinstance(value, (str, UserString)) and",
                f"{j} len(value) == 1 and ord(value) >= -128 and ord(value) < 128), \\",
                f"{j}\"The '{n}' field must be of type 'str' or 'UserString' \" \\",
                f"{j}'with length 1 and the character ord() in [-128, 127]'"]
    elif m.vt == "basic" and m.typename == "wchar":
        out.append(f"{j}False")  # rosidl_generator_py (Jazzy) has no check for a wchar: any value fails
    elif m.vt in ("string", "wstring"):
        out += [f"{j}isinstance(value, str), \\", f"{j}\"The '{n}' field must be of type 'str'\""]
    else:
        pt = python_type(m)
        out += [f"{j}isinstance(value, {pt}), \\", f"{j}\"The '{n}' field must be of type '{pt}'\""]
        t = m.typename
        if t.startswith("int"):
            lo, hi, _ = _int_bounds(t)
            out += [f"{i}assert value >= {lo} and value < {hi}, \\",
                    f"{j}\"The '{n}' field must be an integer in [{lo}, {hi - 1}]\""]
        elif t.startswith("uint"):
            _, hi, _ = _int_bounds(t)
            out += [f"{i}assert value >= 0 and value < {hi}, \\",
                    f"{j}\"The '{n}' field must be an unsigned integer in [0, {hi - 1}]\""]
        elif t in _FLOAT_BOUND:
            b = _FLOAT_BOUND[t]
            out += [f"{i}assert not (value < -{b!r} or value > {b!r}) or math.isinf(value), \\",
                    f"{j}\"The '{n}' field must be a {t} in [{-b!r}, {b!r}]\""]
    if m.special:
        dtype, code = SPECIAL[m.typename]
        if m.nest == "array":
            out.append(f"        self._{n} = numpy.array(value, dtype={dtype})")
        else:
            out.append(f"        self._{n} = array.array('{code}', value)")
    else:
        out.append(f"        self._{n} = value")
    return out


def _init_lines(cls: str, m: Member, has_default: bool) -> list[str]:
    n = m.name
    if has_default:
        return [f"        self.{n} = kwargs.get(", f"            '{n}', {cls}.{n.upper()}__DEFAULT)"]
    out = []
    if m.vt == "named" and not m.seq:
        out.append("        " + import_of(m.ref))
    if m.nest == "array":
        if m.vt == "basic" and m.typename == "octet":
            out += [f"        self.{n} = kwargs.get(", f"            '{n}',",
                    f"            [bytes([0]) for x in range({m.size})]", "        )"]
        elif m.vt == "basic" and m.typename in CHARACTERS:
            out += [f"        self.{n} = kwargs.get(", f"            '{n}',",
                    f"            [chr(0) for x in range({m.size})]", "        )"]
        elif m.special:
            dtype, _ = SPECIAL[m.typename]
            out += [f"        if '{n}' not in kwargs:",
                    f"            self.{n} = numpy.zeros({m.size}, dtype={dtype})", "        else:",
                    f"            self.{n} = kwargs.get('{n}')"]
        else:
            out += [f"        self.{n} = kwargs.get(", f"            '{n}',",
                    f"            [{python_type(m)}() for x in range({m.size})]", "        )"]
    elif m.seq:
        if m.special:
            _, code = SPECIAL[m.typename]
            out.append(f"        self.{n} = array.array('{code}', kwargs.get('{n}', []))")
        else:
            out.append(f"        self.{n} = kwargs.get('{n}', [])")
    elif m.vt == "basic" and m.typename == "octet":
        out.append(f"        self.{n} = kwargs.get('{n}', bytes([0]))")
    elif m.vt == "basic" and m.typename in CHARACTERS:
        out.append(f"        self.{n} = kwargs.get('{n}', chr(0))")
    else:
        out.append(f"        self.{n} = kwargs.get('{n}', {python_type(m)}())")
    return out


def message_source(td: TypeDef, package: str) -> str:
    """The metaclass and class of one message type, as rosidl's _msg.py.em generates them."""
    cls = td.name.split("/")[-1]
    members = [member(n, d) for n, d in td.fields]
    empty = len(members) == 1 and members[0].name == "structure_needs_at_least_one_member"
    shown = [] if empty else members
    meta = f"Metaclass_{cls}"
    L: list[str] = [
        "", "",
        f"class {meta}(type):",
        f"    \"\"\"Metaclass of message '{cls}'.\"\"\"",
        "",
        "    _CREATE_ROS_MESSAGE = None",
        "    _CONVERT_FROM_PY = None",
        "    _CONVERT_TO_PY = None",
        "    _DESTROY_ROS_MESSAGE = None",
        "    _TYPE_SUPPORT = None",
        "",
        "    __constants = {",
        *[f"        '{c}': {constant_py(t, v)}," for c, t, v in td.constants],
        "    }",
        "",
        "    @classmethod",
        "    def __import_type_support__(cls):",
        f"        _import_type_support(cls, '{td.name}')",
        "",
        "    @classmethod",
        "    def __prepare__(cls, name, bases, **kwargs):",
        "        return {",
        *[f"            '{c}': cls.__constants['{c}']," for c, _, _ in td.constants],
        *[f"            '{m.name.upper()}__DEFAULT': {value_py(m, td.defaults[m.name])},"
          for m in members if m.name in td.defaults],
        "        }",
    ]
    for c, _, _ in td.constants:
        L += ["", "    @property", f"    def {c}(self):", f"        \"\"\"Message constant '{c}'.\"\"\"",
              f"        return {meta}.__constants['{c}']"]
    for m in members:
        if m.name in td.defaults:
            L += ["", "    @property", f"    def {m.name.upper()}__DEFAULT(cls):",
                  f"        \"\"\"Return default value for message field '{m.name}'.\"\"\"",
                  f"        return {value_py(m, td.defaults[m.name])}"]
    L += ["", "", f"class {cls}(metaclass={meta}):"]
    if not td.constants:
        L.append(f"    \"\"\"Message class '{cls}'.\"\"\"")
    else:
        L += ['    """', f"    Message class '{cls}'.", "", "    Constants:",
              *[f"      {c}" for c, _, _ in td.constants], '    """']
    L += ["", "    __slots__ = [", *[f"        '_{m.name}'," for m in shown], "        '_check_fields',", "    ]",
          "", "    _fields_and_field_types = {", *[f"        '{m.name}': '{field_type_text(m)}'," for m in shown],
          "    }", "", "    SLOT_TYPES = (", *[f"        {slot_type(m)}," for m in shown], "    )", "",
          "    def __init__(self, **kwargs):",
          "        if 'check_fields' in kwargs:",
          "            self._check_fields = kwargs['check_fields']",
          "        else:",
          "            self._check_fields = ros_python_check_fields == '1'",
          "        if self._check_fields:",
          "            assert all('_' + key in self.__slots__ for key in kwargs.keys()), \\",
          "                'Invalid arguments passed to constructor: %s' % \\",
          "                ', '.join(sorted(k for k in kwargs.keys() if '_' + k not in self.__slots__))"]
    for m in shown:
        L += _init_lines(cls, m, m.name in td.defaults)
    L += ["",
          "    def __repr__(self):",
          "        typename = self.__class__.__module__.split('.')",
          "        typename.pop()",
          "        typename.append(self.__class__.__name__)",
          "        args = []",
          "        for s, t in zip(self.get_fields_and_field_types().keys(), self.SLOT_TYPES):",
          "            field = getattr(self, s)",
          "            fieldstr = repr(field)",
          "            if (",
          "                isinstance(t, rosidl_parser.definition.AbstractSequence) and",
          "                isinstance(t.value_type, rosidl_parser.definition.BasicType) and",
          f"                t.value_type.typename in {SPECIAL_ORDER!r}",
          "            ):",
          "                if len(field) == 0:",
          "                    fieldstr = '[]'",
          "                else:",
          "                    if self._check_fields:",
          "                        assert fieldstr.startswith('array(')",
          "                    prefix = \"array('X', \"",
          "                    suffix = ')'",
          "                    fieldstr = fieldstr[len(prefix):-len(suffix)]",
          "            args.append(s + '=' + fieldstr)",
          "        return '%s(%s)' % ('.'.join(typename), ', '.join(args))",
          "",
          "    def __eq__(self, other):",
          "        if not isinstance(other, self.__class__):",
          "            return False"]
    for m in shown:
        if m.nest == "array" and m.special:
            L.append(f"        if any(self.{m.name} != other.{m.name}):")
        else:
            L.append(f"        if self.{m.name} != other.{m.name}:")
        L.append("            return False")
    L += ["        return True", "",
          "    @classmethod",
          "    def get_fields_and_field_types(cls):",
          "        from copy import copy",
          "        return copy(cls._fields_and_field_types)"]
    for m in shown:
        noqa = "  # noqa: A003" if m.name in _BUILTIN_NAMES else ""
        L += ["", f"    @builtins.property{noqa}", f"    def {m.name}(self):{noqa}",
              f"        \"\"\"Message field '{m.name}'.\"\"\"", f"        return self._{m.name}", "",
              f"    @{m.name}.setter{noqa}", f"    def {m.name}(self, value):{noqa}", *_setter(m)]
    return "\n".join(L) + "\n"


def service_source(name: str) -> str:
    """The service class (Request, Response and Event as attributes), as rosidl's _srv.py.em."""
    pkg, kind, cls = name.split("/")
    mod = f"{pkg}.{kind}._{snake(cls.split('_')[0] if kind == 'action' else cls)}"
    return "\n".join([
        "", "",
        f"class Metaclass_{cls}(type):",
        f"    \"\"\"Metaclass of service '{cls}'.\"\"\"",
        "",
        "    _TYPE_SUPPORT = None",
        "",
        "    @classmethod",
        "    def __import_type_support__(cls):",
        f"        _import_type_support(cls, '{name}')",
        "",
        "",
        f"class {cls}(metaclass=Metaclass_{cls}):",
        f"    from {mod} import {cls}_Request as Request",
        f"    from {mod} import {cls}_Response as Response",
        f"    from {mod} import {cls}_Event as Event",
        "",
        "    def __init__(self):",
        "        raise NotImplementedError('Service classes can not be instantiated')",
    ]) + "\n"


def action_source(name: str) -> str:
    pkg, kind, cls = name.split("/")
    mod = f"{pkg}.{kind}._{snake(cls)}"
    return "\n".join([
        "", "",
        f"class Metaclass_{cls}(type):",
        f"    \"\"\"Metaclass of action '{cls}'.\"\"\"",
        "",
        "    _TYPE_SUPPORT = None",
        "",
        "    @classmethod",
        "    def __import_type_support__(cls):",
        f"        _import_type_support(cls, '{name}')",
        "",
        "",
        f"class {cls}(metaclass=Metaclass_{cls}):",
        "",
        "    # The goal message defined in the action definition.",
        f"    from {mod} import {cls}_Goal as Goal",
        "    # The result message defined in the action definition.",
        f"    from {mod} import {cls}_Result as Result",
        "    # The feedback message defined in the action definition.",
        f"    from {mod} import {cls}_Feedback as Feedback",
        "",
        "    class Impl:",
        "",
        "        # The send_goal service using a wrapped version of the goal message as a request.",
        f"        from {mod} import {cls}_SendGoal as SendGoalService",
        "        # The get_result service using a wrapped version of the result message as a response.",
        f"        from {mod} import {cls}_GetResult as GetResultService",
        "        # The feedback message with generic fields which wraps the feedback message.",
        f"        from {mod} import {cls}_FeedbackMessage as FeedbackMessage",
        "",
        "        # The generic service to cancel a goal.",
        "        from action_msgs.srv._cancel_goal import CancelGoal as CancelGoalService",
        "        # The generic message for get the status of a goal.",
        "        from action_msgs.msg._goal_status_array import GoalStatusArray as GoalStatusMessage",
        "",
        "    def __init__(self):",
        "        raise NotImplementedError('Action classes can not be instantiated')",
    ]) + "\n"


HEADER = """\
# generated by diffctl from {source}, as rosidl_generator_py generates it

from os import getenv

ros_python_check_fields = getenv('ROS_PYTHON_CHECK_FIELDS', default='')

import array  # noqa: E402, F401, I100
import builtins  # noqa: E402, F401, I100
import math  # noqa: E402, F401, I100

import numpy  # noqa: E402, F401, I100
import rosidl_parser.definition  # noqa: E402, F401, I100

from diffctl.interfaces.classes import import_type_support as _import_type_support  # noqa: E402
"""


def module_source(kind: str, name: str, defs: dict[str, TypeDef], source: str) -> str:
    """The whole `_<snake>` module of interface `pkg/kind/Name`; `defs` holds every type it defines."""
    pkg = name.split("/")[0]
    parts = [HEADER.format(source=source)]
    if kind == "msg":
        parts.append(message_source(defs[name], pkg))
    elif kind == "srv":
        for suffix in ("_Request", "_Response", "_Event"):
            parts.append(message_source(defs[name + suffix], pkg))
        parts.append(service_source(name))
    else:
        for suffix in ("_Goal", "_Result", "_Feedback"):
            parts.append(message_source(defs[name + suffix], pkg))
        for svc in ("_SendGoal", "_GetResult"):
            for suffix in ("_Request", "_Response", "_Event"):
                parts.append(message_source(defs[name + svc + suffix], pkg))
            parts.append(service_source(name + svc))
        parts.append(message_source(defs[name + "_FeedbackMessage"], pkg))
        parts.append(action_source(name))
    return "".join(parts)
