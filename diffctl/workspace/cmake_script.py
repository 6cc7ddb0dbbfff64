"""Just enough of the CMake language to read a package's `install()` calls without running CMake.

Reads commands (comments, quoted, bracket and unquoted arguments, multi-line calls), expands `${VAR}`
and `$ENV{VAR}`, and follows what install rules usually depend on: `project()`, `set()`/`unset()`,
`list(APPEND)`, `file(GLOB[_RECURSE])`, `foreach()`, `add_subdirectory()` and GNUInstallDirs' names.
Both branches of an `if()` are read (nothing is configured here); function and macro bodies are not.
"""

from __future__ import annotations

import glob
import os
import re
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from diffctl.errors import ConfigError

# Stands for ${CMAKE_INSTALL_PREFIX}: a destination starting with it is relative to the prefix.
PREFIX_SENTINEL = "\x00prefix"

GNU_INSTALL_DIRS = {
    "CMAKE_INSTALL_BINDIR": "bin",
    "CMAKE_INSTALL_SBINDIR": "sbin",
    "CMAKE_INSTALL_LIBDIR": "lib",
    "CMAKE_INSTALL_LIBEXECDIR": "libexec",
    "CMAKE_INSTALL_INCLUDEDIR": "include",
    "CMAKE_INSTALL_DATAROOTDIR": "share",
    "CMAKE_INSTALL_DATADIR": "share",
    "CMAKE_INSTALL_SYSCONFDIR": "etc",
    "CMAKE_INSTALL_DOCDIR": "share/doc",
}

_IDENT = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
_BRACKET_OPEN = re.compile(r"\[(=*)\[")
_VAR_REF = re.compile(r"\$(ENV)?\{([^${}]*)\}")


@dataclass(frozen=True)
class Argument:
    text: str
    quoted: bool  # quoted and bracket arguments are one value each; unquoted ones split on ';'


@dataclass(frozen=True)
class Command:
    name: str  # lower case: CMake command names are case-insensitive
    args: tuple[Argument, ...]
    line: int


def _bracket_end(text: str, i: int, source: str, line: int) -> tuple[str, int]:
    """`text[i:]` starts with `[=*[`: the bracket content and the index after its closing `]=*]`."""
    m = _BRACKET_OPEN.match(text, i)
    assert m is not None
    close = "]" + m.group(1) + "]"
    end = text.find(close, m.end())
    if end < 0:
        raise ConfigError("unterminated bracket argument or comment", source=source, line=line)
    content = text[m.end() : end]
    if content.startswith("\n"):
        content = content[1:]
    return content, end + len(close)


def parse_commands(text: str, source: str) -> list[Command]:
    """The command invocations of a CMake file, in order; malformed text is one located ConfigError."""
    commands: list[Command] = []
    i, n, line = 0, len(text), 1
    while i < n:
        c = text[i]
        if c == "\n":
            line += 1
            i += 1
        elif c.isspace():
            i += 1
        elif c == "#":
            i, line = _skip_comment(text, i, source, line)
        else:
            m = _IDENT.match(text, i)
            if not m:
                raise ConfigError(f"unexpected {c!r} where a command was expected", source=source, line=line)
            name, start_line = m.group(0).lower(), line
            i = m.end()
            while i < n and text[i] in " \t":
                i += 1
            if i >= n or text[i] != "(":
                raise ConfigError(f"command {m.group(0)!r} is not followed by '('", source=source, line=line)
            args, i, line = _parse_args(text, i + 1, source, line)
            commands.append(Command(name, tuple(args), start_line))
    return commands


def _skip_comment(text: str, i: int, source: str, line: int) -> tuple[int, int]:
    """Past a `#` line comment or `#[[…]]` bracket comment starting at `i`: (next index, line there)."""
    if _BRACKET_OPEN.match(text, i + 1):
        _, j = _bracket_end(text, i + 1, source, line)
        return j, line + text.count("\n", i, j)
    j = text.find("\n", i)
    return (len(text) if j < 0 else j), line


def _parse_args(text: str, i: int, source: str, line: int) -> tuple[list[Argument], int, int]:
    args: list[Argument] = []
    depth, n, start_line = 0, len(text), line
    while i < n:
        c = text[i]
        if c == "\n":
            line += 1
            i += 1
        elif c.isspace():
            i += 1
        elif c == "(":
            depth += 1
            i += 1
        elif c == ")":
            if depth == 0:
                return args, i + 1, line
            depth -= 1
            i += 1
        elif c == "#":
            i, line = _skip_comment(text, i, source, line)
        elif c == '"':
            value, i, line = _quoted(text, i + 1, source, line)
            args.append(Argument(value, True))
        elif c == "[" and _BRACKET_OPEN.match(text, i):
            value, j = _bracket_end(text, i, source, line)
            line += text.count("\n", i, j)
            i = j
            args.append(Argument(value, True))
        else:
            out: list[str] = []
            while i < n and not text[i].isspace() and text[i] not in '()#"':
                if text[i] == "\\" and i + 1 < n:
                    # \; keeps a literal semicolon (no list split); other escapes give the character.
                    out.append("\\;" if text[i + 1] == ";" else _ESCAPES.get(text[i + 1], text[i + 1]))
                    i += 2
                else:
                    out.append(text[i])
                    i += 1
            args.append(Argument("".join(out), False))
    raise ConfigError("unbalanced '(': the call is never closed", source=source, line=start_line)


_ESCAPES = {"n": "\n", "t": "\t", "r": "\r"}


def _quoted(text: str, i: int, source: str, line: int) -> tuple[str, int, int]:
    out: list[str] = []
    n, start_line = len(text), line
    while i < n:
        c = text[i]
        if c == '"':
            return "".join(out), i + 1, line
        if c == "\\" and i + 1 < n:
            nxt = text[i + 1]
            if nxt == "\n":  # a line continuation
                line += 1
            else:
                out.append("\\;" if nxt == ";" else _ESCAPES.get(nxt, nxt))
            i += 2
            continue
        if c == "\n":
            line += 1
        out.append(c)
        i += 1
    raise ConfigError("unterminated quoted argument", source=source, line=start_line)


def split_list(value: str) -> list[str]:
    """A CMake list (';'-separated, '\\;' escaped) as items, empty items dropped."""
    items = re.split(r"(?<!\\);", value)
    return [item.replace("\\;", ";") for item in items if item]


@dataclass(frozen=True)
class Call:
    """A command whose arguments have been expanded, with the directory it was read in."""

    name: str
    args: list[str]
    line: int
    source: Path
    current_dir: Path


class Script:
    """Reads a CMakeLists.txt tree and hands each command it does not interpret itself to `on_call`."""

    def __init__(self, package_dir: Path, on_call: Callable[[Call], None]) -> None:
        self.package_dir = package_dir
        self.on_call = on_call
        self.variables: dict[str, str] = {
            "CMAKE_SOURCE_DIR": str(package_dir),
            "PROJECT_SOURCE_DIR": str(package_dir),
            "CMAKE_INSTALL_PREFIX": PREFIX_SENTINEL,
            **GNU_INSTALL_DIRS,
        }

    def run_file(self, path: Path, depth: int = 0) -> None:
        if depth > 16:
            raise ConfigError("add_subdirectory() nests more than 16 levels deep", source=str(path))
        try:
            text = path.read_text(encoding="utf-8", errors="replace")
        except OSError as e:
            raise ConfigError(f"cannot read: {e.strerror}", source=str(path)) from None
        saved = dict(self.variables)
        self.variables["CMAKE_CURRENT_SOURCE_DIR"] = str(path.parent)
        self.variables["CMAKE_CURRENT_LIST_DIR"] = str(path.parent)
        try:
            self._run(parse_commands(text, str(path)), path, depth)
        finally:
            # add_subdirectory gives the child its own scope: its set()s do not leak to the parent.
            if depth:
                self.variables = saved

    def expand(self, text: str) -> str:
        for _ in range(100):
            new = _VAR_REF.sub(self._lookup, text)
            if new == text:
                return new
            text = new
        return text

    def _lookup(self, m: re.Match[str]) -> str:
        if m.group(1):
            return os.environ.get(m.group(2), "")
        return self.variables.get(m.group(2), "")

    def _values(self, args: tuple[Argument, ...]) -> list[str]:
        out: list[str] = []
        for a in args:
            if a.quoted:
                out.append(self.expand(a.text).replace("\\;", ";"))
            else:
                out.extend(split_list(self.expand(a.text)))
        return out

    def _run(self, commands: list[Command], path: Path, depth: int) -> None:
        i = 0
        while i < len(commands):
            cmd = commands[i]
            if cmd.name in ("function", "macro"):
                i = _block_end(commands, i, cmd.name, "end" + cmd.name, path) + 1
                continue
            if cmd.name == "foreach":
                end = _block_end(commands, i, "foreach", "endforeach", path)
                self._foreach(cmd, commands[i + 1 : end], path, depth)
                i = end + 1
                continue
            self._command(cmd, path, depth)
            i += 1

    def _foreach(self, cmd: Command, body: list[Command], path: Path, depth: int) -> None:
        values = self._values(cmd.args)
        if not values:
            return
        var, rest = values[0], values[1:]
        if rest[:1] == ["RANGE"]:
            return  # numeric loops do not name files to install
        if rest[:1] == ["IN"]:
            items: list[str] = []
            mode = None
            for word in rest[1:]:
                if word in ("LISTS", "ITEMS"):
                    mode = word
                elif mode == "LISTS":
                    items.extend(split_list(self.variables.get(word, "")))
                else:
                    items.append(word)
            rest = items
        for item in rest:
            self.variables[var] = item
            self._run(body, path, depth)

    def _command(self, cmd: Command, path: Path, depth: int) -> None:
        values = self._values(cmd.args)
        current = Path(self.variables["CMAKE_CURRENT_SOURCE_DIR"])
        if cmd.name == "project" and values:
            self.variables.update(
                PROJECT_NAME=values[0], PROJECT_SOURCE_DIR=str(current), **{f"{values[0]}_SOURCE_DIR": str(current)}
            )
            # catkin's destinations, for packages still written against them
            self.variables.update(
                CATKIN_PACKAGE_SHARE_DESTINATION=f"share/{values[0]}",
                CATKIN_PACKAGE_BIN_DESTINATION=f"lib/{values[0]}",
                CATKIN_GLOBAL_SHARE_DESTINATION="share",
            )
        elif cmd.name == "set" and values:
            items = values[1:]
            if "PARENT_SCOPE" in items:
                return
            if "CACHE" in items:
                items = items[: items.index("CACHE")]
                if values[0] in self.variables:
                    return  # a cache entry does not override a normal variable
            self.variables[values[0]] = ";".join(items)
        elif cmd.name == "unset" and values:
            self.variables.pop(values[0], None)
        elif cmd.name == "list" and len(values) >= 2 and values[0] == "APPEND":
            old = split_list(self.variables.get(values[1], ""))
            self.variables[values[1]] = ";".join(old + values[2:])
        elif cmd.name == "file" and len(values) >= 2 and values[0] in ("GLOB", "GLOB_RECURSE"):
            self.variables[values[1]] = ";".join(_file_glob(values, current))
        elif cmd.name == "add_subdirectory" and values:
            sub = Path(values[0]) if os.path.isabs(values[0]) else current / values[0]
            lists = sub / "CMakeLists.txt"
            if lists.is_file():
                self.run_file(lists, depth + 1)
        else:
            self.on_call(Call(cmd.name, values, cmd.line, path, current))


def _file_glob(values: list[str], current: Path) -> list[str]:
    recurse = values[0] == "GLOB_RECURSE"
    relative: Path | None = None
    patterns: list[str] = []
    words = iter(values[2:])
    for w in words:
        if w == "RELATIVE":
            relative = Path(next(words, str(current)))
        elif w in ("LIST_DIRECTORIES", "FOLLOW_SYMLINKS", "CONFIGURE_DEPENDS"):
            if w == "LIST_DIRECTORIES":
                next(words, None)
        else:
            patterns.append(w)
    found: set[str] = set()
    for p in patterns:
        base = p if os.path.isabs(p) else str(current / p)
        if recurse:
            head, tail = os.path.split(base)
            matches = glob.glob(os.path.join(head, "**", tail), recursive=True)
        else:
            matches = glob.glob(base)
        found.update(m for m in matches if os.path.isfile(m))
    if relative is not None:
        return sorted(os.path.relpath(m, relative) for m in found)
    return sorted(found)


def _block_end(commands: list[Command], start: int, opener: str, closer: str, path: Path) -> int:
    depth = 0
    for j in range(start, len(commands)):
        if commands[j].name == opener:
            depth += 1
        elif commands[j].name == closer:
            depth -= 1
            if depth == 0:
                return j
    raise ConfigError(f"{opener}() is never closed by {closer}()", source=str(path), line=commands[start].line)
