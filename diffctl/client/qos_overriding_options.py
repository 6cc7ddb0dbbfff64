"""rclpy.qos_overriding_options: a publisher's or subscription's QoS policies as read-only parameters.

`qos_overrides./topic.publisher[_id].<policy>` is declared with the profile's value (policies by their short
name, durations in nanoseconds); an override (`-p`, a params file) replaces the policy before the endpoint is
created, and the user's callback may refuse the result.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import Any

from diffctl.client.duration import Duration
from diffctl.client.exceptions import InvalidQosOverridesError, ParameterAlreadyDeclaredException
from diffctl.client.interfaces import cls
from diffctl.client.qos import (
    DurabilityPolicy,
    HistoryPolicy,
    LivelinessPolicy,
    QoSPolicyKind,
    QoSProfile,
    ReliabilityPolicy,
)

# rclpy's alias: a QoS callback answers as a set-parameters callback does.
QosCallbackResult = cls("rcl_interfaces/msg/SetParametersResult")
QosCallbackType = Callable[[QoSProfile], Any]

_ENUMS = {QoSPolicyKind.HISTORY: HistoryPolicy, QoSPolicyKind.RELIABILITY: ReliabilityPolicy,
          QoSPolicyKind.DURABILITY: DurabilityPolicy, QoSPolicyKind.LIVELINESS: LivelinessPolicy}
_DURATIONS = (QoSPolicyKind.LIFESPAN, QoSPolicyKind.DEADLINE, QoSPolicyKind.LIVELINESS_LEASE_DURATION)


class QoSOverridingOptions:
    def __init__(self, policy_kinds: Iterable[QoSPolicyKind], *, callback: Callable[[QoSProfile], Any] | None = None,
                 entity_id: str | None = None) -> None:
        self._policy_kinds = policy_kinds
        self._callback = callback
        self._entity_id = entity_id

    @property
    def policy_kinds(self) -> Iterable[QoSPolicyKind]:
        return self._policy_kinds

    @property
    def callback(self) -> Callable[[QoSProfile], Any] | None:
        return self._callback

    @property
    def entity_id(self) -> str | None:
        return self._entity_id

    @classmethod
    def with_default_policies(cls_, *, callback: Callable[[QoSProfile], Any] | None = None,
                              entity_id: str | None = None) -> QoSOverridingOptions:
        return cls_(policy_kinds=(QoSPolicyKind.HISTORY, QoSPolicyKind.DEPTH, QoSPolicyKind.RELIABILITY),
                    callback=callback, entity_id=entity_id)


def _policy_value(qos: QoSProfile, policy: QoSPolicyKind) -> Any:
    value = getattr(qos, policy.name.lower())
    if policy in _ENUMS:
        text = value.name.lower()
        if text == "unknown":
            raise ValueError("User provided QoS profile is invalid")
        return text
    if isinstance(value, Duration):
        return value.nanoseconds
    return value


def _apply(qos: QoSProfile, policy: QoSPolicyKind, value: Any) -> None:
    if policy in _ENUMS:
        try:
            value = _ENUMS[policy][str(value).upper()]
        except KeyError:  # left chained, as rclpy's: the traceback shows the KeyError of the upper-cased value too
            raise RuntimeError(f"Unexpected QoS override for policy `{policy.name.lower()}`: `{value}`")  # noqa: B904
    elif policy in _DURATIONS:
        value = Duration(nanoseconds=value)
    setattr(qos, policy.name.lower(), value)


def declare_qos_parameters(kind: str, node: Any, topic_name: str, qos: QoSProfile,
                           options: QoSOverridingOptions, *, rclcpp: bool = False) -> None:
    """`kind` is "publisher" or "subscription"; `qos` is changed in place, as rclpy does. `rclcpp` describes
    the parameters as rclcpp does (for diffctl's nodes that ROS writes in C++)."""
    suffix = "" if options.entity_id is None else f"_{options.entity_id}"
    name = f"qos_overrides.{topic_name}.{kind}{suffix}." + "{}"
    def description(policy_name: str) -> str:
        if rclcpp:
            with_id = f" with id {{{options.entity_id}}}" if options.entity_id else ""
            return f"qos policy {{{policy_name}}} for {kind} {{{topic_name}}}{with_id}"
        return f"{policy_name} for {kind} `{topic_name}` with id `{options.entity_id}`"

    for policy in options.policy_kinds:
        if policy == QoSPolicyKind.INVALID or (kind == "subscription" and policy == QoSPolicyKind.LIFESPAN):
            continue
        policy_name = policy.name.lower()
        descriptor = cls("rcl_interfaces/msg/ParameterDescriptor")(
            description=description(policy_name), read_only=True)
        try:
            param = node.declare_parameter(name.format(policy_name), _policy_value(qos, policy), descriptor)
        except ParameterAlreadyDeclaredException:
            param = node.get_parameter(name.format(policy_name))
        _apply(qos, policy, param.value)
    if options.callback is not None:
        result = options.callback(qos)
        if not result.successful:
            raise InvalidQosOverridesError(
                f"{description('Provided QoS overrides')}, are not valid: {result.reason}")


def _declare_qos_parameters(entity_type: type, node: Any, topic_name: str, qos: QoSProfile,
                            options: QoSOverridingOptions) -> None:
    """rclpy's private spelling, which community code calls: the entity is named by its class."""
    from diffctl.client.publisher import Publisher
    from diffctl.client.subscription import Subscription

    if not (isinstance(entity_type, type) and issubclass(entity_type, (Publisher, Subscription))):
        raise TypeError("Argument `entity_type` should be a subclass of Publisher or Subscription")
    kind = "publisher" if issubclass(entity_type, Publisher) else "subscription"
    declare_qos_parameters(kind, node, topic_name, qos, options)


# rclpy's name for one policy's parameter value (enum policies by their short name, durations in nanoseconds)
_get_qos_policy_parameter = _policy_value
