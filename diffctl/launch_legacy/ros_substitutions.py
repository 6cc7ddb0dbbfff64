"""launch_ros's Parameter substitution (`$(param name [default])`): a parameter SetParameter set before it.

As launch_ros (jazzy): the `(name, value)` pairs SetParameter appended to the `global_params` launch
configuration are searched, the first of the name wins, its value as text (`str(value)`); not found → the
default, or a substitution failure naming the parameter. In Python it is `launch_ros.substitutions.Parameter`
(the name `launch_ros.parameter_descriptions.Parameter` is the node parameter, see ros_names).
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

from diffctl.errors import LaunchError
from diffctl.launch_legacy.context import GLOBAL_PARAMS
from diffctl.launch_legacy.substitutions import SomeSubstitutions, Substitution, describe, normalize, perform

if TYPE_CHECKING:
    from diffctl.launch_legacy.context import Scope


class ParameterSubstitution(Substitution):
    def __init__(self, name: SomeSubstitutions, *, default: Any = None) -> None:
        self.name = normalize(name)
        if default is None:
            self.default = None
        else:
            items = default if isinstance(default, Iterable) and not isinstance(default, str) else (default,)
            self.default = normalize([i if isinstance(i, (str, Substitution)) else str(i) for i in items])

    def describe(self) -> str:
        return f"Parameter(name={describe(self.name)})"

    def perform(self, scope: Scope) -> str:
        name = perform(self.name, scope)
        for entry in scope.configurations.get(GLOBAL_PARAMS) or ():
            if isinstance(entry, tuple) and entry[0] == name:
                return str(entry[1])
        if self.default is None:
            raise LaunchError(f"parameter '{name}' not found", hint="set it before with SetParameter / <set_parameter>")
        return perform(self.default, scope)


def from_frontend(args: list[tuple[Substitution, ...]]) -> Substitution:
    """`$(param name)` / `$(param name default)`."""
    if not 1 <= len(args) <= 2:
        raise LaunchError(f"$(param) takes 1 or 2 arguments, got {len(args)}")
    return ParameterSubstitution(args[0], default=args[1] if len(args) == 2 else None)


class FindPackage(Substitution):
    """launch_ros's FindPackage: the base of the package substitutions; a subclass gives `find(package_name)`."""

    def __init__(self, package: SomeSubstitutions) -> None:
        self.package = normalize(package)

    def find(self, package_name: str) -> str:
        raise NotImplementedError

    def describe(self) -> str:
        return f"{type(self).__name__}(pkg={describe(self.package)})"

    def perform(self, scope: Scope) -> str:
        return self.find(perform(self.package, scope))
