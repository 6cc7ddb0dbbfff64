"""`$(param name [default])`: the value a SetParameter earlier in the scope gave `name`."""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import Any

from diffctl.launch.frontend import expose_substitution
from diffctl.launch.launch_context import LaunchContext
from diffctl.launch.some_substitutions_type import SomeSubstitutionsType
from diffctl.launch.substitution import Substitution
from diffctl.launch.substitutions import SubstitutionFailure
from diffctl.launch.utilities import normalize_to_list_of_substitutions, perform_substitutions


@expose_substitution("param")
class Parameter(Substitution):
    """The text of a parameter set by SetParameter (the first of the name); the default, else
    SubstitutionFailure, when none was set."""

    def __init__(self, name: SomeSubstitutionsType, *, default: Any | Iterable[Any] | None = None) -> None:
        super().__init__()
        self.__name = normalize_to_list_of_substitutions(name)
        self.__default: list[Substitution] | None = None
        if default is not None:
            items = default if isinstance(default, Iterable) else (default,)
            self.__default = normalize_to_list_of_substitutions(
                [item if isinstance(item, (str, Substitution)) else str(item) for item in items]
            )

    @classmethod
    def parse(cls, data: Sequence[SomeSubstitutionsType]) -> tuple[type, dict[str, Any]]:
        if not 1 <= len(data) <= 2:
            raise TypeError("param substitution expects 1 or 2 arguments")
        kwargs: dict[str, Any] = {"name": data[0]}
        if len(data) == 2:
            kwargs["default"] = data[1]
        return cls, kwargs

    @property
    def name(self) -> list[Substitution]:
        return self.__name

    def describe(self) -> str:
        return f"{type(self).__name__}(name={' + '.join(s.describe() for s in self.name)})"

    def perform(self, context: LaunchContext) -> str:
        name = perform_substitutions(context, self.name)
        for entry in context.launch_configurations.get("global_params", []):
            if isinstance(entry, tuple) and entry[0] == name:
                return str(entry[1])
        if self.__default is None:
            raise SubstitutionFailure(f"parameter '{name}' not found")
        return perform_substitutions(context, self.__default)
