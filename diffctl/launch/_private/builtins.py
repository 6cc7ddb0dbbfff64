"""Importing launch's own exposed actions and substitutions before the frontend's registry is read.

`launch.actions` and `launch.substitutions` import their modules on first use, so the `expose_*`
decorators of the built-in ones have not necessarily run when a markup file is parsed.
"""

from __future__ import annotations

import importlib

_ACTION_MODULES = (
    'append_environment_variable', 'declare_launch_argument', 'execute_process', 'group_action',
    'include_launch_description', 'log_info', 'reset_environment', 'reset_launch_configurations',
    'set_environment_variable', 'set_launch_configuration', 'shutdown_action', 'timer_action',
    'unset_environment_variable',
)
_SUBSTITUTION_MODULES = (
    'anon_name', 'boolean_substitution', 'command', 'environment_variable', 'equals_substitution',
    'file_content', 'find_executable', 'if_else_substitution', 'launch_configuration', 'launch_log_dir',
    'not_equals_substitution', 'python_expression', 'this_launch_file', 'this_launch_file_dir',
)
_loaded = False


def load_builtin_frontend_names() -> None:
    """Import every module of launch that exposes a tag or a substitution name (once)."""
    global _loaded
    if _loaded:
        return
    package = __name__.rsplit('.', 2)[0]
    for module in _ACTION_MODULES:
        importlib.import_module(f'{package}.actions.{module}')
    for module in _SUBSTITUTION_MODULES:
        importlib.import_module(f'{package}.substitutions.{module}')
    _loaded = True
