"""rcl_interfaces ParameterValue ↔ Python values, shared by the manager's parameter services and clients."""

from __future__ import annotations

from typing import Any

# rcl_interfaces/msg/ParameterType
P_NOT_SET, P_BOOL, P_INT, P_DOUBLE, P_STRING = 0, 1, 2, 3, 4
P_BOOL_ARRAY, P_INT_ARRAY, P_DOUBLE_ARRAY, P_STRING_ARRAY = 6, 7, 8, 9


def param_value_to_python(v: Any) -> Any:
    t = int(v.type)
    return {
        P_NOT_SET: lambda: None,
        P_BOOL: lambda: bool(v.bool_value),
        P_INT: lambda: int(v.integer_value),
        P_DOUBLE: lambda: float(v.double_value),
        P_STRING: lambda: str(v.string_value),
        P_BOOL_ARRAY: lambda: [bool(x) for x in v.bool_array_value],
        P_INT_ARRAY: lambda: [int(x) for x in v.integer_array_value],
        P_DOUBLE_ARRAY: lambda: [float(x) for x in v.double_array_value],
        P_STRING_ARRAY: lambda: [str(x) for x in v.string_array_value],
    }.get(t, lambda: None)()


def python_to_param_value(value: Any) -> dict[str, Any]:
    if value is None:
        return {"type": P_NOT_SET}
    if isinstance(value, bool):
        return {"type": P_BOOL, "bool_value": value}
    if isinstance(value, int):
        return {"type": P_INT, "integer_value": value}
    if isinstance(value, float):
        return {"type": P_DOUBLE, "double_value": value}
    if isinstance(value, str):
        return {"type": P_STRING, "string_value": value}
    if isinstance(value, list | tuple):
        if all(isinstance(x, bool) for x in value) and value:
            return {"type": P_BOOL_ARRAY, "bool_array_value": list(value)}
        if all(isinstance(x, int) and not isinstance(x, bool) for x in value) and value:
            return {"type": P_INT_ARRAY, "integer_array_value": list(value)}
        if all(isinstance(x, int | float) and not isinstance(x, bool) for x in value) and value:
            return {"type": P_DOUBLE_ARRAY, "double_array_value": [float(x) for x in value]}
        return {"type": P_STRING_ARRAY, "string_array_value": [str(x) for x in value]}
    return {"type": P_STRING, "string_value": str(value)}
