"""rclpy's exception types, with the messages rclpy gives them."""

from __future__ import annotations

from typing import Any

from diffctl import errors as _errors


class NotInitializedException(Exception):
    """Raised when the rclpy context is used before init() or after shutdown()."""

    def __init__(self, message: str | None = None) -> None:
        Exception.__init__(self, f"rclpy.init() has not been called. msg:{message}" if message
                           else "rclpy.init() has not been called.")


class NoTypeSupportImportedException(Exception):
    def __init__(self, *args: Any) -> None:
        Exception.__init__(self, "no type_support imported", *args)


class NameValidationException(Exception):
    """A node, namespace or topic name that ROS's validators reject."""

    def __init__(self, name_type: str, name: str, error_msg: str, invalid_index: int) -> None:
        self.name_type = name_type
        self.name = name
        self.error_msg = error_msg
        self.invalid_index = invalid_index
        Exception.__init__(
            self, f"Invalid {name_type}: {error_msg}:\n  '{name}'\n   {' ' * invalid_index}^"
        )


class InvalidNodeNameException(NameValidationException):
    def __init__(self, name: str, error_msg: str, invalid_index: int, *args: Any) -> None:
        NameValidationException.__init__(self, "node name", name, error_msg, invalid_index)


class InvalidNamespaceException(NameValidationException):
    def __init__(self, name: str, error_msg: str, invalid_index: int, *args: Any) -> None:
        NameValidationException.__init__(self, "namespace", name, error_msg, invalid_index)


class InvalidTopicNameException(NameValidationException):
    def __init__(self, name: str, error_msg: str, invalid_index: int, *args: Any) -> None:
        NameValidationException.__init__(self, "topic name", name, error_msg, invalid_index)


class InvalidServiceNameException(NameValidationException):
    def __init__(self, name: str, error_msg: str, invalid_index: int, *args: Any) -> None:
        NameValidationException.__init__(self, "service name", name, error_msg, invalid_index)


class ParameterException(Exception):
    """Base of the parameter errors; the names involved end the message, as in rclpy."""

    def __init__(self, error_msg: str, parameters: Any, *args: Any) -> None:
        Exception.__init__(self, f"{error_msg}: {parameters}")


class ParameterNotDeclaredException(ParameterException):
    def __init__(self, parameters: Any, *args: Any) -> None:
        ParameterException.__init__(self, "Invalid access to undeclared parameter(s)", parameters, *args)


class ParameterAlreadyDeclaredException(ParameterException):
    def __init__(self, parameters: Any, *args: Any) -> None:
        ParameterException.__init__(self, "Parameter(s) already declared", parameters, *args)


class InvalidParameterException(ParameterException):
    def __init__(self, parameter: Any, *args: Any) -> None:
        ParameterException.__init__(self, "Invalid parameter name", parameter, *args)


class InvalidParameterValueException(ParameterException):
    def __init__(self, parameter: Any, value: Any, reason: str, *args: Any) -> None:
        Exception.__init__(
            self, f"Invalid parameter value ({value}) for parameter. Reason: {reason}: {parameter}"
        )


class InvalidParameterTypeException(ParameterException):
    def __init__(self, desired_parameter: Any, expected_type: str, *args: Any) -> None:
        Exception.__init__(
            self,
            f"Trying to set parameter '{desired_parameter._name}' to '{desired_parameter._value}' of type "
            f"'{desired_parameter._type_.name}', expecting type '{expected_type}': {desired_parameter._name}",
        )


class ParameterImmutableException(ParameterException):
    def __init__(self, parameter: Any, *args: Any) -> None:
        ParameterException.__init__(self, "Attempted to modify read-only parameter", parameter, *args)


class ParameterUninitializedException(ParameterException):
    def __init__(self, parameter: Any, *args: Any) -> None:
        ParameterException.__init__(self, f"The parameter '{parameter}' is not initialized", parameter)


class ROSInterruptException(Exception):
    def __init__(self, *args: Any) -> None:
        Exception.__init__(self, "rclpy.shutdown() has been called", *args)


class RCLError(RuntimeError):
    """rclpy's RCLError (a RuntimeError): a failure the rcl layer would report."""


class InvalidHandle(RuntimeError):
    pass


class InvalidQoSProfileException(Exception):
    def __init__(self, *args: Any) -> None:
        Exception.__init__(self, "Invalid QoSProfile", *args)


class UnsupportedEventTypeError(RCLError):
    pass


class RCLInvalidROSArgsError(RCLError, _errors.ConfigError):
    """`--ros-args` with a malformed rule or an unreadable parameter file. Also diffctl's ConfigError, so a
    component handed such arguments ends with one line and exit code 2."""

    def __init__(self, message: str) -> None:
        _errors.ConfigError.__init__(self, message)


class UnknownROSArgsError(RuntimeError, _errors.ConfigError):
    """`--ros-args` holding arguments that are no ROS flag; the message lists them as a Python list."""

    def __init__(self, message: str) -> None:
        _errors.ConfigError.__init__(self, message)


class InvalidQosOverridesError(Exception):
    pass


class NodeNameNonExistentError(RCLError):
    """A graph query about a node that is not in the graph."""


# Tracebacks name them as rclpy does (`rclpy.exceptions.ParameterNotDeclaredException: …`); the overlay's
# rclpy.exceptions is where users import them from.
for _cls in list(globals().values()):
    if isinstance(_cls, type) and issubclass(_cls, Exception) and _cls.__module__ == __name__:
        _cls.__module__ = "rclpy.exceptions"
InvalidQosOverridesError.__module__ = "rclpy.qos_overriding_options"  # where rclpy defines it
# The ones rclpy's C++ binding defines: a traceback's last line reads `rclpy._rclpy_pybind11.RCLError: …`.
for _cls in (InvalidHandle, RCLError, RCLInvalidROSArgsError, UnknownROSArgsError, UnsupportedEventTypeError,
             NodeNameNonExistentError):
    _cls.__module__ = "rclpy._rclpy_pybind11"
