"""`PythonExpression` (`$(eval expr [modules])`): the value of a Python expression, as text."""

from __future__ import annotations

import collections.abc
from collections.abc import Sequence
from typing import TYPE_CHECKING

from ..frontend.expose import expose_substitution
from ..substitution import Substitution
from ..utilities.ensure_argument_type_impl import ensure_argument_type
from ..utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from ..utilities.perform_substitutions_impl import perform_substitutions

if TYPE_CHECKING:
    from ..launch_context import LaunchContext
    from ..some_substitutions_type import SomeSubstitutionsType


@expose_substitution('eval')
class PythonExpression(Substitution):
    """`str(eval(expression))`, with `python_modules` imported and available by name.

    The names of `math` are also available unqualified (`ceil(1.3)`) when `math` is among the modules,
    as it is by default. In markup the modules are one comma-separated argument.
    """

    def __init__(self, expression: SomeSubstitutionsType, python_modules: SomeSubstitutionsType = ('math',)) -> None:
        super().__init__()
        accepted = (str, Substitution, collections.abc.Iterable)
        ensure_argument_type(expression, accepted, 'expression', 'PythonExpression')
        ensure_argument_type(python_modules, accepted, 'python_modules', 'PythonExpression')
        self.__expression = normalize_to_list_of_substitutions(expression)
        self.__python_modules = normalize_to_list_of_substitutions(python_modules)

    @classmethod
    def parse(cls, data: Sequence[SomeSubstitutionsType]):
        if not 1 <= len(data) <= 2:
            raise TypeError('eval substitution expects 1 or 2 arguments')
        kwargs = {'expression': data[0]}
        if len(data) == 2:
            # one comma-separated list of module names, given as text
            modules = list(data[1])
            kwargs['python_modules'] = [n.strip() for n in modules[0].perform(None).split(',')] if modules else []
        return cls, kwargs

    @property
    def expression(self) -> list[Substitution]:
        return self.__expression

    @property
    def python_modules(self) -> list[Substitution]:
        return self.__python_modules

    def describe(self) -> str:
        return 'PythonExpr({}, [{}])'.format(
            ' + '.join(sub.describe() for sub in self.expression),
            ', '.join(sub.describe() for sub in self.python_modules))

    def perform(self, context: LaunchContext) -> str:
        import importlib

        names: dict = {}
        for module_name in (context.perform_substitution(sub) for sub in self.python_modules):
            module = importlib.import_module(module_name)
            if module.__name__ == 'math':
                names.update(vars(module))
            names[module.__name__] = module
        return str(eval(perform_substitutions(context, self.expression), {}, names))
