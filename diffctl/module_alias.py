"""ROS-named packages that are diffctl's own packages under another name (`launch` → `diffctl.launch`).

`alias('launch', 'diffctl.launch')`, called from the overlay's `launch/__init__.py`, makes `launch` the very
module object `diffctl.launch`, and a meta-path finder makes every `launch.X.Y` the module
`diffctl.launch.X.Y`: one module under two names, so classes are identical whichever name imported them,
and private names are reachable. A sourced ROS 2 earlier on `sys.path` still wins: the overlay's
`__init__` (and so the alias) only runs when Python picked the overlay's `launch`, and the finder only
answers for names whose top-level module is the aliased diffctl package.
"""

from __future__ import annotations

import importlib
import importlib.machinery
import sys
from types import ModuleType

_aliases: dict[str, str] = {}  # ROS name -> diffctl package


class _AliasLoader:
    """Hands back the already-imported diffctl module instead of making a new one."""

    def __init__(self, module: ModuleType) -> None:
        self.module = module
        self.own_spec = module.__spec__

    def create_module(self, spec: importlib.machinery.ModuleSpec) -> ModuleType:
        return self.module

    def exec_module(self, module: ModuleType) -> None:
        # executed once already, under its diffctl name; the import system just replaced its __spec__
        # with the alias's, which would make its relative imports disagree with its __package__
        module.__spec__ = self.own_spec

    def get_code(self, fullname: str):
        # `python -m launch_testing.launch_test`: runpy runs the module's code afresh as __main__
        return self.own_spec.loader.get_code(self.own_spec.name)


class _AliasFinder:
    """Finds `launch.X.Y` as `diffctl.launch.X.Y` while `launch` is the aliased package."""

    def find_spec(self, fullname: str, path=None, target=None):
        top, dot, rest = fullname.partition('.')
        package = _aliases.get(top)
        if package is None or not dot:
            return None
        if sys.modules.get(top) is not sys.modules.get(package):
            return None  # `launch` is someone else's (a sourced ROS 2)
        name = f'{package}.{rest}'
        try:
            module = importlib.import_module(name)
        except ModuleNotFoundError as e:
            if e.name is not None and (name == e.name or name.startswith(e.name + '.')):
                return None  # no such module: the import fails as usual
            raise
        return importlib.machinery.ModuleSpec(
            fullname, _AliasLoader(module), origin=getattr(module, '__file__', None),
            is_package=hasattr(module, '__path__'))


_finder = _AliasFinder()


def alias(name: str, package: str) -> ModuleType:
    """Make the top-level module `name` be `package` (imported now), and its submodules `package`'s."""
    module = importlib.import_module(package)
    _aliases[name] = package
    sys.modules[name] = module
    if _finder not in sys.meta_path:
        sys.meta_path.insert(0, _finder)
    return module
