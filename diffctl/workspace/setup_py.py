"""An ament_python package's install layout from `setup.py` / `setup.cfg`, without running either.

setup.py is read with `ast` and only a safe subset is evaluated: literals, module-level names, `+`,
`%`, f-strings, `os.path.join`, `glob`, `str.format`, `sorted`/`list`, and comprehensions over those.
Each data file installs to `<dest>/<basename>` (nothing recurses, as setuptools does); console scripts
and `scripts=` files install to `lib/<pkg>` (ament_python's setup.cfg sets `install_scripts` there).
An entry that needs the script to run is reported, not guessed.
"""

from __future__ import annotations

import ast
import configparser
import glob
import os
import posixpath
from collections.abc import Callable
from pathlib import Path
from typing import Any

from diffctl.workspace.install_rules import InstallIndex


class _Unsupported(Exception):
    def __init__(self, node: ast.AST) -> None:
        super().__init__(getattr(node, "lineno", 0))
        self.line = getattr(node, "lineno", 0)


def _glob_in(package_dir: Path) -> Callable[..., list[str]]:
    def run(pattern: str, recursive: bool = False) -> list[str]:
        base = str(package_dir)
        found = glob.glob(os.path.join(base, pattern), recursive=recursive)
        return sorted(os.path.relpath(f, base) for f in found)

    return run


class _Evaluator:
    """Evaluates the safe subset of expressions; anything else raises _Unsupported."""

    def __init__(self, package_dir: Path) -> None:
        self.names: dict[str, Any] = {}
        g = _glob_in(package_dir)
        # Callables by their dotted name as written, whatever the import style.
        self.functions: dict[str, Callable[..., Any]] = {
            "os.path.join": posixpath.join,
            "path.join": posixpath.join,
            "join": posixpath.join,
            "os.path.basename": posixpath.basename,
            "os.path.dirname": posixpath.dirname,
            "glob": g,
            "glob.glob": g,
            "sorted": sorted,
            "list": list,
            "str": str,
            "set": set,
        }

    def dotted(self, node: ast.AST) -> str | None:
        if isinstance(node, ast.Name):
            return node.id
        if isinstance(node, ast.Attribute):
            inner = self.dotted(node.value)
            return f"{inner}.{node.attr}" if inner else None
        return None

    def eval(self, node: ast.AST) -> Any:
        if isinstance(node, ast.Constant):
            return node.value
        if isinstance(node, ast.Name):
            if node.id in self.names:
                return self.names[node.id]
            raise _Unsupported(node)
        if isinstance(node, ast.Attribute) and self.dotted(node) == "os.sep":
            return "/"
        if isinstance(node, (ast.List, ast.Tuple, ast.Set)):
            items: list[Any] = []
            for el in node.elts:
                if isinstance(el, ast.Starred):
                    items.extend(self.eval(el.value))
                else:
                    items.append(self.eval(el))
            return tuple(items) if isinstance(node, ast.Tuple) else items
        if isinstance(node, ast.Dict):
            return {self.eval(k): self.eval(v) for k, v in zip(node.keys, node.values, strict=True) if k is not None}
        if isinstance(node, ast.JoinedStr):
            parts = []
            for v in node.values:
                parts.append(str(self.eval(v.value)) if isinstance(v, ast.FormattedValue) else str(self.eval(v)))
            return "".join(parts)
        if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Add, ast.Mod)):
            left, right = self.eval(node.left), self.eval(node.right)
            try:
                return left + right if isinstance(node.op, ast.Add) else left % right
            except TypeError:
                raise _Unsupported(node) from None
        if isinstance(node, ast.Call):
            return self.call(node)
        if isinstance(node, ast.ListComp) and len(node.generators) == 1:
            gen = node.generators[0]
            if not isinstance(gen.target, (ast.Name, ast.Tuple)):
                raise _Unsupported(node)
            out = []
            for item in self.eval(gen.iter):
                saved = dict(self.names)
                self.bind(gen.target, item)
                if all(self.eval(cond) for cond in gen.ifs):
                    out.append(self.eval(node.elt))
                self.names = saved
            return out
        if isinstance(node, ast.Compare) and len(node.ops) == 1 and isinstance(node.ops[0], (ast.Eq, ast.NotEq)):
            equal = self.eval(node.left) == self.eval(node.comparators[0])
            return equal if isinstance(node.ops[0], ast.Eq) else not equal
        raise _Unsupported(node)

    def bind(self, target: ast.AST, value: Any) -> None:
        if isinstance(target, ast.Name):
            self.names[target.id] = value
        elif isinstance(target, ast.Tuple):
            for t, v in zip(target.elts, value, strict=True):
                self.bind(t, v)
        else:
            raise _Unsupported(target)

    def call(self, node: ast.Call) -> Any:
        func = node.func
        if isinstance(func, ast.Attribute) and func.attr in ("format", "replace", "endswith", "startswith"):
            owner = self.eval(func.value)
            if isinstance(owner, str):
                args = [self.eval(a) for a in node.args]
                kwargs = {k.arg: self.eval(k.value) for k in node.keywords if k.arg}
                return getattr(owner, func.attr)(*args, **kwargs)
        name = self.dotted(func)
        if name in self.functions:
            args = [self.eval(a) for a in node.args]
            kwargs = {k.arg: self.eval(k.value) for k in node.keywords if k.arg}
            return self.functions[name](*args, **kwargs)
        raise _Unsupported(node)


def _setup_call(tree: ast.Module) -> ast.Call | None:
    for node in ast.walk(tree):
        if isinstance(node, ast.Call):
            f = node.func
            if (isinstance(f, ast.Name) and f.id == "setup") or (isinstance(f, ast.Attribute) and f.attr == "setup"):
                return node
    return None


def _module_names(tree: ast.Module, ev: _Evaluator) -> None:
    """Module-level assignments (package_name = …, data_files = […], data_files += …, .append/.extend)."""
    for stmt in tree.body:
        try:
            if isinstance(stmt, ast.Assign):
                value = ev.eval(stmt.value)
                for t in stmt.targets:
                    ev.bind(t, value)
            elif isinstance(stmt, ast.AnnAssign) and stmt.value is not None and isinstance(stmt.target, ast.Name):
                ev.names[stmt.target.id] = ev.eval(stmt.value)
            elif isinstance(stmt, ast.AugAssign) and isinstance(stmt.target, ast.Name):
                if isinstance(stmt.op, ast.Add) and stmt.target.id in ev.names:
                    ev.names[stmt.target.id] = ev.names[stmt.target.id] + ev.eval(stmt.value)
            elif isinstance(stmt, ast.Expr) and isinstance(stmt.value, ast.Call):
                f = stmt.value.func
                if (
                    isinstance(f, ast.Attribute)
                    and f.attr in ("append", "extend")
                    and isinstance(f.value, ast.Name)
                    and isinstance(ev.names.get(f.value.id), list)
                    and len(stmt.value.args) == 1
                ):
                    getattr(ev.names[f.value.id], f.attr)(ev.eval(stmt.value.args[0]))
        except (_Unsupported, TypeError, ValueError):
            if isinstance(stmt, ast.Assign):
                for t in stmt.targets:
                    if isinstance(t, ast.Name):
                        ev.names.pop(t.id, None)


def _add_data_files(index: InstallIndex, package_dir: Path, entries: Any, where: str) -> None:
    if not isinstance(entries, (list, tuple)):
        index.problems.append(f"{where}: data_files is not a list of (destination, [files])")
        return
    for entry in entries:
        if not (isinstance(entry, (list, tuple)) and len(entry) == 2 and isinstance(entry[0], str)):
            index.problems.append(f"{where}: data_files entry {entry!r} is not (destination, [files])")
            continue
        dest, files = entry
        dest = posixpath.normpath(dest.replace("\\", "/").lstrip("/"))
        for f in [files] if isinstance(files, str) else files:
            path = package_dir / str(f)
            if path.is_dir():
                index.problems.append(f"{where}: data_files names the directory {f} (only files are installed)")
            elif not path.is_file():
                index.problems.append(f"{where}: data file {f} does not exist")
            else:
                index.add(posixpath.join(dest, path.name), path)


def _console_scripts(index: InstallIndex, entry_points: Any) -> None:
    scripts = entry_points.get("console_scripts", []) if isinstance(entry_points, dict) else []
    if isinstance(scripts, str):
        scripts = scripts.splitlines()
    for line in scripts:
        if isinstance(line, str) and "=" in line:
            name, target = (part.strip() for part in line.split("=", 1))
            if name and ":" in target:
                index.console_scripts[name] = target


def _add_scripts(index: InstallIndex, package_dir: Path, package_name: str, scripts: Any, where: str) -> None:
    if isinstance(scripts, str):
        scripts = scripts.split()
    if not isinstance(scripts, (list, tuple)):
        index.problems.append(f"{where}: scripts is not a list of files")
        return
    for f in scripts:
        path = package_dir / str(f)
        if not path.is_file():
            index.problems.append(f"{where}: script {f} does not exist")
        else:
            index.add(f"lib/{package_name}/{path.name}", path, program=True)


def _read_setup_cfg(index: InstallIndex, package_dir: Path, package_name: str) -> None:
    cfg_path = package_dir / "setup.cfg"
    if not cfg_path.is_file():
        return
    cfg = configparser.ConfigParser(interpolation=None)
    try:
        cfg.read(cfg_path, encoding="utf-8")
    except configparser.Error as e:
        index.problems.append(f"setup.cfg: cannot read: {e}".splitlines()[0])
        return
    if cfg.has_section("options.data_files"):
        g = _glob_in(package_dir)
        entries = []
        for dest, value in cfg.items("options.data_files"):
            files: list[str] = []
            for item in (v.strip() for v in value.replace(",", "\n").splitlines()):
                if item:
                    files.extend(g(item) if any(c in item for c in "*?[") else [item])
            entries.append((dest, files))
        _add_data_files(index, package_dir, entries, "setup.cfg [options.data_files]")
    if cfg.has_option("options", "scripts"):
        _add_scripts(index, package_dir, package_name, cfg.get("options", "scripts"), "setup.cfg [options] scripts")
    if cfg.has_section("options.entry_points") and cfg.has_option("options.entry_points", "console_scripts"):
        _console_scripts(index, {"console_scripts": cfg.get("options.entry_points", "console_scripts")})


def python_install_index(package_dir: Path, package_name: str) -> InstallIndex:
    """The files `setup.py install` (or colcon's symlink_data) would put under the prefix."""
    index = InstallIndex()
    _read_setup_cfg(index, package_dir, package_name)
    setup_py = package_dir / "setup.py"
    if setup_py.is_file():
        try:
            tree = ast.parse(setup_py.read_text(encoding="utf-8", errors="replace"), str(setup_py))
        except SyntaxError as e:
            index.problems.append(f"setup.py:{e.lineno}: syntax error: {e.msg}")
            tree = None
        call = _setup_call(tree) if tree is not None else None
        if tree is not None and call is not None:
            ev = _Evaluator(package_dir)
            _module_names(tree, ev)
            for kw in call.keywords:
                if kw.arg not in ("data_files", "entry_points", "scripts"):
                    continue
                # A literal list is read entry by entry, so one entry built by code loses only itself.
                literal = kw.arg == "data_files" and isinstance(kw.value, (ast.List, ast.Tuple))
                for node in kw.value.elts if literal else [kw.value]:  # type: ignore[attr-defined]
                    try:
                        value = ev.eval(node)
                    except (_Unsupported, TypeError, ValueError) as e:
                        line = e.line if isinstance(e, _Unsupported) else node.lineno
                        index.problems.append(
                            f"setup.py:{line}: {kw.arg} uses code diffctl does not run (it never executes setup.py)"
                        )
                        continue
                    if kw.arg == "entry_points":
                        _console_scripts(index, value)
                    elif kw.arg == "scripts":
                        _add_scripts(index, package_dir, package_name, value, f"setup.py:{node.lineno}")
                    else:
                        _add_data_files(index, package_dir, [value] if literal else value, f"setup.py:{node.lineno}")
    # colcon installs package.xml and the index marker itself when data_files leaves them out.
    manifest = package_dir / "package.xml"
    key = f"share/{package_name}/package.xml"
    if key not in index.files and manifest.is_file():
        index.add(key, manifest)
    return index
