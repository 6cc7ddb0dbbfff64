"""parameter_blackboard (a node that accepts any parameter, the peer of async_param_client) and
set_and_get_parameters of demo_nodes_cpp."""

from __future__ import annotations

from rcl_interfaces.msg import Parameter as ParameterMsg
from rcl_interfaces.srv import ListParameters
from rclpy.node import Node
from rclpy.parameter import Parameter

from diffctl.demo_nodes.spin import spin_node

# rclcpp's names of the parameter types (rclcpp::to_string(ParameterType))
TYPE_NAMES = {
    Parameter.Type.NOT_SET: "not set",
    Parameter.Type.BOOL: "bool",
    Parameter.Type.INTEGER: "integer",
    Parameter.Type.DOUBLE: "double",
    Parameter.Type.STRING: "string",
    Parameter.Type.BYTE_ARRAY: "byte_array",
    Parameter.Type.BOOL_ARRAY: "bool_array",
    Parameter.Type.INTEGER_ARRAY: "integer_array",
    Parameter.Type.DOUBLE_ARRAY: "double_array",
    Parameter.Type.STRING_ARRAY: "string_array",
}


class Blackboard(Node):
    def __init__(self) -> None:
        super().__init__(
            "parameter_blackboard",
            allow_undeclared_parameters=True,
            automatically_declare_parameters_from_overrides=True,
        )
        count = len(self.list_parameters([], ListParameters.Request.DEPTH_RECURSIVE).names)
        self.get_logger().info(
            f"Parameter blackboard node named '{self.get_fully_qualified_name()}' ready, "
            f"and serving '{count}' parameters already!"
        )


def blackboard() -> int:
    return spin_node(Blackboard)


def _value_text(type_name: str, value: object) -> str:
    """rclcpp's Parameter::value_to_string: std::to_string for numbers, '[a, b]' arrays, bytes in 0x hex."""
    if type_name == "double":
        return f"{value:f}"
    if type_name == "bool":
        return "true" if value else "false"
    if type_name == "byte_array":
        return "[" + ", ".join(hex(b[0] if isinstance(b, bytes) else b) for b in value) + "]"
    if type_name == "bool_array":
        return "[" + ", ".join("true" if v else "false" for v in value) + "]"
    if type_name.endswith("_array"):
        return "[" + ", ".join(str(v) for v in value) + "]"
    return str(value)


def set_and_get() -> int:
    """demo_nodes_cpp's set_and_get_parameters: sets six parameters of its own through the parameter services,
    reads four back, logs them in one line, and exits."""
    import rclpy
    from rclpy.parameter_client import AsyncParameterClient

    rclpy.init()
    node = Node("set_and_get_parameters")
    try:
        node.declare_parameter("foo", 0)
        node.declare_parameter("bar", "")
        node.declare_parameter("baz", 0.0)
        node.declare_parameter("foobar", False)
        node.declare_parameter("foobarbaz", Parameter.Type.BOOL_ARRAY)
        node.declare_parameter("toto", Parameter.Type.BYTE_ARRAY)
        client = AsyncParameterClient(node, node.get_fully_qualified_name())
        while not client.wait_for_services(timeout_sec=1.0):
            if not rclpy.ok():
                node.get_logger().error("Interrupted while waiting for the service. Exiting.")
                return 0
            node.get_logger().info("service not available, waiting again...")
        future = client.set_parameters([
            Parameter("foo", value=2),
            Parameter("bar", value="hello"),
            Parameter("baz", value=1.45),
            Parameter("foobar", value=True),
            Parameter("foobarbaz", value=[True, False]),
            Parameter("toto", value=[b"\xff", b"\x7f"]),
        ])
        rclpy.spin_until_future_complete(node, future)
        for result in future.result().results:
            if not result.successful:
                node.get_logger().error(f"Failed to set parameter: {result.reason}")
        names = ["foo", "baz", "foobarbaz", "toto"]
        future = client.get_parameters(names)
        rclpy.spin_until_future_complete(node, future)
        text = ""
        for name, value in zip(names, future.result().values, strict=True):
            parameter = Parameter.from_parameter_msg(ParameterMsg(name=name, value=value))
            type_name = TYPE_NAMES[parameter.type_]
            shown = _value_text(type_name, parameter.value)
            text += f"\nParameter name: {name}\nParameter value ({type_name}): {shown}"
        node.get_logger().info(text)
    except KeyboardInterrupt:
        pass
    finally:
        node.destroy_node()
        rclpy.try_shutdown()
    return 0
