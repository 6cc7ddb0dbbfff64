"""A node's parameters with rclpy's semantics: every declare, get and set decided the way rclpy's Node does.

Descriptors are rcl_interfaces messages, an override wins before the checks, pre/on/post-set callbacks run
newest first, failures come back as SetParametersResult with rclpy's exceptions and texts; the node's own
calls and its parameter services (`parameter_service.py`) go through the same code. Every accepted change
is handed to `on_event`, which the node turns into `/parameter_events`.
"""

from __future__ import annotations

import math
import threading
import warnings
from collections.abc import Callable
from typing import Any

from diffctl.bus.session import before_close
from diffctl.client.exceptions import (
    InvalidParameterTypeException,
    InvalidParameterValueException,
    ParameterAlreadyDeclaredException,
    ParameterImmutableException,
    ParameterNotDeclaredException,
    ParameterUninitializedException,
)
from diffctl.client.interfaces import cls
from diffctl.client.parameter import PARAMETER_SEPARATOR_STRING, Parameter

PARAM_REL_TOL = 1e-6
# rclcpp::to_string(ParameterType)
_RCLCPP_TYPE = {0: "not set", 1: "bool", 2: "integer", 3: "double", 4: "string", 5: "byte_array", 6: "bool_array",
                7: "integer_array", 8: "double_array", 9: "string_array"}


def _descriptor(**kw: Any) -> Any:
    return cls("rcl_interfaces/msg/ParameterDescriptor")(**kw)


def _result(successful: bool, reason: str = "") -> Any:
    return cls("rcl_interfaces/msg/SetParametersResult")(successful=successful, reason=reason)


# /parameter_events leave in the order the changes were made in this process: one publication at a time.
_events_lock = threading.RLock()


def _publishing_done() -> None:
    """A publication under way ends before the session closes (none is attempted once it closes)."""
    if _events_lock.acquire(timeout=2.0):
        _events_lock.release()


before_close(_publishing_done, first=True)


def validate_parameter_name(name: str) -> bool:
    if not name:  # rclpy checks nothing else
        from diffctl.client.exceptions import InvalidParameterException

        raise InvalidParameterException(name)
    return True


class NodeParameters:
    def __init__(self, *, overrides: dict[str, Parameter], allow_undeclared: bool, rclcpp: bool = False) -> None:
        """`rclcpp`: refusals worded as rclcpp words them (a diffctl node that ROS writes in C++)."""
        self.allow_undeclared = allow_undeclared
        self.rclcpp = rclcpp
        self.param_overrides = overrides
        self.parameters: dict[str, Parameter] = {}
        self.msg_descriptors: dict[str, Any] = {}
        self.pre_set: list[Callable[[list[Parameter]], list[Parameter]]] = []
        self.on_set: list[Callable[[list[Parameter]], Any]] = []
        self.post_set: list[Callable[[list[Parameter]], None]] = []
        self.rlock = threading.RLock()
        # (new, changed, deleted) of each accepted set, for /parameter_events
        self.on_event: Callable[[list[Parameter], list[Parameter], list[Parameter]], None] | None = None

    def _notify(self, new: list[Parameter], changed: list[Parameter], deleted: list[Parameter]) -> None:
        # /parameter_events leave before the declare or set that caused them returns, as rcl publishes them (a
        # watcher made after a node never hears the node's start declarations, as with rclpy), published by the
        # thread that made the change. A worker thread published them, the declare waiting for it: a hand-over
        # per declaration, several ms each on a loaded machine, and a controller's load declares a dozen.
        if self.on_event is not None and (new or changed or deleted):
            with _events_lock:
                self.on_event(new, changed, deleted)

    # ------------------------------------------------------------------ rclpy's API
    def declare_parameters(self, namespace: str, parameters: list[tuple], ignore_override: bool = False
                           ) -> list[Parameter]:
        desc_cls = cls("rcl_interfaces/msg/ParameterDescriptor")
        plist: list[Parameter] = []
        descriptors: dict[str, Any] = {}
        for index, tup in enumerate(parameters):
            if len(tup) < 1 or len(tup) > 3:
                raise TypeError(f"Invalid parameter tuple length at index {index} in parameters list: {tup}; "
                                "expecting length between 1 and 3")
            name = tup[0]
            if not isinstance(name, str):
                raise TypeError(f"First element {name} at index {index} in parameters list is not a str.")
            if namespace:
                name = f"{namespace}.{name}"
            validate_parameter_name(name)
            second = tup[1] if len(tup) > 1 else None
            descriptor = tup[2] if len(tup) > 2 else desc_cls()
            if not isinstance(descriptor, desc_cls):
                raise TypeError(f"Third element {descriptor} at index {index} in parameters list is not a "
                                "ParameterDescriptor.")
            value = None
            if len(tup) == 1:
                warnings.warn(
                    f"when declaring parameter named '{name}', declaring a parameter only providing its name is "
                    "deprecated. You have to either:\n\t- Pass a name and a default value different to "
                    '"PARAMETER NOT SET" (and optionally a descriptor).\n\t- Pass a name and a parameter type.\n'
                    "\t- Pass a name and a descriptor with `dynamic_typing=True", stacklevel=3)
                descriptor.dynamic_typing = True
            if isinstance(second, Parameter.Type):
                if second == Parameter.Type.NOT_SET:
                    raise ValueError(f"Cannot declare parameter {{{name}}} as statically typed of type NOT_SET")
                if descriptor.dynamic_typing is True:
                    raise ValueError(f"When declaring parameter {{{name}}} passing a descriptor with"
                                     "`dynamic_typing=True` is not allowed when the parameter type is provided")
                descriptor.type = second.value
            else:
                value = second
                if not descriptor.dynamic_typing:
                    # A ParameterValue message as the default (its class is not made just to ask).
                    if type(value).__name__ == "ParameterValue" and hasattr(value, "double_array_value"):
                        descriptor.type = value.type
                    else:
                        descriptor.type = Parameter.Type.from_parameter_value(value).value
                    if descriptor.type == 0:
                        raise ValueError("Cannot declare a statically typed parameter with default value of type "
                                         "PARAMETER_NOT_SET")
            if not ignore_override and name in self.param_overrides:
                value = self.param_overrides[name].value
            plist.append(Parameter(name, value=value))
            descriptors[name] = descriptor
        with self.rlock:
            already = [p.name for p in plist if p.name in self.parameters]
            if any(already):
                raise ParameterAlreadyDeclaredException(already)
            for p in plist:
                result = self._set_common([p], descriptors, allow_not_set_type=True)
                if not result.successful:
                    if result.reason.startswith("Wrong parameter type"):
                        raise InvalidParameterTypeException(p, Parameter.Type(descriptors[p.name].type).name)
                    raise InvalidParameterValueException(p.name, p.value, result.reason)
            return [self.parameters[p.name] for p in plist]

    def undeclare_parameter(self, name: str) -> None:
        with self.rlock:
            if name not in self.parameters:
                raise ParameterNotDeclaredException(name)
            if self.msg_descriptors[name].read_only:
                raise ParameterImmutableException(name)
            del self.parameters[name]
            del self.msg_descriptors[name]

    def get_parameter(self, name: str) -> Parameter:
        if name in self.parameters:
            p = self.parameters[name]
            if p.type_ != Parameter.Type.NOT_SET or self.msg_descriptors[name].dynamic_typing:
                return p
            raise ParameterUninitializedException(name)
        if self.allow_undeclared:
            return Parameter(name, Parameter.Type.NOT_SET, None)
        raise ParameterNotDeclaredException(name)

    def get_parameter_or(self, name: str, alternative_value: Parameter | None = None) -> Parameter:
        if alternative_value is None:
            alternative_value = Parameter(name, Parameter.Type.NOT_SET)
        p = self.parameters.get(name)
        if p is None or p.type_ == Parameter.Type.NOT_SET:
            return alternative_value
        return p

    def get_parameter_type(self, name: str) -> Parameter.Type:
        if name in self.parameters:
            return self.parameters[name].type_.value
        if self.allow_undeclared:
            return Parameter.Type.NOT_SET
        raise ParameterNotDeclaredException(name)

    def get_parameters_by_prefix(self, prefix: str) -> dict[str, Parameter]:
        if prefix:
            prefix += PARAMETER_SEPARATOR_STRING
        return {n[len(prefix):]: p for n, p in self.parameters.items() if n.startswith(prefix)}

    def set_parameters(self, parameter_list: list[Parameter]) -> list[Any]:
        return [self.set_parameters_atomically([p]) for p in parameter_list]

    def set_parameters_atomically(self, parameter_list: list[Parameter]) -> Any:
        with self.rlock:
            if self.pre_set:
                modified: list[Parameter] = []
                for cb in self.pre_set:
                    modified.extend(cb(parameter_list))
                parameter_list = modified
                if len(parameter_list) == 0:
                    return _result(False, "parameter list cannot be empty, this might be due to "
                                          "pre_set_parameters_callback modifying the original parameters list.")
            if not all(isinstance(p, Parameter) for p in parameter_list):
                raise TypeError(f"parameter must be instance of type '{Parameter!r}'")
            undeclared = [p.name for p in parameter_list if p.name not in self.parameters]
            if not self.allow_undeclared and any(undeclared):
                # rclpy builds this list from an exhausted generator: it prints as [].
                raise ParameterNotDeclaredException([])
            return self._set_common(parameter_list)

    def describe_parameter(self, name: str) -> Any:
        try:
            return self.msg_descriptors[name]
        except KeyError:
            if self.allow_undeclared:
                return _descriptor()
            raise ParameterNotDeclaredException(name) from None

    def set_descriptor(self, name: str, descriptor: Any, alternative_value: Any = None) -> Any:
        with self.rlock:
            if name not in self.parameters:
                if not self.allow_undeclared:
                    raise ParameterNotDeclaredException(name)
                return self.get_parameter(name).get_parameter_value()
            if self.describe_parameter(name).read_only:
                raise ParameterImmutableException(name)
            current = self.get_parameter(name)
            alternative = current if alternative_value is None else Parameter.from_parameter_msg(
                cls("rcl_interfaces/msg/Parameter")(name=name, value=alternative_value))
            if not self._apply_and_store(current, descriptor).successful:
                r = self._apply_and_store(alternative, descriptor)
                if not r.successful:
                    raise InvalidParameterValueException(name, alternative.value, r.reason)
            self.msg_descriptors[name] = descriptor
            return self.get_parameter(name).get_parameter_value()

    def list_parameters(self, prefixes: list[str], depth: int) -> Any:
        if not isinstance(prefixes, list):
            raise TypeError("The prefixes argument must be a list")
        if not all(isinstance(p, str) for p in prefixes):
            raise TypeError("All prefixes must be instances of type str")
        if not isinstance(depth, int):
            raise TypeError("The depth must be instance of type int")
        if depth < 0:
            raise ValueError("The depth must be greater than or equal to zero")
        names, parents = self._list(prefixes, depth)
        return cls("rcl_interfaces/msg/ListParametersResult")(names=names, prefixes=parents)

    def _list(self, prefixes: list[str], depth: int) -> tuple[list[str], list[str]]:
        def shallow(s: str) -> bool:
            return s.count(PARAMETER_SEPARATOR_STRING) < depth

        recursive = not prefixes and depth == 0
        names: list[str] = []
        parents: list[str] = []
        for name in list(self.parameters):
            if not recursive:
                get_all = not prefixes and shallow(name)
                if not get_all and not any(
                    name == p or (name.startswith(p + ".") and (depth == 0 or shallow(name[len(p) + 1:])))
                    for p in prefixes
                ):
                    continue
            names.append(name)
            i = name.rfind(".")
            if i != -1 and name[:i] not in parents:
                parents.append(name[:i])
        return names, parents

    # ------------------------------------------------------------------ the set
    def _apply_and_store(self, p: Parameter, descriptor: Any) -> Any:
        r = self._apply_descriptor(p, descriptor, False)
        if r.successful:
            self.parameters[p.name] = p
        return r

    def _apply_descriptor(self, p: Parameter, descriptor: Any, check_read_only: bool) -> Any:
        descriptor.name = p.name
        if check_read_only and descriptor.read_only:
            return _result(False, f"parameter '{p.name}' cannot be set because it is read-only" if self.rclcpp
                           else f"Trying to set a read-only parameter: {p.name}.")
        if descriptor.dynamic_typing:
            descriptor.type = p.type_.value
        elif p.name in self.parameters and p.type_ == Parameter.Type.NOT_SET:
            return _result(False, "Static parameter cannot be undeclared")
        elif p.type_ != Parameter.Type.NOT_SET and p.type_.value != descriptor.type:
            if self.rclcpp:
                return _result(False, f"Wrong parameter type, parameter {{{p.name}}} is of type "
                                      f"{{{_RCLCPP_TYPE[descriptor.type]}}}, setting it to "
                                      f"{{{_RCLCPP_TYPE[p.type_.value]}}} is not allowed.")
            return _result(False, f"Wrong parameter type, expected '{Parameter.Type(descriptor.type)}' "
                                  f"got '{p.type_}'")
        if p.type_ == Parameter.Type.INTEGER and descriptor.integer_range:
            r = _integer_range(p, descriptor.integer_range[0])
            return _result(False, f"Parameter {{{p.name}}} doesn't comply with integer range.") \
                if self.rclcpp and not r.successful else r
        if p.type_ == Parameter.Type.DOUBLE and descriptor.floating_point_range:
            r = _float_range(p, descriptor.floating_point_range[0])
            return _result(False, f"Parameter {{{p.name}}} doesn't comply with floating point range.") \
                if self.rclcpp and not r.successful else r
        return _result(True)

    def _set_common(self, plist: list[Parameter], descriptors: dict[str, Any] | None = None,
                    allow_not_set_type: bool = False) -> Any:
        table = descriptors if descriptors is not None else self.msg_descriptors
        for p in plist:
            if p.name in table:
                r = self._apply_descriptor(p, table[p.name], descriptors is None)
                if not r.successful:
                    return r
        result_cls = cls("rcl_interfaces/msg/SetParametersResult")
        for cb in self.on_set:
            r = cb(plist)
            if not isinstance(r, result_cls):
                warnings.warn("Callback returned an invalid type, it should return SetParameterResult.",
                              stacklevel=2)
                r = _result(False, "Callback returned an invalid type")
            if not r.successful:
                return r
        new: list[Parameter] = []
        changed: list[Parameter] = []
        deleted: list[Parameter] = []
        for p in plist:
            if not allow_not_set_type and p.type_ == Parameter.Type.NOT_SET:
                deleted.append(p)
                self.parameters.pop(p.name, None)
                self.msg_descriptors.pop(p.name, None)
                continue
            if descriptors is not None:
                self.msg_descriptors[p.name] = descriptors[p.name]
            elif p.name not in self.msg_descriptors:
                # An undeclared parameter being set: rclpy keeps it dynamically typed; rclcpp declares it
                # implicitly, named and typed by its value.
                self.msg_descriptors[p.name] = (_descriptor(name=p.name, type=p.type_.value) if self.rclcpp
                                                else _descriptor(dynamic_typing=True))
            is_new = self.get_parameter_or(p.name).type_ == Parameter.Type.NOT_SET
            (new if is_new else changed).append(p)
            self.parameters[p.name] = p
        self._notify(new, changed, deleted)
        for cb in self.post_set:
            cb(plist)
        return _result(True)


def _integer_range(p: Parameter, rng: Any) -> Any:
    lo, hi = min(rng.from_value, rng.to_value), max(rng.from_value, rng.to_value)
    if p.value in (lo, hi):
        return _result(True)
    if not lo < p.value < hi:
        return _result(False, f"Parameter {p.name} out of range. Min: {lo}, Max: {hi}, value: {p.value}")
    if rng.step != 0 and (p.value - lo) % rng.step != 0:
        return _result(False, f"The parameter value for {p.name} is not a valid step. "
                              f"Min: {lo}, max: {hi}, value: {p.value}, step: {rng.step}")
    return _result(True)


def _float_range(p: Parameter, rng: Any) -> Any:
    lo, hi = min(rng.from_value, rng.to_value), max(rng.from_value, rng.to_value)
    if math.isclose(p.value, lo, rel_tol=PARAM_REL_TOL) or math.isclose(p.value, hi, rel_tol=PARAM_REL_TOL):
        return _result(True)
    if not lo < p.value < hi:
        return _result(False, f"Parameter {p.name} out of range Min: {lo}, Max: {hi}, value: {p.value}")
    if rng.step != 0.0:
        n = round((p.value - lo) / rng.step)
        if not math.isclose(lo + n * rng.step, p.value, rel_tol=PARAM_REL_TOL):
            return _result(False, f"The parameter value for {p.name} is not close enough to a valid step. "
                                  f"Min: {lo}, max: {hi}, value: {p.value}, step: {rng.step}")
    return _result(True)
