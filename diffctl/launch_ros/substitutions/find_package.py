"""Substitutions that find a package: its install prefix (`$(find-pkg-prefix pkg)`) or share directory
(`$(find-pkg-share pkg)`), resolved through diffctl's package index (the user's workspace, install trees,
then diffctl's own packages), as ament_index_python resolves them in ROS."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from diffctl.launch.frontend import expose_substitution
from diffctl.launch.launch_context import LaunchContext
from diffctl.launch.some_substitutions_type import SomeSubstitutionsType
from diffctl.launch.substitution import Substitution
from diffctl.launch.utilities import normalize_to_list_of_substitutions, perform_substitutions


class FindPackage(Substitution):
    """The base of the package-finding substitutions: a subclass says what `find(package_name)` gives."""

    def __init__(self, package: SomeSubstitutionsType) -> None:
        super().__init__()
        self.__package = normalize_to_list_of_substitutions(package)

    @classmethod
    def parse(cls, data: Sequence[SomeSubstitutionsType]) -> tuple[type, dict[str, Any]]:
        if not data or len(data) != 1:
            raise AttributeError("find package substitutions expect 1 argument")
        return cls, {"package": data[0]}

    @property
    def package(self) -> list[Substitution]:
        return self.__package

    def find(self, package_name: str) -> str:
        """The directory this substitution stands for, of `package_name`."""
        raise NotImplementedError()

    def describe(self) -> str:
        return f"{type(self).__name__}(pkg={' + '.join(s.describe() for s in self.package)})"

    def perform(self, context: LaunchContext) -> str:
        return self.find(perform_substitutions(context, self.package))


@expose_substitution("find-pkg-prefix")
class FindPackagePrefix(FindPackage):
    """The install prefix of a package (`<prefix>/share/<package>` is its share directory); raises
    PackageNotFoundError when no package has that name."""

    def find(self, package_name: str) -> str:
        from diffctl.workspace.package_index import get_package_prefix

        return get_package_prefix(package_name)


@expose_substitution("find-pkg-share")
class FindPackageShare(FindPackage):
    """The share directory of a package; raises PackageNotFoundError when no package has that name."""

    def find(self, package_name: str) -> str:
        from diffctl.workspace.package_index import get_package_share_directory

        return get_package_share_directory(package_name)
