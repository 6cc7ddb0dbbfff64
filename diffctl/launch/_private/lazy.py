"""Package attributes imported on first use (PEP 562), so that `import launch` stays cheap.

A package says which submodule holds each of its names; `from launch.actions import ExecuteProcess`
then imports only the modules that name needs, while `dir()` and `__all__` list every public name.

A name is looked up in its module each time, never kept in the package: whoever drops modules from
sys.modules (pytester between in-process sessions) gets the classes of the modules imported again, not
those of the dropped ones alongside them.
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
            # a submodule not re-exported by name, e.g. `launch.actions.timer_action` (importing it binds it
            # in the package, as any import does)
            try:
                return importlib.import_module(f'{package}.{attr}')
            except ModuleNotFoundError as missing:
                if missing.name != f'{package}.{attr}':
                    raise
                raise AttributeError(f'module {package!r} has no attribute {attr!r}') from None
        if home.endswith('/'):
            return importlib.import_module(f'.{attr}', package)
        return getattr(importlib.import_module(home, package), attr)

    def listing() -> list[str]:
        return sorted(set(namespace) | set(where))

    return load, listing, sorted(where)
