"""What `diffctl test` runs: launch test files and plain pytest files, given or found in a workspace.

The framework is chosen by what a file uses, read from its syntax tree without running it: launch_pytest
(an import of it, a `@pytest.mark.launch` test) makes it pytest's, whatever its function names;
else a module-level `generate_test_description()` makes it a launch_testing file (`launch_test`); anything
else named `test_*.py` / `*_test.py` is pytest's. Without paths, inside a workspace, each package's `test/`
folder is searched, as `colcon test` would (`--packages-select` keeps some).
"""

from __future__ import annotations

import ast
import fnmatch
from dataclasses import dataclass
from pathlib import Path

from diffctl.errors import ConfigError, suggest

TEST_PATTERNS = ("test_*.py", "*_test.py")
ENTRYPOINT = "generate_test_description"


@dataclass(frozen=True)
class TestFile:
    path: Path
    kind: str  # "launch" (launch_testing) | "launch_pytest" | "pytest"
    package: str | None = None
    root: Path | None = None  # the package folder (pytest runs there, as colcon test)

    @property
    def label(self) -> str:
        return f"{self.package}/{self.path.name}" if self.package else str(self.path)


def _uses_launch_pytest(tree: ast.Module) -> bool:
    for node in ast.walk(tree):
        if isinstance(node, ast.Import) and any(a.name.split(".")[0] == "launch_pytest" for a in node.names):
            return True
        if isinstance(node, ast.ImportFrom) and (node.module or "").split(".")[0] == "launch_pytest":
            return True
        # pytest.mark.launch(...) / mark.launch: launch_pytest's marker, whatever imported it
        if isinstance(node, ast.Attribute) and node.attr == "launch" and isinstance(node.value, ast.Attribute) \
                and node.value.attr == "mark":
            return True
    return False


def framework(path: Path) -> str | None:
    """'launch' (launch_testing: run by launch_test), 'launch_pytest', 'pytest', or None when the file is no
    test at all. A file that does not parse goes where its text says, to report its error there."""
    try:
        text = path.read_text(errors="replace")
    except OSError:
        return None
    try:
        tree = ast.parse(text, filename=str(path))
    except (SyntaxError, ValueError):
        if "launch_pytest" in text:
            return "launch_pytest"
        if ENTRYPOINT in text:
            return "launch"
        return "pytest" if _is_test_name(path.name) else None
    if _uses_launch_pytest(tree):
        return "launch_pytest"
    if any(isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef)) and n.name == ENTRYPOINT for n in tree.body):
        return "launch"
    return "pytest" if _is_test_name(path.name) else None


def is_launch_test(path: Path) -> bool:
    return framework(path) == "launch"


def _is_test_name(name: str) -> bool:
    return any(fnmatch.fnmatch(name, p) for p in TEST_PATTERNS)


def classify(path: Path, package: str | None = None, root: Path | None = None) -> TestFile:
    return TestFile(path, framework(path) or "pytest", package, root)


def in_folder(folder: Path, package: str | None = None, root: Path | None = None) -> list[TestFile]:
    out = []
    for path in sorted(folder.rglob("*.py")):
        if any(part.startswith(".") or part == "__pycache__" for part in path.relative_to(folder).parts):
            continue
        kind = framework(path)
        if kind is not None:
            out.append(TestFile(path, kind, package, root))
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
