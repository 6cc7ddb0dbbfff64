# QoS overriding options as the qos_overrides demos use them: the qos_overrides.* parameters a publisher and a
# subscription declare, overrides from parameter_overrides, and the validation callback (QosCallbackResult).
import json

import rclpy
from rclpy.node import Node
from rclpy.parameter import Parameter
from rclpy.qos_overriding_options import InvalidQosOverridesError, QosCallbackResult, QoSOverridingOptions
from std_msgs.msg import String

out = []
rclpy.init()


def check(qos):
    result = QosCallbackResult()
    if qos.depth <= 10:
        result.successful = True
        return result
    result.successful = False
    result.reason = "expected qos depth less than 10"
    return result


out.append(["QosCallbackResult", QosCallbackResult.__name__])
talker = Node("qos_overrides_talker", parameter_overrides=[
    Parameter("qos_overrides./qos_overrides_chatter.publisher.reliability", value="best_effort"),
    Parameter("qos_overrides./qos_overrides_chatter.publisher.depth", value=9)])
pub = talker.create_publisher(String, "qos_overrides_chatter", 10,
                              qos_overriding_options=QoSOverridingOptions.with_default_policies(callback=check))
out.append(["publisher qos", [pub.qos_profile.depth, pub.qos_profile.reliability.name, pub.qos_profile.history.name]])
names = sorted(talker.list_parameters(["qos_overrides"], 0).names)
out.append(["declared", [[n, talker.get_parameter(n).value] for n in names]])
desc = talker.describe_parameter(names[0])
out.append(["descriptor", [desc.description, desc.read_only, desc.type]])
listener = Node("qos_overrides_listener")
sub = listener.create_subscription(String, "qos_overrides_chatter", lambda m: None, 10,
                                   qos_overriding_options=QoSOverridingOptions.with_default_policies(
                                       entity_id="my_id"))
out.append(["subscription parameters", sorted(listener.list_parameters(["qos_overrides"], 0).names)])
bad = Node("bad_talker", parameter_overrides=[
    Parameter("qos_overrides./qos_overrides_chatter.publisher.depth", value=11)])
try:
    bad.create_publisher(String, "qos_overrides_chatter", 10,
                         qos_overriding_options=QoSOverridingOptions.with_default_policies(callback=check))
    out.append(["refused", None])
except InvalidQosOverridesError as e:
    out.append(["refused", [f"{type(e).__module__}.{type(e).__name__}", str(e)]])
try:
    talker.set_parameters([Parameter("qos_overrides./qos_overrides_chatter.publisher.depth", value=5)])
    out.append(["read only", None])
except Exception as e:
    out.append(["read only", type(e).__name__])
# rclpy's module-private helpers, which packages import: the entity named by its class, one policy's value
from rclpy.publisher import Publisher  # noqa: E402
from rclpy.qos import QoSPolicyKind, QoSProfile  # noqa: E402
from rclpy.qos_overriding_options import _declare_qos_parameters, _get_qos_policy_parameter  # noqa: E402

helper_node = Node("qos_helper_demo")
profile = QoSProfile(depth=3)
_declare_qos_parameters(Publisher, helper_node, "/helped", profile,
                        QoSOverridingOptions.with_default_policies(entity_id="x"))
try:
    _declare_qos_parameters(int, helper_node, "/helped", profile, QoSOverridingOptions.with_default_policies())
    refused_type = "no error"
except TypeError as e:
    refused_type = str(e)
out.append(["private helpers", [sorted((k, p.value) for k, p in helper_node.get_parameters_by_prefix(
    "qos_overrides").items()), [_get_qos_policy_parameter(profile, k) for k in (
        QoSPolicyKind.HISTORY, QoSPolicyKind.DEPTH, QoSPolicyKind.RELIABILITY, QoSPolicyKind.DEADLINE)],
    refused_type]])
helper_node.destroy_node()
rclpy.shutdown()
print(json.dumps(out))
