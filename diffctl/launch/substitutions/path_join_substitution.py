"""`PathJoinSubstitution` and `PathSubstitution`: a path built from pieces, some of them substitutions."""

from __future__ import annotations

import os
from collections.abc import Iterable
from typing import TYPE_CHECKING

from .._private.operands import joined
from ..some_substitutions_type import SomeSubstitutionsType
from ..substitution import Substitution
from ..utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions

if TYPE_CHECKING:
    from ..launch_context import LaunchContext


class PathJoinSubstitution(Substitution):
    """The performed components joined by `os.path.join` (an absolute one restarts the path, as there).

    A component is anything a substitution list may be made of (`[LaunchConfiguration('model'), '.xacro']`
    is one component), and `/` appends one, as `pathlib.Path` does.
    """

    def __init__(self, substitutions: Iterable[SomeSubstitutionsType]) -> None:
        self._components = [normalize_to_list_of_substitutions(part) for part in substitutions]

    @property
    def substitutions(self) -> Iterable[Substitution]:
        return [sub for part in self._components for sub in part]

    def __truediv__(self, additional_path: SomeSubstitutionsType) -> PathJoinSubstitution:
        return PathJoinSubstitution([self, additional_path])

    def describe(self) -> str:
        return f"PathJoin('{' + '.join(joined(part) for part in self._components)}')"

    def perform(self, context: LaunchContext) -> str:
        # Each piece performs itself, as Jazzy's does: all-text paths join without a context (`perform(None)`).
        return os.path.join(*[''.join(sub.perform(context) for sub in part) for part in self._components])


class PathSubstitution(PathJoinSubstitution):
    """One path to extend with `/`: `PathSubstitution(FindPackageShare('pkg')) / 'urdf' / 'robot.xacro'`."""

    def __init__(self, path: SomeSubstitutionsType) -> None:
        super().__init__([path])
