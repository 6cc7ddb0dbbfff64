"""Conditions for actions: on an expression's truth, or (deprecated) on a launch configuration's value."""

from .._private.lazy import lazy_exports

__getattr__, __dir__, __all__ = lazy_exports(__name__, globals(), {
    '.if_condition': ('IfCondition',),
    '.unless_condition': ('UnlessCondition',),
    '.evaluate_condition_expression_impl': ('evaluate_condition_expression',),
    '.invalid_condition_expression_error': ('InvalidConditionExpressionError',),
    '.launch_configuration_equals': ('LaunchConfigurationEquals',),
    '.launch_configuration_not_equals': ('LaunchConfigurationNotEquals',),
})
