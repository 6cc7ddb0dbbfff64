"""What `diffctl test` runs: launch test files and plain pytest files, given or found in a workspace.

A launch test file defines `generate_test_description()` (`test/test_*.launch.py`, `*_launch_test.py`, any
name); other `test_*.py` / `*_test.py` files are pytest's. Without paths, inside a workspace, each package's
`test/` folder is searched, as `colcon test` would (`--packages-select` keeps some).
"""

from __future__ import annotations

import fnmatch
import re
from dataclasses import dataclass
from pathlib import Path

from diffctl.errors import ConfigError, suggest

TEST_PATTERNS = ("test_*.py", "*_test.py")
_GENERATE = re.compile(r"^def generate_test_description\(", re.MULTILINE)


@dataclass(frozen=True)
class TestFile:
    path: Path
    kind: str  # "launch" | "pytest"
    package: str | None = None
    root: Path | None = None  # the package folder (pytest runs there, as colcon test)

    @property
    def label(self) -> str:
        return f"{self.package}/{self.path.name}" if self.package else str(self.path)


def is_launch_test(path: Path) -> bool:
    try:
        return bool(_GENERATE.search(path.read_text(errors="replace")))
    except OSError:
        return False


def _is_test_name(name: str) -> bool:
    return any(fnmatch.fnmatch(name, p) for p in TEST_PATTERNS)


def classify(path: Path, package: str | None = None, root: Path | None = None) -> TestFile:
    return TestFile(path, "launch" if is_launch_test(path) else "pytest", package, root)


def in_folder(folder: Path, package: str | None = None, root: Path | None = None) -> list[TestFile]:
    out = []
    for path in sorted(folder.rglob("*.py")):
        if any(part.startswith(".") or part == "__pycache__" for part in path.relative_to(folder).parts):
            continue
        if _is_test_name(path.name) or is_launch_test(path):
            out.append(classify(path, package, root))
    return out


def from_paths(paths: list[Path]) -> list[TestFile]:
    out: list[TestFile] = []
    for path in paths:
        if not path.exists():
            raise ConfigError(f"{path}: no such file or folder", hint="give launch test files or folders of them")
        out += in_folder(path) if path.is_dir() else [classify(path)]
    return out


def from_workspace(workspace: Path, packages_select: list[str] | None = None) -> list[TestFile]:
    from diffctl.workspace.resolve import scan_workspace

    manifests = scan_workspace(workspace).manifests
    names = sorted(manifests)
    for name in packages_select or []:
        if name not in manifests:
            raise ConfigError(
                f"--packages-select: no package {name!r} in {workspace}{suggest(name, names)}",
                hint="packages: " + (", ".join(names) or "none"),
            )
    out: list[TestFile] = []
    for name in names:
        if packages_select and name not in packages_select:
            continue
        root = manifests[name].path.parent
        test_dir = root / "test"
        if test_dir.is_dir():
            out += in_folder(test_dir, name, root)
    return out
