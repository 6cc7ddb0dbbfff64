"""`gz` (and the older `ign`) on PATH for processes diffctl starts, whatever the shell's PATH holds.

Launch files run `ExecuteProcess(cmd=['gz', 'sim', …])`. The venv's console script serves an activated venv;
for `.venv/bin/diffctl launch …` from a plain shell, a two-line wrapper in diffctl's cache (running this
interpreter) is put first on the children's PATH, ahead of a real Gazebo's `gz`, which diffctl replaces.
"""

from __future__ import annotations

import os
import sys
from collections.abc import MutableMapping
from pathlib import Path

COMMANDS = ("gz", "ign")


def bin_dir() -> Path:
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "diffctl" / "bin"


def _wrapper() -> str:
    return f"#!{sys.executable}\nfrom diffctl.gz.cli import main\nmain()\n"


def write_wrapper(path: Path, text: str) -> None:
    """Write an executable script at `path` unless it already holds `text`; atomic, so a launch starting
    meanwhile never runs half a script."""
    try:
        if path.read_text() == text:
            return
    except OSError:
        pass
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.name}.{os.getpid()}")
    tmp.write_text(text)
    tmp.chmod(0o755)
    tmp.replace(path)


def put_first_on_path(env: MutableMapping[str, str], folder: Path) -> None:
    parts = [p for p in env.get("PATH", "").split(os.pathsep) if p and p != str(folder)]
    env["PATH"] = os.pathsep.join([str(folder), *parts])


def put_gz_on_path(env: MutableMapping[str, str]) -> Path:
    """Write the wrappers (when missing or stale) and put their folder first on `env`'s PATH."""
    folder = bin_dir()
    text = _wrapper()
    for name in COMMANDS:
        write_wrapper(folder / name, text)
    put_first_on_path(env, folder)
    return folder
