"""The `$(name arg …)` syntax of the YAML and XML frontends: text → substitution objects.

Arguments are separated by spaces, may be quoted with '…' or "…", and may nest `$(…)`; inside them a
backslash escapes any character (`\\'` in a '…' argument); anywhere, `\\$(` is a literal `$(`. Every
name maps to a substitution class of substitutions.py / logic_substitutions.py.
"""

from __future__ import annotations

from typing import Any

from diffctl.errors import LaunchError, suggest
from diffctl.launch_legacy.logic_substitutions import (
    AllSubstitution,
    AndSubstitution,
    AnySubstitution,
    EqualsSubstitution,
    IfElseSubstitution,
    NotEqualsSubstitution,
    NotSubstitution,
    OrSubstitution,
)
from diffctl.launch_legacy.substitutions import (
    AnonName,
    Command,
    EnvironmentVariable,
    ExecutableInPackage,
    FileContent,
    FindExecutable,
    FindPackagePrefix,
    FindPackageShare,
    LaunchConfiguration,
    LaunchLogDir,
    PythonExpression,
    SomeSubstitutions,
    Substitution,
    TextSubstitution,
    ThisLaunchFile,
    ThisLaunchFileDir,
)


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


def _make_eval(args: list[tuple[Substitution, ...]], quoted: list[bool]) -> Substitution:
    # `$(eval 'expr' 'math,os')`: a quoted expression may be followed by the modules it uses. Unquoted,
    # `$(eval 1 + 2)` splits into several arguments; the expression is all of them.
    _arity("eval", args, 1, 99)
    if len(args) == 2 and quoted[0]:
        return PythonExpression(args[0], python_modules=args[1])
    joined: list[Substitution] = []
    for i, part in enumerate(args):
        joined += ([TextSubstitution(" ")] if i else []) + list(part)
    return PythonExpression(joined)


def _one(name: str, make: Any) -> Any:
    def build(args: list[tuple[Substitution, ...]]) -> Substitution:
        _arity(name, args, 1, 1)
        return make(args[0])

    return build


def _two(name: str, make: Any) -> Any:
    def build(args: list[tuple[Substitution, ...]]) -> Substitution:
        _arity(name, args, 2, 2)
        return make(args[0], args[1])

    return build


def _make_if(args: list[tuple[Substitution, ...]]) -> Substitution:
    _arity("if", args, 2, 3)
    return IfElseSubstitution(args[0], args[1], args[2] if len(args) > 2 else "")


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
    "eval": None,  # built by the parser, which knows which arguments were quoted
    "anon": lambda a: (_arity("anon", a, 1, 1), AnonName(a[0]))[1],
    "command": lambda a: (_arity("command", a, 1, 2), Command(a[0], a[1] if len(a) > 1 else "fail"))[1],
    "file-content": _make_file_content,
    "find-exec": _one("find-exec", lambda n: FindExecutable(name=n)),
    "find-pkg-prefix": _one("find-pkg-prefix", FindPackagePrefix),
    "exec-in-pkg": _two("exec-in-pkg", ExecutableInPackage),
    "not": _one("not", NotSubstitution),
    "and": _two("and", AndSubstitution),
    "or": _two("or", OrSubstitution),
    "all": lambda a: (_arity("all", a, 1, 99), AllSubstitution(*a))[1],
    "any": lambda a: (_arity("any", a, 1, 99), AnySubstitution(*a))[1],
    "equals": _two("equals", EqualsSubstitution),
    "not-equals": _two("not-equals", NotEqualsSubstitution),
    "if": _make_if,
    "param": lambda a: _ros_param(a),
    "launch_log_dir": lambda a: (_arity("launch_log_dir", a, 0, 0), LaunchLogDir())[1],
    "log_dir": lambda a: (_arity("log_dir", a, 0, 0), LaunchLogDir())[1],
}


def _ros_param(args: list[tuple[Substitution, ...]]) -> Substitution:
    from diffctl.launch_legacy.ros_substitutions import from_frontend  # launch_ros's, registered as its frontend does

    return from_frontend(args)


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
            if c == "\\" and stop and self.i + 1 < len(self.text):
                # Inside a substitution's arguments a backslash escapes any character, as in launch's grammar:
                # $(eval '\'$(var mode)\' == \'sim\''). Outside, text is kept as written (regexes, paths).
                buf.append(self.text[self.i + 1])
                self.i += 2
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
        quoted: list[bool] = []
        while True:
            while self.i < len(self.text) and self.text[self.i].isspace():
                self.i += 1
            if self.i >= len(self.text):
                self.i = start
                raise self.error("unterminated $(")
            if self.text[self.i] == ")":
                self.i += 1
                break
            quoted.append(self.text[self.i] in "'\"")
            args.append(self.parse_argument())
        if name not in SUBSTITUTIONS:
            raise LaunchError(
                f"unknown substitution $({name}){suggest(name, SUBSTITUTIONS)}",
                hint="valid: " + ", ".join(f"$({n})" for n in SUBSTITUTIONS),
            )
        if name == "eval":
            return _make_eval(args, quoted)
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
