"""Package attributes imported on first use (PEP 562), so that `import launch` stays cheap.

A package lists `name -> submodule` pairs; `from launch.actions import ExecuteProcess` then imports only the
modules that name needs, and `dir()` / `__all__` still show every public name.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable, Mapping


def lazy_exports(
    package: str, namespace: dict[str, object], names: Mapping[str, str]
) -> tuple[Callable[[str], object], Callable[[], list[str]]]:
    """`__getattr__` and `__dir__` for `package`: `names` maps an attribute to the submodule holding it.

    A value starting with '.' names a submodule relative to the package; the attribute of the same name is
    read from it unless the value ends with ':' (the attribute is the submodule itself).
    """

    def __getattr__(attr: str) -> object:
        where = names.get(attr)
        if where is None:
            # a submodule that is not re-exported by name (e.g. `launch.actions.timer_action`)
            try:
                module = importlib.import_module(f"{package}.{attr}")
            except ModuleNotFoundError as e:
                if e.name != f"{package}.{attr}":
                    raise
                raise AttributeError(f"module {package!r} has no attribute {attr!r}") from None
            namespace[attr] = module
            return module
        if where.endswith(":"):
            value = importlib.import_module(where[:-1], package)
        else:
            value = getattr(importlib.import_module(where, package), attr)
        namespace[attr] = value
        return value

    def __dir__() -> list[str]:
        return sorted(set(namespace) | set(names))

    return __getattr__, __dir__
