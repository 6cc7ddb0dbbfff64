"""rclpy.impl.implementation_singleton: `rclpy_implementation`, rclpy's binding to rcl; here the module of the
names programs reach through it (its exceptions and enums), diffctl.client being the implementation."""

import types

from diffctl.client import exceptions as _exceptions
from diffctl.client import service_introspection as _service_introspection

rclpy_implementation = types.SimpleNamespace(
    **{name: getattr(_exceptions, name) for name in dir(_exceptions)
       if isinstance(getattr(_exceptions, name), type) and issubclass(getattr(_exceptions, name), Exception)},
    ServiceIntrospectionState=_service_introspection.ServiceIntrospectionState,
)

package = "rclpy"
