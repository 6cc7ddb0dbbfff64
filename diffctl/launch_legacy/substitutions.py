"""Substitutions: values computed when a launch description is resolved (`$(var x)`, LaunchConfiguration, …).

The same classes back every frontend: the YAML and XML frontends parse `$(name arg …)` strings into them
(substitution_syntax.py); the Python frontend constructs them directly (LaunchConfiguration, …).
Everything is evaluated against a `Scope` (see context.py) by `perform(value, scope)`.
"""

from __future__ import annotations

import os
import shlex
import subprocess
from abc import ABC, abstractmethod
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from diffctl.errors import LaunchError, suggest

if TYPE_CHECKING:
    from diffctl.launch_legacy.context import Scope


class Substitution(ABC):
    """A piece of text known only at resolve time."""

    @abstractmethod
    def perform(self, scope: Scope) -> str:
        """The substitution's text in `scope`."""

    def describe(self) -> str:
        return f"$({type(self).__name__})"

    def __repr__(self) -> str:
        return self.describe()


SomeSubstitutions = str | Substitution | Sequence["str | Substitution"]


def normalize(value: Any) -> tuple[Substitution, ...]:
    """str / Substitution / list of those → a tuple of substitutions (a list concatenates its parts)."""
    if isinstance(value, Substitution):
        return (value,)
    if isinstance(value, str):
        return (TextSubstitution(value),)
    if isinstance(value, (int, float, bool)):
        return (TextSubstitution(str(value).lower() if isinstance(value, bool) else str(value)),)
    if isinstance(value, Iterable):
        out: list[Substitution] = []
        for part in value:
            out.extend(normalize(part))
        return tuple(out)
    raise LaunchError(f"cannot use {value!r} ({type(value).__name__}) as text or a substitution")


def describe(parts: tuple[Substitution, ...]) -> str:
    """Substitutions as a YAML launch file would write them."""
    return "".join(p.describe() for p in parts)


def perform(value: Any, scope: Scope) -> str:
    """Evaluate a str, a Substitution or a list of them to one string."""
    return "".join(s.perform(scope) for s in normalize(value))


def is_static(value: Any) -> bool:
    return all(isinstance(s, TextSubstitution) for s in normalize(value))


@dataclass(frozen=True, repr=False)
class TextSubstitution(Substitution):
    text: str

    def perform(self, scope: Scope) -> str:
        return self.text

    def describe(self) -> str:
        return self.text


class LaunchConfiguration(Substitution):
    """`$(var name)`: the value of a launch argument or `let` variable."""

    def __init__(self, variable_name: SomeSubstitutions, default: SomeSubstitutions | None = None) -> None:
        self.variable_name = normalize(variable_name)
        self.default = None if default is None else normalize(default)

    def perform(self, scope: Scope) -> str:
        name = perform(self.variable_name, scope)
        if name in scope.configurations:
            return scope.configurations[name]
        if self.default is not None:
            return perform(self.default, scope)
        known = sorted(scope.configurations)
        raise LaunchError(
            f"launch configuration {name!r} is not set{suggest(name, known)}",
            hint="set: " + (", ".join(known) if known else "none") + "; declare it with an `arg` or `let`",
        )

    def describe(self) -> str:
        return f"$(var {''.join(s.describe() for s in self.variable_name)})"


class EnvironmentVariable(Substitution):
    """`$(env NAME [default])`; without a default an unset variable is an error. `$(optenv …)` defaults to ''."""

    def __init__(self, name: SomeSubstitutions, *, default_value: SomeSubstitutions | None = None) -> None:
        self.name = normalize(name)
        self.default_value = None if default_value is None else normalize(default_value)

    def describe(self) -> str:
        if self.default_value is None:
            return f"$(env {describe(self.name)})"
        return f"$(optenv {describe(self.name)} '{describe(self.default_value)}')"

    def perform(self, scope: Scope) -> str:
        name = perform(self.name, scope)
        if name in scope.env:
            return scope.env[name]
        if self.default_value is not None:
            return perform(self.default_value, scope)
        raise LaunchError(f"environment variable {name!r} is not set", hint="use $(optenv NAME default) to allow it")


class FindPackageShare(Substitution):
    """`$(find-pkg-share pkg)`: the share directory of a package from the package index."""

    def __init__(self, package: SomeSubstitutions) -> None:
        self.package = normalize(package)

    def describe(self) -> str:
        return f"$(find-pkg-share {describe(self.package)})"

    def perform(self, scope: Scope) -> str:
        from diffctl.workspace import package_index

        return str(package_index.share_dir(perform(self.package, scope)))


class PathJoinSubstitution(Substitution):
    """Parts joined with the path separator, as os.path.join does."""

    def __init__(self, substitutions: Sequence[SomeSubstitutions]) -> None:
        self.parts = [normalize(p) for p in substitutions]

    def describe(self) -> str:
        return "/".join(describe(p) for p in self.parts)

    def perform(self, scope: Scope) -> str:
        return os.path.join(*[perform(p, scope) for p in self.parts]) if self.parts else ""


class ThisLaunchFileDir(Substitution):
    """`$(dirname)`: the directory of the launch file being read."""

    def describe(self) -> str:
        return "$(dirname)"

    def perform(self, scope: Scope) -> str:
        return str(Path(scope.launch_file).parent) if scope.launch_file else os.getcwd()


class ThisLaunchFile(Substitution):
    """`$(filename)`: the path of the launch file being read."""

    def describe(self) -> str:
        return "$(filename)"

    def perform(self, scope: Scope) -> str:
        return scope.launch_file or ""


class PythonExpression(Substitution):
    """`$(eval expr [modules])`: a Python expression, as text (`str()` of its value, `True`/`False` capitalised).

    As launch's: evaluated with empty globals, so every builtin is there (`map`, `format`, `isinstance`, …);
    each module of `python_modules` (default `math`) is bound by its name, and `math`'s names also bare
    (`pi`, `sqrt(2)`).
    """

    def __init__(self, expression: SomeSubstitutions, python_modules: SomeSubstitutions | None = None) -> None:
        self.expression = normalize(expression)
        # ROS takes a list of module names; `$(eval expr 'math,os')` gives one comma-separated text.
        if python_modules is None:
            self.python_modules: list[tuple[Substitution, ...]] | None = None
        elif isinstance(python_modules, (list, tuple)):
            self.python_modules = [normalize(m) for m in python_modules]
        else:
            self.python_modules = [normalize(python_modules)]

    def describe(self) -> str:
        return f"$(eval '{describe(self.expression)}')"

    def _modules(self, scope: Scope) -> list[str]:
        if self.python_modules is None:
            return ["math"]
        names = ",".join(perform(m, scope) for m in self.python_modules)
        return [m.strip() for m in names.split(",") if m.strip()]

    def perform(self, scope: Scope) -> str:
        import importlib

        text = perform(self.expression, scope)
        names: dict[str, Any] = {}
        for name in self._modules(scope):
            try:
                module = importlib.import_module(name)
            except ImportError:
                raise LaunchError(f"$(eval): python module {name!r} cannot be imported") from None
            if module.__name__ == "math":
                names.update(vars(module))
            names[module.__name__] = module
            names.setdefault(name.split(".")[0], importlib.import_module(name.split(".")[0]))
        try:
            return str(eval(text, {}, names))
        except Exception as e:
            raise LaunchError(f"$(eval {text}) failed: {type(e).__name__}: {e}") from None


class AnonName(Substitution):
    """`$(anon name)`: a name made unique for this launch, the same each time it is used in one launch."""

    def __init__(self, name: SomeSubstitutions) -> None:
        self.name = normalize(name)

    def describe(self) -> str:
        return f"$(anon {describe(self.name)})"

    def perform(self, scope: Scope) -> str:
        return scope.anon_name(perform(self.name, scope))


class Command(Substitution):
    """`$(command 'cmd args' [fail|warn|ignore])`: the stdout of a command run at resolve time."""

    def __init__(self, command: SomeSubstitutions, on_stderr: SomeSubstitutions = "fail") -> None:
        self.command = normalize(command)
        self.on_stderr = normalize(on_stderr)

    def describe(self) -> str:
        return f"$(command '{describe(self.command)}')"

    def perform(self, scope: Scope) -> str:
        text = perform(self.command, scope)
        policy = perform(self.on_stderr, scope)
        if policy not in ("fail", "warn", "ignore", "capture"):
            raise LaunchError(f"$(command) stderr policy {policy!r} is not valid", hint="valid: fail, warn, ignore")
        from diffctl.launch_legacy.environment import with_tool_path

        try:
            argv = shlex.split(text)
        except ValueError as e:
            raise LaunchError(f"$(command {text}): cannot split it into arguments: {e}") from None
        if not argv:
            raise LaunchError("$(command) was given an empty command")
        try:
            done = subprocess.run(
                argv, capture_output=True, text=True, env=with_tool_path(dict(scope.env)), timeout=120
            )
        except (OSError, subprocess.TimeoutExpired) as e:
            raise LaunchError(f"$(command {text}) could not run: {e}") from None
        if done.returncode != 0:
            raise LaunchError(
                f"executed command failed (exit code {done.returncode}). Command: {text}: "
                + (done.stderr.strip().splitlines() or ["(no error output)"])[-1][:300]
            )
        if done.stderr.strip() and policy == "warn":
            from diffctl import console

            console.warn(f"$(command {text}) wrote to stderr: {done.stderr.strip()[:300]}")
        if done.stderr.strip() and policy == "fail":
            raise LaunchError(
                f"$(command {text}) wrote to stderr: {done.stderr.strip()[:200]}",
                hint="pass 'warn' or 'ignore' as second argument to allow it",
            )
        if policy == "capture":
            return done.stdout + done.stderr
        return done.stdout


class FileContent(Substitution):
    """`$(file-content path)`: a file's text, with placeholders replaced (the tutorial's SDF step).

    `FileContent(path, replacements={"PARAMETERS_CONFIG_FILE_PLACEHOLDER": config_path})`.
    """

    def __init__(self, path: SomeSubstitutions, replacements: Mapping[str, SomeSubstitutions] | None = None) -> None:
        self.path = normalize(path)
        self.replacements = {k: normalize(v) for k, v in (replacements or {}).items()}

    def describe(self) -> str:
        return f"$(file-content {describe(self.path)})"

    def perform(self, scope: Scope) -> str:
        path = perform(self.path, scope)
        try:
            text = Path(path).read_text()
        except OSError as e:
            raise LaunchError(f"cannot read file {path!r}: {e.strerror or e}") from None
        for placeholder, value in self.replacements.items():
            if placeholder not in text:
                raise LaunchError(
                    f"placeholder {placeholder!r} does not occur in {path}",
                    hint="check the spelling; every listed placeholder must be replaced",
                )
            text = text.replace(placeholder, perform(value, scope))
        return text


class FindExecutable(Substitution):
    """`$(find-exec name)`: the full path of an executable on PATH (this interpreter's bin directory first)."""

    def __init__(self, *, name: SomeSubstitutions) -> None:
        self.name = normalize(name)

    def describe(self) -> str:
        return f"$(find-exec {describe(self.name)})"

    def perform(self, scope: Scope) -> str:
        import shutil

        from diffctl.launch_legacy.environment import with_tool_path

        name = perform(self.name, scope)
        found = shutil.which(name, path=with_tool_path(dict(scope.env)).get("PATH", ""))
        if found is None:
            raise LaunchError(f"executable {name!r} not found on the PATH")
        return found


class FindPackagePrefix(Substitution):
    """`$(find-pkg-prefix pkg)`: the install prefix of a package (its share directory's grandparent)."""

    def __init__(self, package: SomeSubstitutions) -> None:
        self.package = normalize(package)

    def describe(self) -> str:
        return f"$(find-pkg-prefix {describe(self.package)})"

    def perform(self, scope: Scope) -> str:
        from diffctl.workspace import package_index

        share = package_index.share_dir(perform(self.package, scope))
        return str(share.parent.parent) if share.parent.name == "share" else str(share)


class ExecutableInPackage(Substitution):
    """`$(exec-in-pkg exe pkg)`: the command that runs a package's executable."""

    def __init__(self, executable: SomeSubstitutions, package: SomeSubstitutions) -> None:
        self.executable, self.package = normalize(executable), normalize(package)

    def describe(self) -> str:
        return f"$(exec-in-pkg {describe(self.executable)} {describe(self.package)})"

    def perform(self, scope: Scope) -> str:
        from diffctl.workspace import package_index

        argv = package_index.executable_argv(perform(self.package, scope), perform(self.executable, scope))
        return shlex.join(argv)


def parse(text: str) -> tuple[Substitution, ...]:
    """A frontend string with `$(...)` substitutions → a tuple of substitutions (see substitution_syntax.py)."""
    from diffctl.launch_legacy.substitution_syntax import parse as parse_syntax

    return parse_syntax(text)


class PathSubstitution(Substitution):
    """A path built with `/` from substitutions (`PathSubstitution(FindPackageShare('p')) / 'config' / 'x.yaml'`)."""

    def __init__(self, path: SomeSubstitutions | os.PathLike[str]) -> None:
        self.parts: list[tuple[Substitution, ...]] = [
            normalize(os.fspath(path) if isinstance(path, os.PathLike) else path)
        ]

    def __truediv__(self, other: SomeSubstitutions | os.PathLike[str]) -> PathSubstitution:
        out = PathSubstitution("")
        out.parts = [*self.parts, normalize(os.fspath(other) if isinstance(other, os.PathLike) else other)]
        return out

    def describe(self) -> str:
        return "/".join(describe(p) for p in self.parts)

    def perform(self, scope: Scope) -> str:
        return os.path.join(*[perform(p, scope) for p in self.parts])


class LocalSubstitution(Substitution):
    """A value of the context's locals (`LocalSubstitution('event.returncode')`), as launch's."""

    def __init__(self, expression: str, description: str | None = None) -> None:
        self.expression = expression
        self.description = description

    def describe(self) -> str:
        return self.description or f"LocalVar('{self.expression}')"

    def perform(self, scope: Scope) -> str:
        values = scope.get_locals_as_dict()
        try:
            return str(eval(self.expression, {}, values))
        except Exception as e:
            raise LaunchError(f"LocalSubstitution {self.expression!r}: {type(e).__name__}: {e}") from None


class LaunchLogDir(Substitution):
    """`$(launch_log_dir)` / `$(log_dir)`: the directory of this launch's logs."""

    def describe(self) -> str:
        return "$(launch_log_dir)"

    def perform(self, scope: Scope) -> str:
        return (
            scope.env.get("DIFFCTL_LOG_DIR")
            or os.environ.get("DIFFCTL_LOG_DIR")
            or os.path.join(os.path.expanduser("~"), ".ros", "log")
        )
