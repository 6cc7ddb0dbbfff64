"""Fixtures for workspace resolution: an isolated cache, environment and current directory per test,
and a helper that writes a package tree."""

from __future__ import annotations

import os
from collections.abc import Iterator
from pathlib import Path

import pytest

PACKAGE_XML = """<?xml version="1.0"?>
<package format="3">
  <name>{name}</name>
  <version>0.1.0</version>
  <description>test package {name}</description>
  <maintainer email="a@b.c">a</maintainer>
  <license>Apache-2.0</license>
  <export><build_type>{build_type}</build_type></export>
</package>
"""


def write_tree(root: Path, files: dict[str, str]) -> Path:
    """Create `files` (relative path → text) under `root`; return `root`."""
    for rel, text in files.items():
        path = root / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
    return root


def package_xml(name: str, build_type: str = "ament_cmake") -> str:
    return PACKAGE_XML.format(name=name, build_type=build_type)


def snapshot(root: Path) -> dict[str, tuple[float, int]]:
    """Every path under `root` with its mtime and size: proof that nothing was written there."""
    out = {}
    for dirpath, dirnames, filenames in os.walk(root):
        for name in dirnames + filenames:
            p = os.path.join(dirpath, name)
            st = os.lstat(p)
            out[os.path.relpath(p, root)] = (st.st_mtime, st.st_size)
    return out


@pytest.fixture(autouse=True)
def isolated(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Iterator[Path]:
    """A private cache, no install trees or named workspace from the caller's shell, cwd outside any workspace."""
    for var in ("AMENT_PREFIX_PATH", "COLCON_PREFIX_PATH", "DIFFCTL_WORKSPACE", "DIFFCTL_PROJECT_DIR"):
        monkeypatch.delenv(var, raising=False)
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    outside = tmp_path / "elsewhere"
    outside.mkdir()
    monkeypatch.chdir(outside)
    yield tmp_path
