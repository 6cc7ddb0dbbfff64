"""The controller manager's node: a client Node declared as controller_manager declares it.

`make_manager_node` makes `/<ns>/<controller_manager_name>` with controller_manager's node options: undeclared
parameters allowed and every override declared as given (so `<controller>.type`, `update_rate`, … from the
parameter files appear as plain parameters, as in Jazzy), logger services on, an rclcpp node's declarations.
Then the parameters of controller_manager_parameters.yaml (`MANAGER_DECLS`, generate_parameter_library's
descriptors) are declared where no override did, and `overruns.print_warnings` with the manager's own default
(true unless on sim time).
`manager_flat_params` reads the values back for `params.manager_params`.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from diffctl.control.controllers.param_decl import Check, ParamDecl, declare, table

_GT0 = (Check("gt", (0,)),)
_GT0_DOUBLE = (Check("gt", (0.0,)),)
_UNIQUE = (Check("unique", ()),)
_OVERRUNS_TEXT = (
    "If true, the controller manager will print a warning message to the console if an overrun is detected in its "
    "real-time loop (read, update and write). By default, it is set to true, except when used with use_sim_time "
    "parameter set to true."
)


def _diagnostics() -> list[ParamDecl]:
    """diagnostics.threshold.* (controller_manager_parameters.yaml): warn/error thresholds of the manager's,
    the controllers' and the hardware components' periodicity and execution time."""
    out = []
    subjects = (
        ("controller_manager", "the controller manager's periodicity in Hz", None),
        ("controllers", "the controller update loop in Hz",
         "the controller's update cycle execution time in microseconds"),
        ("hardware_components", "the hardware component's read/write loop in Hz",
         "the hardware component's read/write cycle execution time in microseconds"),
    )
    for subject, periodicity, execution in subjects:
        for kind, what, defaults in (("periodicity", periodicity, (5.0, 10.0, 5.0, 10.0)),
                                     ("execution_time", execution, (1000.0, 2000.0, 100.0, 200.0))):
            if what is None:
                continue
            values = iter(defaults)
            for statistic, stat_text in (("mean_error", "mean error"), ("standard_deviation", "standard deviation")):
                for level in ("warn", "error"):
                    text = what
                    article = "a warning" if level == "warn" else "an error"
                    if subject == "hardware_components" and kind == "execution_time" and level == "error":
                        # the YAML's own wording of these two
                        if statistic == "mean_error":
                            article = "a error"
                        else:
                            text = "the hardware component's update cycle execution time in microseconds"
                    threshold = "warning" if level == "warn" else "error"
                    out.append(ParamDecl(
                        f"diagnostics.threshold.{subject}.{kind}.{statistic}.{level}", "double", next(values),
                        f"The {threshold} threshold for the {stat_text} of {text}. If the {stat_text} exceeds this "
                        f"threshold, {article} diagnostic will be published.", checks=_GT0_DOUBLE,
                    ))
    return out


# controller_manager_parameters.yaml (ros2_control, jazzy), in its order.
MANAGER_DECLS: dict[str, ParamDecl] = table([
    ParamDecl("update_rate", "int", 100,
              "The frequency of controller manager's real-time update loop. This loop reads states from hardware, "
              "updates controllers and writes commands to hardware.", True, _GT0),
    ParamDecl("enforce_command_limits", "bool", False,
              "If true, the controller manager will enforce command limits defined in the robot description. If "
              "false, no limits will be enforced. If true, when the command is outside the limits, the command is "
              "clamped to be within the limits depending on the type of configured joint limits defined in the robot "
              "description. If the command is within the limits, the command is passed through without any changes.",
              True),
    ParamDecl("handle_exceptions", "bool", True,
              "If true, the controller manager will catch exceptions thrown during the different operations of "
              "controllers and hardware components. If false, exceptions will propagate up and will cause the "
              "controller manager to crash.", True),
    ParamDecl("hardware_components_initial_state.unconfigured", "string_array", [],
              "Defines which hardware components will be only loaded when controller manager is started. These "
              "hardware components will need to be configured and activated manually or via a hardware spawner.",
              checks=_UNIQUE),
    ParamDecl("hardware_components_initial_state.inactive", "string_array", [],
              "Defines which hardware components will be configured when controller manager is started. These "
              "hardware components will need to be activated manually or via a hardware spawner.", checks=_UNIQUE),
    ParamDecl("hardware_components_initial_state.shutdown_on_initial_state_failure", "bool", True,
              "Specifies whether the controller manager should shut down if setting the desired initial state fails "
              "during startup.", True),
    ParamDecl("defaults.switch_controller.strictness", "string", "best_effort",
              "The default switch controller strategy. This strategy is used when no strategy is specified in the "
              "switch_controller service call.",
              checks=(Check("not_empty", ()), Check("one_of", (["strict", "best_effort"],)))),
    ParamDecl("defaults.allow_controller_activation_with_inactive_hardware", "bool", False,
              "If true, controllers are allowed to claim resources from inactive hardware components. If false, "
              "controllers can only claim resources from active hardware components. However, it is not recommended "
              "to set this parameter to true for the safety reasons with the hardware and unexpected movement, this "
              "is purely added for backward compatibility.", True),
    ParamDecl("defaults.deactivate_controllers_on_hardware_self_deactivate", "bool", True,
              "If set to true, when a hardware component returns DEACTIVATE on the write cycle, controllers using "
              "those interfaces will be deactivated. When set to false, controllers using those interfaces will "
              "continue to run. It is not recommended to set this parameter to false for safety reasons with "
              "hardware. This will be the default behaviour of the controller manager and this parameter will be "
              "removed in future releases. Please use with caution.", True),
    *_diagnostics(),
])


def make_manager_node(name: str, namespace: str, arguments: Sequence[str], *, context: Any = None,
                      use_global_arguments: bool = True) -> Any:
    """The manager's client Node with its parameters declared (raises the client's exceptions on bad arguments;
    the values are validated by `params.manager_params`)."""
    from diffctl.client.interfaces import cls
    from diffctl.client.node import Node

    node = Node(name, namespace=namespace, cli_args=list(arguments), context=context,
                use_global_arguments=use_global_arguments, allow_undeclared_parameters=True,
                automatically_declare_parameters_from_overrides=True, enable_logger_service=True,
                client_library="rclcpp")
    if not node.has_parameter("overruns.print_warnings"):
        use_sim_time = node.get_parameter("use_sim_time").value is True
        node.declare_parameter("overruns.print_warnings", not use_sim_time,
                               cls("rcl_interfaces/msg/ParameterDescriptor")(description=_OVERRUNS_TEXT))
    for decl_name, decl in MANAGER_DECLS.items():
        if not node.has_parameter(decl_name):
            declare(node, decl, decl.default)
    return node


def manager_flat_params(node: Any) -> dict[str, Any]:
    """Every parameter of the manager node that has a value, by name."""
    from diffctl.client.parameter import Parameter

    return {n: p.value for n, p in node.get_parameters_by_prefix("").items() if p.type_ != Parameter.Type.NOT_SET}
