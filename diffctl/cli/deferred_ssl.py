"""asyncio without OpenSSL loaded until something uses it: the launcher's loop runs processes, not TLS.

Importing asyncio imports `ssl` (asyncio.sslproto reads ssl's error classes at import), and with it libssl: 1.2 MB
of the launcher's resident memory here, more where libcrypto is not mapped already. `defer_ssl()` puts `ssl` and
`asyncio.sslproto` in `sys.modules` as modules whose code runs on the first use of one of their names, then
imports asyncio. `importlib.util.LazyLoader` cannot do it: the import system reads a module's `__spec__` at every
`import ssl`, which loads a LazyLoader module at asyncio's second mention of it. A launch file that imports ssl,
or a TLS connection made on the loop, gets the whole module on first use.
"""

from __future__ import annotations

import importlib.machinery
import importlib.util
import sys
import threading
import types
from typing import Any

_loading = threading.RLock()


class _RunsOnFirstUse(types.ModuleType):
    """A module whose code has not run yet: it runs when a name the module does not have yet is looked up
    (only the import system's own attributes, `__spec__` and the like, are there before)."""

    def __getattr__(self, name: str) -> Any:
        with _loading:
            if type(self) is _RunsOnFirstUse:  # not loaded by another thread meanwhile
                self.__class__ = types.ModuleType
                spec = self.__spec__
                try:
                    spec.loader.exec_module(self)
                except BaseException:
                    del sys.modules[spec.name]  # as a failed import leaves it: the next import tries again
                    raise
        return getattr(self, name)


def _defer(spec: importlib.machinery.ModuleSpec) -> types.ModuleType:
    module = importlib.util.module_from_spec(spec)
    module.__class__ = _RunsOnFirstUse
    sys.modules[spec.name] = module
    return module


def defer_ssl() -> None:
    """Import asyncio with `ssl` and `asyncio.sslproto` deferred to their first use (nothing is deferred when
    either, or asyncio, is imported already, or when Python has no `_ssl`)."""
    if any(name in sys.modules for name in ("ssl", "asyncio", "asyncio.sslproto")):
        return
    ssl_spec = importlib.util.find_spec("ssl")
    asyncio_spec = importlib.util.find_spec("asyncio")
    if ssl_spec is None or asyncio_spec is None or importlib.util.find_spec("_ssl") is None:
        return
    # a submodule's spec found without importing its package (importlib.util.find_spec would import asyncio)
    sslproto_spec = importlib.machinery.PathFinder.find_spec(
        "asyncio.sslproto", list(asyncio_spec.submodule_search_locations or [])
    )
    if sslproto_spec is None:
        return
    _defer(ssl_spec)
    sslproto = _defer(sslproto_spec)
    import asyncio

    asyncio.sslproto = sslproto  # what loading it as a submodule would have set
