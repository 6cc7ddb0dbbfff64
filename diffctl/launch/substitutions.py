"""Substitutions: values computed when a launch description is resolved (`$(var x)`, LaunchConfiguration, …).

The same classes back both frontends: the YAML frontend parses `$(name arg …)` strings into them with
`parse()`, the Python frontend constructs them directly (LaunchConfiguration, PathJoinSubstitution, …).
Everything is evaluated against a `Scope` (see context.py) by `perform(value, scope)`.
"""

from __future__ import annotations

import builtins
import math
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
    from diffctl.launch.context import Scope


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
        from diffctl.launch import package_index

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


# What `$(eval …)` may use: arithmetic, comparisons and a few pure builtins, plus `math`.
_EVAL_BUILTINS: dict[str, Any] = {
    name: getattr(builtins, name) for name in ("abs", "min", "max", "round", "int", "float", "str", "bool", "len")
}


class PythonExpression(Substitution):
    """`$(eval expr)`: a Python expression over `math` and basic builtins, evaluated to text."""

    def __init__(self, expression: SomeSubstitutions) -> None:
        self.expression = normalize(expression)

    def describe(self) -> str:
        return f"$(eval '{describe(self.expression)}')"

    def perform(self, scope: Scope) -> str:
        text = perform(self.expression, scope)
        namespace = {"__builtins__": _EVAL_BUILTINS, "math": math}
        namespace.update({k: getattr(math, k) for k in dir(math) if not k.startswith("_")})
        try:
            return str(eval(text, namespace))
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
        try:
            done = subprocess.run(shlex.split(text), capture_output=True, text=True, env=dict(scope.env), timeout=30)
        except (OSError, ValueError, subprocess.TimeoutExpired) as e:
            raise LaunchError(f"$(command {text}) could not run: {e}") from None
        if done.returncode != 0:
            raise LaunchError(f"$(command {text}) exited with code {done.returncode}: {done.stderr.strip()[:200]}")
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


class EqualsSubstitution(Substitution):
    def __init__(self, left: SomeSubstitutions, right: SomeSubstitutions) -> None:
        self.left, self.right = normalize(left), normalize(right)

    def perform(self, scope: Scope) -> str:
        return str(perform(self.left, scope) == perform(self.right, scope)).lower()


class NotSubstitution(Substitution):
    def __init__(self, value: SomeSubstitutions) -> None:
        self.value = normalize(value)

    def perform(self, scope: Scope) -> str:
        from diffctl.launch.conditions import truth

        return str(not truth(perform(self.value, scope), "not")).lower()


# ---- the `$(...)` parser of the YAML frontend ---------------------------------------------------------------


def _make_var(args: list[tuple[Substitution, ...]]) -> Substitution:
    _arity("var", args, 1, 2)
    return LaunchConfiguration(args[0], default=args[1] if len(args) > 1 else None)


def _make_env(args: list[tuple[Substitution, ...]]) -> Substitution:
    _arity("env", args, 1, 2)
    return EnvironmentVariable(args[0], default_value=args[1] if len(args) > 1 else None)


def _make_optenv(args: list[tuple[Substitution, ...]]) -> Substitution:
    _arity("optenv", args, 1, 2)
    return EnvironmentVariable(args[0], default_value=args[1] if len(args) > 1 else "")


def _make_file_content(args: list[tuple[Substitution, ...]]) -> Substitution:
    # Extra arguments are PLACEHOLDER=value pairs.
    if not args:
        _arity("file-content", args, 1, 99)
    replacements: dict[str, SomeSubstitutions] = {}
    for pair in args[1:]:
        head = pair[0] if pair else None
        if not isinstance(head, TextSubstitution) or "=" not in head.text:
            raise LaunchError("$(file-content PATH PLACEHOLDER=VALUE …): replacement must be PLACEHOLDER=VALUE")
        key, first = head.text.split("=", 1)
        replacements[key] = (TextSubstitution(first), *pair[1:])
    return FileContent(args[0], replacements)


def _make_eval(args: list[tuple[Substitution, ...]]) -> Substitution:
    # Unquoted `$(eval 1 + 2)` splits into several arguments; the expression is all of them.
    _arity("eval", args, 1, 99)
    joined: list[Substitution] = []
    for i, part in enumerate(args):
        joined += ([TextSubstitution(" ")] if i else []) + list(part)
    return PythonExpression(joined)


def _arity(name: str, args: list[Any], low: int, high: int) -> None:
    if not low <= len(args) <= high:
        want = str(low) if low == high else f"{low} to {high}"
        raise LaunchError(f"$({name}) takes {want} argument(s), got {len(args)}")


SUBSTITUTIONS: dict[str, Any] = {
    "var": _make_var,
    "env": _make_env,
    "optenv": _make_optenv,
    "find-pkg-share": lambda a: (_arity("find-pkg-share", a, 1, 1), FindPackageShare(a[0]))[1],
    "dirname": lambda a: (_arity("dirname", a, 0, 0), ThisLaunchFileDir())[1],
    "filename": lambda a: (_arity("filename", a, 0, 0), ThisLaunchFile())[1],
    "eval": _make_eval,
    "anon": lambda a: (_arity("anon", a, 1, 1), AnonName(a[0]))[1],
    "command": lambda a: (_arity("command", a, 1, 2), Command(a[0], a[1] if len(a) > 1 else "fail"))[1],
    "file-content": _make_file_content,
}


class _Parser:
    """Recursive descent over `text $(name arg 'quoted arg' $(nested)) text`."""

    def __init__(self, text: str) -> None:
        self.text = text
        self.i = 0

    def error(self, message: str) -> LaunchError:
        return LaunchError(f"{message} at character {self.i + 1} of {self.text!r}")

    def parse_text(self, stop: str = "") -> tuple[Substitution, ...]:
        parts: list[Substitution] = []
        buf: list[str] = []
        while self.i < len(self.text):
            c = self.text[self.i]
            if c == "\\" and self.text.startswith("\\$(", self.i):
                buf.append("$(")
                self.i += 3
                continue
            if self.text.startswith("$(", self.i):
                if buf:
                    parts.append(TextSubstitution("".join(buf)))
                    buf = []
                parts.append(self.parse_substitution())
                continue
            if c in stop:
                break
            buf.append(c)
            self.i += 1
        if buf:
            parts.append(TextSubstitution("".join(buf)))
        return tuple(parts)

    def parse_substitution(self) -> Substitution:
        start = self.i
        self.i += 2
        name_start = self.i
        while self.i < len(self.text) and not self.text[self.i].isspace() and self.text[self.i] != ")":
            self.i += 1
        name = self.text[name_start : self.i]
        args: list[tuple[Substitution, ...]] = []
        while True:
            while self.i < len(self.text) and self.text[self.i].isspace():
                self.i += 1
            if self.i >= len(self.text):
                self.i = start
                raise self.error("unterminated $(")
            if self.text[self.i] == ")":
                self.i += 1
                break
            args.append(self.parse_argument())
        if name not in SUBSTITUTIONS:
            raise LaunchError(
                f"unknown substitution $({name}){suggest(name, SUBSTITUTIONS)}",
                hint="valid: " + ", ".join(f"$({n})" for n in SUBSTITUTIONS),
            )
        return SUBSTITUTIONS[name](args)

    def parse_argument(self) -> tuple[Substitution, ...]:
        c = self.text[self.i]
        if c in "'\"":
            self.i += 1
            inner = self.parse_text(stop=c)
            if self.i >= len(self.text):
                raise self.error(f"unterminated quote {c}")
            self.i += 1
            return inner or (TextSubstitution(""),)
        return self.parse_text(stop=" \t\n)")


def parse(text: str) -> tuple[Substitution, ...]:
    """A YAML string with `$(...)` substitutions → a tuple of substitutions (plain text → one TextSubstitution)."""
    if "$(" not in text:
        return (TextSubstitution(text),)
    p = _Parser(text)
    parts = p.parse_text()
    return parts or (TextSubstitution(""),)
