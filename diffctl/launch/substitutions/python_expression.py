"""`PythonExpression`, `$(eval expr [modules])`: a Python expression's value, as text."""

from __future__ import annotations

import collections.abc
import importlib
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

from .._private.operands import joined, tag_kwargs
from ..frontend.expose import expose_substitution
from ..substitution import Substitution
from ..utilities.ensure_argument_type_impl import ensure_argument_type
from ..utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from ..utilities.perform_substitutions_impl import perform_substitutions

if TYPE_CHECKING:
    from ..launch_context import LaunchContext
    from ..some_substitutions_type import SomeSubstitutionsType


def _module_list(argument: Any) -> list[str]:
    """`$(eval …)`'s second argument: module names separated by commas, in its first (literal) piece."""
    pieces = list(argument)
    if not pieces:
        return []
    return [name.strip() for name in pieces[0].perform(None).split(',')]


@expose_substitution('eval')
class PythonExpression(Substitution):
    """`str(eval(expression))` with each of `python_modules` imported under its name.

    `math` (the default) is special: its functions are also usable unqualified, `ceil(x)` as `math.ceil(x)`.
    """

    def __init__(
        self, expression: SomeSubstitutionsType, python_modules: SomeSubstitutionsType = ['math'],  # noqa: B006
    ) -> None:
        super().__init__()
        for value, argument in ((expression, 'expression'), (python_modules, 'python_modules')):
            ensure_argument_type(value, (str, Substitution, collections.abc.Iterable), argument, 'PythonExpression')
        self._source = normalize_to_list_of_substitutions(expression)
        self._imports = normalize_to_list_of_substitutions(python_modules)

    @property
    def expression(self) -> list[Substitution]:
        return self._source

    @property
    def python_modules(self) -> list[Substitution]:
        return self._imports

    @classmethod
    def parse(cls, data: Sequence[SomeSubstitutionsType]):
        kwargs = tag_kwargs(
            data, ('expression', 'python_modules'), 'eval substitution expects 1 or 2 arguments', required=1)
        if 'python_modules' in kwargs:
            kwargs['python_modules'] = _module_list(kwargs['python_modules'])
        return cls, kwargs

    def describe(self) -> str:
        return f"PythonExpr({joined(self._source)}, [{joined(self._imports, ', ')}])"

    def _namespace(self, context: LaunchContext) -> dict[str, Any]:
        namespace: dict[str, Any] = {}
        for piece in self._imports:
            module = importlib.import_module(context.perform_substitution(piece))
            if module.__name__ == 'math':
                namespace.update(vars(module))
            namespace[module.__name__] = module
        return namespace

    def perform(self, context: LaunchContext) -> str:
        source = perform_substitutions(context, self._source)
        return str(eval(source, {}, self._namespace(context)))
