"""rclpy.parameter: Parameter with its Type enum, and conversions to and from rcl_interfaces messages."""

from __future__ import annotations

import array
import enum
from typing import Any

from diffctl.client.interfaces import cls

PARAMETER_SEPARATOR_STRING = "."


class Type(enum.Enum):
    """Parameter.Type (its str is `Type.INTEGER`, as rclpy's nested enum)."""

    NOT_SET = 0
    BOOL = 1
    INTEGER = 2
    DOUBLE = 3
    STRING = 4
    BYTE_ARRAY = 5
    BOOL_ARRAY = 6
    INTEGER_ARRAY = 7
    DOUBLE_ARRAY = 8
    STRING_ARRAY = 9

    @classmethod
    def from_parameter_value(cls_, value: Any) -> Type:
        """The type of a Python value; `[]` is a BYTE_ARRAY, as in rclpy."""
        if value is None:
            return cls_.NOT_SET
        if isinstance(value, bool):
            return cls_.BOOL
        if isinstance(value, int):
            return cls_.INTEGER
        if isinstance(value, float):
            return cls_.DOUBLE
        if isinstance(value, str):
            return cls_.STRING
        if isinstance(value, (list, tuple, array.array)):
            if all(isinstance(v, bytes) for v in value):
                return cls_.BYTE_ARRAY
            if all(isinstance(v, bool) for v in value):
                return cls_.BOOL_ARRAY
            if all(isinstance(v, int) for v in value):
                return cls_.INTEGER_ARRAY
            if all(isinstance(v, float) for v in value):
                return cls_.DOUBLE_ARRAY
            if all(isinstance(v, str) for v in value):
                return cls_.STRING_ARRAY
            raise TypeError(f"The given value is not a list of one of the allowed types '{value}'.")
        raise TypeError(f"The given value is not one of the allowed types '{value}'.")

    def check(self, value: Any) -> bool:
        t = Type
        seq = (list, tuple)
        if self is t.NOT_SET:
            return value is None
        if self is t.BOOL:
            return isinstance(value, bool)
        if self is t.INTEGER:
            return isinstance(value, int)
        if self is t.DOUBLE:
            return isinstance(value, float)
        if self is t.STRING:
            return isinstance(value, str)
        if self is t.BYTE_ARRAY:
            return isinstance(value, seq) and all(isinstance(v, bytes) and len(v) == 1 for v in value)
        if self is t.BOOL_ARRAY:
            return isinstance(value, seq) and all(isinstance(v, bool) for v in value)
        if self is t.INTEGER_ARRAY:
            return isinstance(value, (*seq, array.array)) and all(isinstance(v, int) for v in value)
        if self is t.DOUBLE_ARRAY:
            return isinstance(value, (*seq, array.array)) and all(isinstance(v, float) for v in value)
        if self is t.STRING_ARRAY:
            return isinstance(value, seq) and all(isinstance(v, str) for v in value)
        return False


_FIELDS = {
    1: "bool_value", 2: "integer_value", 3: "double_value", 4: "string_value", 5: "byte_array_value",
    6: "bool_array_value", 7: "integer_array_value", 8: "double_array_value", 9: "string_array_value",
}


class Parameter:
    Type = Type

    def __init__(self, name: str, type_: Type | None = None, value: Any = None) -> None:
        if type_ is None:
            type_ = Type.from_parameter_value(value)
        if not isinstance(type_, Type):
            raise TypeError(f"type must be an instance of '{Type!r}'")
        if not type_.check(value):
            raise ValueError(f"Type '{type_}' and value '{value}' do not agree")
        self._type_ = type_
        self._name = name
        self._value = value

    @classmethod
    def from_parameter_msg(cls_, param_msg: Any) -> Parameter:
        type_ = Type(param_msg.value.type)
        value = getattr(param_msg.value, _FIELDS[type_.value]) if type_.value in _FIELDS else None
        if type_ is Type.BYTE_ARRAY:
            value = [v if isinstance(v, bytes) else bytes([v]) for v in value]
        return cls_(param_msg.name, type_, value)

    @property
    def name(self) -> str:
        return self._name

    @property
    def type_(self) -> Type:
        return self._type_

    @property
    def value(self) -> Any:
        return self._value

    def get_parameter_value(self) -> Any:
        pv = cls("rcl_interfaces/msg/ParameterValue")(type=self._type_.value)
        field = _FIELDS.get(self._type_.value)
        if field is not None:
            value = self._value
            if self._type_ is Type.DOUBLE_ARRAY or self._type_ is Type.INTEGER_ARRAY:
                value = list(value)
            setattr(pv, field, value)
        return pv

    def to_parameter_msg(self) -> Any:
        return cls("rcl_interfaces/msg/Parameter")(name=self._name, value=self.get_parameter_value())

    def __repr__(self) -> str:
        return f"<rclpy.parameter.Parameter name={self._name!r} type={self._type_} value={self._value!r}>"


def get_parameter_value(string_value: str) -> Any:
    """A ParameterValue message from text, typed as YAML reads it (rclpy's `ros2 param set` rules)."""
    import yaml

    value = cls("rcl_interfaces/msg/ParameterValue")()
    try:
        y = yaml.safe_load(string_value)
    except yaml.YAMLError:
        y = string_value
    if isinstance(y, bool):
        value.type, value.bool_value = 1, y
    elif isinstance(y, int):
        value.type, value.integer_value = 2, y
    elif isinstance(y, float):
        value.type, value.double_value = 3, y
    elif isinstance(y, list):
        for t, field, ok in ((6, "bool_array_value", bool), (7, "integer_array_value", int),
                             (8, "double_array_value", float), (9, "string_array_value", str)):
            if all(isinstance(v, ok) for v in y):
                value.type = t
                setattr(value, field, y)
                break
        else:
            value.type, value.string_value = 4, string_value
    else:
        value.type, value.string_value = 4, y if y is not None else string_value
    return value


def parameter_value_to_python(parameter_value: Any) -> Any:
    t = int(parameter_value.type)
    if t == 0:
        return None
    if t not in _FIELDS:
        raise RuntimeError(f"unexpected parameter type {t}")
    v = getattr(parameter_value, _FIELDS[t])
    return list(v) if t >= 5 else v


def python_value(p: Parameter) -> Any:
    """A parameter's value as diffctl's bus stores it (bytes for a byte array, lists for arrays)."""
    if p.type_ is Type.BYTE_ARRAY:
        return b"".join(p.value)
    if isinstance(p.value, (tuple, array.array)):
        return list(p.value)
    return p.value


def from_python_value(name: str, value: Any) -> Parameter:
    """A Parameter from a bus value (bytes become rclpy's list of one-byte bytes)."""
    if isinstance(value, (bytes, bytearray)):
        return Parameter(name, Type.BYTE_ARRAY, [bytes([b]) for b in value])
    if isinstance(value, tuple):
        value = list(value)
    if isinstance(value, list) and value and all(isinstance(v, (int, float)) and not isinstance(v, bool)
                                                  for v in value) and any(isinstance(v, float) for v in value):
        value = [float(v) for v in value]
    return Parameter(name, value=value)


def parameter_dict_from_yaml_file(parameter_file: str, use_wildcard: bool = False,
                                  target_nodes: list[str] | None = None, namespace: str = "") -> dict[str, Any]:
    """rcl_interfaces/msg/Parameter messages of a params file's sections (rclpy's helper for tools)."""
    import yaml

    with open(parameter_file) as f:
        data = yaml.safe_load(f) or {}
    keys: list[str] = []
    if use_wildcard and "/**" in data:
        keys.append("/**")
    if target_nodes:
        for n in target_nodes:
            if n not in data:
                raise RuntimeError(f"Param file does not contain parameters for {n},only for nodes: {list(data)} ")
            keys.append(n)
    else:
        keys.extend(k for k in data if k != "/**")
    if not keys:
        raise RuntimeError("Param file does not contain selected parameters")
    values: dict[str, Any] = {}
    for k in keys:
        section = data[k]
        if not isinstance(section, dict) or "ros__parameters" not in section:
            raise RuntimeError(f"YAML file is not a valid ROS parameter file for node {k}")
        values.update(section["ros__parameters"])
    out: dict[str, Any] = {}

    def unpack(prefix: str, d: dict[str, Any]) -> None:
        for name, value in d.items():
            full = f"{prefix}.{name}" if prefix else name
            if isinstance(value, dict):
                unpack(full, value)
            else:
                msg = cls("rcl_interfaces/msg/Parameter")(name=full, value=get_parameter_value(str(value)))
                if isinstance(value, (list, str)):
                    msg = Parameter(full, value=value).to_parameter_msg()
                out[full] = msg

    unpack(namespace, values)
    return out
