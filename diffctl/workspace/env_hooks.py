"""Packages' environment hooks applied to an environment as sourcing `install/setup.bash` would.

A package makes its `models/` and `worlds/` findable by Gazebo with `ament_environment_hooks(hooks/x.dsv.in)`
(configured with `@VAR@` substitution, installed to `share/<pkg>/environment/`), or ships colcon hooks in
`share/<pkg>/hook/`. Sourcing a prefix runs each package's `package.dsv` in topological order of run
dependencies (alphabetical between equals), following colcon-core's prefix_util: the line types below,
relative values joined to the package prefix, a `.dsv` preferred to its `.sh` sibling, shell hooks without one
sourced by bash. Workspace packages are handled from their sources: their CMakeLists' hooks are configured in
memory for the prefix diffctl gives them (nothing is written into the workspace), and the `hooks` of a
`colcon.pkg` (colcon-metadata's YAML file beside package.xml: paths relative to the install prefix, sourced
after the package's own hooks, as colcon lists them in its package.dsv) are read from that prefix. A colcon
`install/` of the workspace that the shell has not sourced (it is not on COLCON_PREFIX_PATH) is sourced as its
local_setup would source it, for the packages whose sources are not in the workspace.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import tempfile
from collections.abc import Callable, Iterable, MutableMapping
from dataclasses import dataclass, field
from pathlib import Path

from diffctl.errors import ConfigError, suggest

PREPEND = "prepend-non-duplicate"
PREPEND_IF_EXISTS = "prepend-non-duplicate-if-exists"
APPEND = "append-non-duplicate"
SET = "set"
SET_IF_UNSET = "set-if-unset"
SOURCE = "source"
DSV_TYPES = (PREPEND, PREPEND_IF_EXISTS, APPEND, SET, SET_IF_UNSET, SOURCE)
SHELL_EXTENSIONS = ("sh", "bash")  # what `. install/setup.bash` sources: local_setup runs `… sh bash`
_AT_VAR = re.compile(r"@([A-Za-z_][A-Za-z0-9_]*)@")
_VAR_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")

# Shell functions ament's and colcon's shell hooks call (their prefix scripts define them before sourcing).
_SHELL_PRELUDE = r"""
_diffctl_add() { # mode name value
  eval "_cur=\${$2:-}"
  case ":$_cur:" in *":$3:"*) [ "$1" = plain ] || return 0 ;; esac
  if [ -z "$_cur" ]; then export "$2=$3"
  elif [ "$1" = prepend ]; then export "$2=$3:$_cur"
  else export "$2=$_cur:$3"; fi
}
ament_prepend_unique_value() { _diffctl_add prepend "$1" "$2"; }
ament_append_unique_value() { _diffctl_add append "$1" "$2"; }
ament_append_value() { _diffctl_add plain "$1" "$2"; }
colcon_prepend_unique_value() { _diffctl_add prepend "$1" "$2"; }
colcon_append_unique_value() { _diffctl_add append "$1" "$2"; }
"""


class HookError(ConfigError):
    """A hook file diffctl cannot apply: an unknown line type, a line without its fields."""


@dataclass
class HookEnv:
    """The environment being extended, and what sourcing has seen of each variable (colcon's env_state)."""

    env: MutableMapping[str, str]
    files: dict[str, str] = field(default_factory=dict)  # hook files that exist only in memory: path → text
    # The user's file each in-memory hook was configured from (`hooks/x.dsv.in`), line for line: errors name it.
    origins: dict[str, str] = field(default_factory=dict)
    changed: list[str] = field(default_factory=list)  # variables touched, in order

    def exists(self, path: str) -> bool:
        return path in self.files or os.path.exists(path)

    def read(self, path: str) -> str:
        if path in self.files:
            return self.files[path]
        return Path(path).read_text(encoding="utf-8", errors="replace")

    def origin(self, path: str) -> str:
        """The file to name in an error about hook `path`: the user's source of a configured hook."""
        return self.origins.get(path, path)

    def _note(self, name: str) -> None:
        if name not in self.changed:
            self.changed.append(name)

    def add(self, name: str, value: str, *, prepend: bool) -> None:
        parts = [p for p in self.env.get(name, "").split(os.pathsep) if p]
        if value in parts:
            return
        self.env[name] = os.pathsep.join([value, *parts] if prepend else [*parts, value])
        self._note(name)

    def set(self, name: str, value: str, *, only_if_unset: bool) -> None:
        if only_if_unset and self.env.get(name):
            return
        self.env[name] = value
        self._note(name)


def process_dsv(state: HookEnv, path: str, prefix: str) -> None:
    """Apply one .dsv file (colcon-core's process_dsv_file); `source` lines recurse or run shell hooks."""
    groups: dict[str, set[str]] = {}
    for number, raw in enumerate(state.read(path).splitlines(), 1):
        if not raw.strip() or raw.startswith("#"):
            continue
        kind, sep, rest = raw.partition(";")
        if not sep:
            raise HookError(
                "the line has no ';' after its type", source=state.origin(path), line=number,
                hint="e.g. " + PREPEND + ";VAR;path",
            )
        if kind == SOURCE:
            base, ext = os.path.splitext(rest)
            groups.setdefault(base, set())
            if ext[1:] in SHELL_EXTENSIONS:
                groups[base].add(ext[1:])
            continue
        _line(state, kind, rest, prefix, path, number)
    for base, extensions in groups.items():
        full = base if os.path.isabs(base) else os.path.join(prefix, base)
        if state.exists(full + ".dsv"):
            process_dsv(state, full + ".dsv", prefix)  # a .dsv sibling wins: its .sh is not run
        elif "bash" in extensions:  # the additional extension wins over the primary one, as in colcon
            source_shell(state, full + ".bash", prefix)
        elif "sh" in extensions:
            source_shell(state, full + ".sh", prefix)


def _check(state: HookEnv, name: str, values: list[str], path: str, number: int) -> None:
    # colcon's shell scripts eval the name, and no environment holds a NUL: say so here, not as a ValueError later
    if not _VAR_NAME.fullmatch(name):
        raise HookError(f"{name!r} is not an environment variable name", source=state.origin(path), line=number,
                        hint="letters, digits and '_', not starting with a digit")
    if any("\0" in value for value in values):
        raise HookError(f"the value for {name} holds a NUL character, which no environment can carry",
                        source=state.origin(path), line=number)


def _line(state: HookEnv, kind: str, rest: str, prefix: str, path: str, number: int) -> None:
    if kind in (SET, SET_IF_UNSET):
        name, sep, value = rest.partition(";")
        if not sep:
            raise HookError("the line has no ';' between the variable and its value", source=state.origin(path),
                            line=number)
        _check(state, name, [value], path, number)
        prefixed = os.path.join(prefix, value) if value else prefix
        state.set(name, prefixed if os.path.exists(prefixed) else value, only_if_unset=kind == SET_IF_UNSET)
    elif kind in (PREPEND, PREPEND_IF_EXISTS, APPEND):
        name, *values = rest.split(";")
        _check(state, name, values, path, number)
        for value in values:
            full = prefix if not value else value if os.path.isabs(value) else os.path.join(prefix, value)
            if kind == PREPEND_IF_EXISTS and not os.path.exists(full):
                continue
            state.add(name, full, prepend=kind != APPEND)
    else:
        raise HookError(
            f"unknown environment hook type {kind!r}{suggest(kind, DSV_TYPES)}",
            source=state.origin(path),
            line=number,
            hint="valid: " + ", ".join(DSV_TYPES),
        )


def source_shell(state: HookEnv, path: str, prefix: str) -> None:
    """Source a shell hook in bash and take over what it exported, as `. setup.bash` would."""
    bash = shutil.which("bash")
    if bash is None or not state.exists(path):
        return
    with tempfile.TemporaryDirectory(prefix="diffctl-hook-") as tmp:
        script = path
        if path in state.files:
            script = os.path.join(tmp, os.path.basename(path))
            Path(script).write_text(state.files[path])
        env = {**state.env, "AMENT_CURRENT_PREFIX": prefix, "COLCON_CURRENT_PREFIX": prefix}
        code = _SHELL_PRELUDE + '. "$1" >/dev/null; unset _cur; env -0'
        try:
            out = subprocess.run(
                [bash, "--noprofile", "--norc", "-c", code, "diffctl-hook", script],
                env=env,
                capture_output=True,
                timeout=30,
                check=False,
            )
        except (OSError, subprocess.TimeoutExpired) as e:
            raise HookError(f"sourcing the hook failed: {e}", source=state.origin(path)) from None
    # bash names the file it sourced: the user's, not the configured copy made for it here
    from diffctl.source_paths import user_source

    said = out.stderr.decode(errors="replace").replace(script, user_source(state.origin(path))).strip().splitlines()
    if out.returncode != 0:
        raise HookError(f"sourcing the hook failed: {(said or [f'exit code {out.returncode}'])[-1]}",
                        source=state.origin(path))
    if said:
        # A hook that fails part way is not fatal when a shell sources it: what it printed is shown, as there.
        from diffctl.console import warn

        for line in said:
            warn(line)
    after = dict(item.split("=", 1) for item in out.stdout.decode(errors="replace").split("\0") if "=" in item)
    for name in ("AMENT_CURRENT_PREFIX", "COLCON_CURRENT_PREFIX", "_", "SHLVL", "PWD", "OLDPWD"):
        after.pop(name, None)
    for name, value in after.items():
        if state.env.get(name) != value:
            state.set(name, value, only_if_unset=False)


def order_packages(deps: dict[str, set[str]]) -> list[str]:
    """Topological order, dependencies first, alphabetical among the ready ones (colcon's order_packages)."""
    pending = {name: {d for d in ds if d in deps and d != name} for name, ds in deps.items()}
    ordered: list[str] = []
    while pending:
        ready = sorted(name for name, ds in pending.items() if not ds)
        if not ready:
            raise ConfigError("circular run dependencies between: " + ", ".join(sorted(pending)))
        ordered.append(ready[0])
        del pending[ready[0]]
        for ds in pending.values():
            ds.discard(ordered[-1])
    return ordered


# --- install trees (colcon layout) ------------------------------------------------------------------------


def install_tree_packages(install: Path) -> dict[str, tuple[Path, set[str]]]:
    """name → (prefix, run deps) from `share/colcon-core/packages/<name>`, isolated or merged layout."""
    found: dict[str, tuple[Path, set[str]]] = {}
    index = install / "share" / "colcon-core" / "packages"
    entries = [(install, p) for p in index.iterdir()] if index.is_dir() else []
    if not entries and install.is_dir():
        for sub in install.iterdir():
            marker = sub / "share" / "colcon-core" / "packages" / sub.name
            if sub.is_dir() and not sub.name.startswith(".") and marker.is_file():
                entries.append((sub, marker))
    for prefix, marker in entries:
        if marker.is_file() and not marker.name.startswith("."):
            text = marker.read_text().strip()
            found[marker.name] = (prefix, set(text.split(os.pathsep)) if text else set())
    return found


def apply_install_tree(env: MutableMapping[str, str], install: Path, skip: Iterable[str] = ()) -> list[str]:
    """Source a colcon install tree's packages (but those in `skip`) into `env`; returns the variables changed."""
    skipped = set(skip)
    packages = {n: v for n, v in install_tree_packages(install).items() if n not in skipped}
    state = HookEnv(env)
    for name in order_packages({n: deps for n, (_, deps) in packages.items()}):
        prefix = str(packages[name][0].resolve())
        dsv = os.path.join(prefix, "share", name, "package.dsv")
        if os.path.exists(dsv):
            process_dsv(state, dsv, prefix)
    return state.changed


# --- workspace sources -----------------------------------------------------------------------------------


def configure(text: str, variables: dict[str, str]) -> str:
    """CMake's configure_file(@ONLY): `@VAR@` → its value, unset variables → ''."""
    return _AT_VAR.sub(lambda m: variables.get(m.group(1), ""), text)


def cmake_hooks(package_dir: Path, package: str, prefix: Path) -> dict[str, tuple[str, Path]]:
    """The configured `ament_environment_hooks()` files of a CMake package: installed name → (text, the
    file it was configured from)."""
    from diffctl.workspace.cmake_script import PREFIX_SENTINEL, Call, Script

    lists = package_dir / "CMakeLists.txt"
    hooks: dict[str, tuple[str, Path]] = {}
    if not lists.is_file():
        return hooks
    script: Script

    def on_call(call: Call) -> None:
        if call.name != "ament_environment_hooks":
            return
        variables = {k: v.replace(PREFIX_SENTINEL, str(prefix)) for k, v in script.variables.items()}
        variables.setdefault("PROJECT_NAME", package)
        variables["CMAKE_INSTALL_PREFIX"] = str(prefix)
        for arg in call.args:
            source = Path(arg) if os.path.isabs(arg) else call.current_dir / arg
            try:
                text = source.read_text(encoding="utf-8", errors="replace")
            except OSError as e:
                raise HookError(
                    f"ament_environment_hooks() names {arg!r}, which cannot be read: {e.strerror}",
                    source=str(call.source),
                    line=call.line,
                ) from None
            name = source.name
            if name.endswith(".in"):
                name, text = name[:-3], configure(text, variables)
            hooks[name] = (text, source)

    script = Script(package_dir, on_call)
    script.run_file(lists)
    return hooks


def colcon_pkg_hooks(package_dir: Path) -> list[str]:
    """The `hooks` of a package's `colcon.pkg` (YAML, as colcon-metadata reads it): each a path relative to
    the install prefix, or a list whose first item is one (the rest are shell arguments, unused by dsv)."""
    import yaml

    path = package_dir / "colcon.pkg"
    if not path.is_file():
        return []
    try:
        data = yaml.safe_load(path.read_text(encoding="utf-8", errors="replace"))
    except yaml.YAMLError as e:
        mark = getattr(e, "problem_mark", None)
        raise HookError(
            f"colcon.pkg is not valid YAML: {getattr(e, 'problem', None) or e}",
            source=str(path),
            line=mark.line + 1 if mark is not None else None,
        ) from None
    if data is None:
        return []
    if not isinstance(data, dict):
        raise HookError("colcon.pkg must be a mapping (name, type, dependencies, hooks, …)", source=str(path))
    raw = data.get("hooks", [])
    if not isinstance(raw, list):
        raise HookError(
            f"colcon.pkg: 'hooks' must be a list of paths, got {raw!r}",
            source=str(path),
            field="hooks",
            hint='e.g. hooks: ["share/my_pkg/hook/models.dsv", "share/my_pkg/hook/models.sh"]',
        )
    hooks = []
    for i, item in enumerate(raw):
        first = item[0] if isinstance(item, list) and item else item
        if not isinstance(first, str) or not first:
            raise HookError(
                f"colcon.pkg: hooks[{i}] {item!r} is not a path relative to the install prefix",
                source=str(path),
                field=f"hooks[{i}]",
                hint="a string, or a list whose first item is one",
            )
        hooks.append(first)
    return hooks


def apply_package_hooks(
    state: HookEnv, package: str, prefix: Path, hooks: dict[str, tuple[str, Path]], extra: Iterable[str] = ()
) -> None:
    """Apply one package's hooks as its package.dsv would: its ament environment hooks (`source` per hook,
    sorted by name, through local_setup.dsv), then `extra` hooks (colcon.pkg's, relative to the prefix)."""
    env_dir = prefix / "share" / package / "environment"
    lines = []
    for name in sorted(hooks):
        path = str(env_dir / name)
        state.files[path], source = hooks[name]
        state.origins[path] = str(source)
        lines.append(f"{SOURCE};share/{package}/environment/{name}")
    # colcon makes an absolute hook path relative to the prefix; a relative one stays as written
    lines += [f"{SOURCE};{os.path.relpath(h, prefix) if os.path.isabs(h) else h}" for h in extra]
    local = str(prefix / "share" / package / "local_setup.dsv")
    state.files[local] = "\n".join(lines) + "\n"
    process_dsv(state, local, str(prefix))


@dataclass(frozen=True)
class SourcePackage:
    name: str
    source: Path
    run_depends: frozenset[str]
    prefix: Callable[[], Path]  # the package's prefix (synced on demand: only packages with hooks need one)


def apply_source_packages(env: MutableMapping[str, str], packages: Iterable[SourcePackage]) -> list[str]:
    """Apply the hooks of workspace packages, in colcon's order; returns the variables changed."""
    by_name = {p.name: p for p in packages}
    state = HookEnv(env)
    for name in order_packages({n: set(p.run_depends) for n, p in by_name.items()}):
        pkg = by_name[name]
        extra = colcon_pkg_hooks(pkg.source)
        lists = pkg.source / "CMakeLists.txt"
        # reading the CMake tree only when it names hooks: the common case has none
        has_cmake_hooks = lists.is_file() and "ament_environment_hooks" in lists.read_text(
            encoding="utf-8", errors="replace"
        )
        if not has_cmake_hooks and not extra:
            continue
        prefix = pkg.prefix()
        hooks = cmake_hooks(pkg.source, name, prefix) if has_cmake_hooks else {}
        if hooks or extra:
            apply_package_hooks(state, name, prefix, hooks, extra)
    return state.changed


def install_tree_sourced(env: MutableMapping[str, str], install: Path) -> bool:
    """Whether `install` was sourced into `env` (colcon's prefix script puts it on COLCON_PREFIX_PATH)."""
    here = os.path.realpath(install)
    return any(os.path.realpath(p) == here for p in env.get("COLCON_PREFIX_PATH", "").split(os.pathsep) if p)


def apply_workspace_hooks(env: MutableMapping[str, str], workspace: Path | None) -> list[str]:
    """The hooks of `workspace`'s packages (sources, or its colcon install/ when that is all there is)."""
    if workspace is None:
        return []
    from diffctl.workspace.resolve import find_package, scan_workspace

    scan = scan_workspace(workspace)
    packages = [
        SourcePackage(
            name,
            m.path.parent,
            frozenset(m.run_depends),
            lambda name=name: _prefix_of(find_package(name, workspace)),
        )
        for name, m in scan.manifests.items()
    ]
    changed: list[str] = []
    install = workspace / "install"
    if install.is_dir() and not install_tree_sourced(env, install):
        # built but not sourced: what only the install tree knows (packages without sources here); the
        # workspace's own packages come from their sources below, never from a possibly stale build
        changed += apply_install_tree(env, install, skip=scan.manifests)
    changed += [v for v in apply_source_packages(env, packages) if v not in changed]
    return changed


def _prefix_of(pkg: object) -> Path:
    prefix = getattr(pkg, "prefix", None)
    if prefix is None:
        raise ConfigError(f"package {getattr(pkg, 'name', '?')!r} has no install prefix")
    return prefix
