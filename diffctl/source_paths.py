"""The file a user edits for a path diffctl reached through its own cache.

A workspace package's share directory is a symlink tree in `~/.cache/diffctl/workspaces/…/share/<pkg>/`
(colcon --symlink-install style, diffctl/workspace/share_tree.py): launch files, URDF/xacro, YAML and worlds are
opened through it. An error naming that path would send the user to edit a link; every error location goes
through `user_source`, which names the source file under src/ instead.
"""

from __future__ import annotations

import os


def _cache_roots() -> tuple[str, ...]:
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    root = os.path.join(base, "diffctl", "workspaces") + os.sep
    real = os.path.join(os.path.realpath(os.path.join(base, "diffctl", "workspaces")), "")
    return (root,) if real == root else (root, real)


def user_source(path: str) -> str:
    """`path` itself, or — for a file in diffctl's workspace cache — the source file it links to."""
    if not path or path.startswith("<"):
        return path
    roots = _cache_roots()
    if not path.startswith(roots):
        return path
    real = os.path.realpath(path)
    return path if real.startswith(roots) else real  # generated files (wrappers, markers) have no source
