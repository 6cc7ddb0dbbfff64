"""`$(exec-in-pkg exe pkg)`: the program `exe` of package `pkg`.

A package of the user's workspace or of an install tree has it at `<prefix>/lib/<pkg>/<exe>`, as in ROS.
diffctl's own components (robot_state_publisher, controller_manager's spawner, the demo nodes, …) are no
files but commands (`python -m diffctl …`): `argv()` gives the whole command line, which is what Node
starts; performing the substitution, which must give one word, then fails with a message saying so.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from diffctl.launch.frontend import expose_substitution
from diffctl.launch.launch_context import LaunchContext
from diffctl.launch.some_substitutions_type import SomeSubstitutionsType
from diffctl.launch.substitution import Substitution
from diffctl.launch.substitutions import SubstitutionFailure
from diffctl.launch.utilities import normalize_to_list_of_substitutions, perform_substitutions

from .find_package import FindPackagePrefix


@expose_substitution("exec-in-pkg")
class ExecutableInPackage(FindPackagePrefix):
    """The path of an executable of a ROS package (see the module docstring for diffctl's components)."""

    def __init__(self, executable: SomeSubstitutionsType, package: SomeSubstitutionsType) -> None:
        super().__init__(package)
        self.__executable = normalize_to_list_of_substitutions(executable)

    @classmethod
    def parse(cls, data: Sequence[SomeSubstitutionsType]) -> tuple[type, dict[str, Any]]:
        if not data or len(data) != 2:
            raise AttributeError("exec-in-package substitution expects 2 arguments")
        return cls, {"executable": data[0], "package": data[1]}

    @property
    def executable(self) -> list[Substitution]:
        return self.__executable

    def describe(self) -> str:
        pkg = " + ".join(s.describe() for s in self.package)
        exe = " + ".join(s.describe() for s in self.executable)
        return f"ExecInPkg(pkg={pkg}, exec={exe})"

    def argv(self, context: LaunchContext) -> list[str]:
        """The command line that starts the executable (one word for a program file; a diffctl component's
        `python -m diffctl …`). A missing package or executable raises diffctl's LaunchError naming what
        exists."""
        from diffctl.workspace.package_index import executable_argv

        package = perform_substitutions(context, self.package)
        return executable_argv(package, perform_substitutions(context, self.executable))

    def perform(self, context: LaunchContext) -> str:
        argv = self.argv(context)
        if len(argv) != 1:
            package = perform_substitutions(context, self.package)
            executable = perform_substitutions(context, self.executable)
            raise SubstitutionFailure(
                f"executable '{executable}' of package '{package}' is diffctl's own component, started as "
                f"'{' '.join(argv)}', not a file: start it with Node(package='{package}', executable='{executable}')"
            )
        return argv[0]
