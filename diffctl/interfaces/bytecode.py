"""Generated code (interface modules, CDR codecs) compiled once per machine, not once per process.

Compiling generated source is most of what a generated class or codec costs (1-3 ms each, dozens at every
node's start), so code objects are kept as marshalled bytecode in the user's cache directory, keyed by the
source, its file name and the interpreter's bytecode version.
"""

from __future__ import annotations

import functools
import hashlib
import importlib.util
import marshal
import os
import tempfile
import types
from pathlib import Path


@functools.cache
def _cache_dir() -> Path:
    base = Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "diffctl"
    return base / f"bytecode-{importlib.util.MAGIC_NUMBER.hex()}"


def compiled(source: str, filename: str) -> types.CodeType:
    """The code object of generated `source`, from the cache when it holds it."""
    key = hashlib.sha256(f"{filename}\0{source}".encode()).hexdigest()[:32]
    path = _cache_dir() / f"{key}.marshal"
    try:
        return marshal.loads(path.read_bytes())
    except (OSError, ValueError, EOFError, TypeError):
        pass
    code = compile(source, filename, "exec")
    tmp = None
    try:  # written whole or not at all: processes started together race to write the same entry
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=".tmp-")
        with os.fdopen(fd, "wb") as f:
            f.write(marshal.dumps(code))
        os.replace(tmp, path)
        tmp = None
    except OSError:
        pass  # a read-only home: compiled every time, as without the cache
    finally:
        if tmp is not None:
            Path(tmp).unlink(missing_ok=True)
    return code
