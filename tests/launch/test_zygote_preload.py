"""The fork server's preload: the methods dataclasses writes are compiled once per machine (zygote.py's
dataclass_methods_cached), and a class built from the cache is the class dataclasses builds."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap

PROGRAM = textwrap.dedent(
    """
    import contextlib, dataclasses, hashlib, sys
    from diffctl.supervision import zygote

    cached = zygote.dataclass_methods_cached if sys.argv[1] == "cached" else contextlib.nullcontext
    with cached():
        import diffctl.description.model as model

        @dataclasses.dataclass(frozen=True, order=True)
        class Local:
            a: int
            b: "list[str]" = dataclasses.field(default_factory=list)

    seen = []
    for cls in [Local, *(c for c in vars(model).values() if isinstance(c, type) and dataclasses.is_dataclass(c))]:
        for name in ("__init__", "__repr__", "__eq__", "__lt__", "__setattr__", "__delattr__", "__hash__"):
            code = getattr(cls.__dict__.get(name), "__code__", None)
            if code is not None:
                seen.append((cls.__qualname__, name, code.co_code, code.co_consts, code.co_names, code.co_flags,
                             code.co_filename, repr(cls.__dict__[name].__annotations__)))
    local = Local(1)
    try:
        local.a = 2
    except dataclasses.FrozenInstanceError as e:
        seen.append(str(e))
    seen += [repr(local), Local(1) == Local(1, []), Local(0) < Local(1)]
    print(len(seen), hashlib.sha256(repr(seen).encode()).hexdigest())
    """
)


def test_dataclass_methods_from_the_cache_are_those_dataclasses_compiles(tmp_path) -> None:
    env = dict(os.environ, XDG_CACHE_HOME=str(tmp_path))

    def run(mode: str) -> str:
        done = subprocess.run(
            [sys.executable, "-c", PROGRAM, mode], capture_output=True, text=True, env=env, timeout=120
        )
        assert done.returncode == 0, done.stderr
        return done.stdout

    plain = run("plain")
    assert not list(tmp_path.rglob("dataclass-methods-by-text.marshal"))
    first = run("cached")  # compiles, and keeps them
    (cache,) = tmp_path.rglob("dataclass-methods-by-text.marshal")
    written = cache.stat().st_mtime_ns
    second = run("cached")  # every one from the cache: nothing to write
    assert plain == first == second
    assert int(plain.split()[0]) > 100
    assert cache.stat().st_mtime_ns == written
