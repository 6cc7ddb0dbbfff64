"""Package attributes imported on first use (PEP 562), so that `import launch` stays cheap.

A package says which submodule holds each of its names; `from launch.actions import ExecuteProcess`
then imports only the modules that name needs, while `dir()` and `__all__` list every public name.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable, Iterable, Mapping


def lazy_exports(
    package: str, namespace: dict[str, object], homes: Mapping[str, Iterable[str]]
) -> tuple[Callable[[str], object], Callable[[], list[str]], list[str]]:
    """`__getattr__`, `__dir__` and `__all__` for `package`.

    `homes` maps a submodule (relative: '.timer_action') to the names it holds and the package re-exports.
    A name with a trailing '/' is a subpackage exported as itself ('actions/').
    """
    where: dict[str, str] = {}
    for module, names in homes.items():
        for name in names:
            where[name.rstrip('/')] = name if name.endswith('/') else module

    def load(attr: str) -> object:
        home = where.get(attr)
        if home is None:
            # a submodule not re-exported by name, e.g. `launch.actions.timer_action`
            try:
                value = importlib.import_module(f'{package}.{attr}')
            except ModuleNotFoundError as missing:
                if missing.name != f'{package}.{attr}':
                    raise
                raise AttributeError(f'module {package!r} has no attribute {attr!r}') from None
        elif home.endswith('/'):
            value = importlib.import_module(f'.{attr}', package)
        else:
            value = getattr(importlib.import_module(home, package), attr)
        namespace[attr] = value
        return value

    def listing() -> list[str]:
        return sorted(set(namespace) | set(where))

    return load, listing, sorted(where)
