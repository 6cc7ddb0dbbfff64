"""A package's install layout from its CMakeLists.txt `install()` rules: `<dest>/<file>` → source file.

Follows CMake's semantics (see reference/workspace_urdf.md §2): `DIRECTORY dir` installs `dir` itself
under DESTINATION, `DIRECTORY dir/` only its contents; `FILES_MATCHING` keeps files matched by a
`PATTERN` (a glob on the name) or `REGEX` (on the full path); `PATTERN … EXCLUDE` drops files and whole
subtrees; `FILES`/`PROGRAMS` install files (RENAME for one). Targets are not built, so `TARGETS`,
`EXPORT`, `CODE` and `SCRIPT` install nothing here. `ament_package()` adds package.xml to the share dir.
"""

from __future__ import annotations

import fnmatch
import os
import posixpath
import re
from dataclasses import dataclass, field
from pathlib import Path

from diffctl.workspace.cmake_script import PREFIX_SENTINEL, Call, Script

# Keywords that end the list of sources of install(FILES|PROGRAMS|DIRECTORY …).
_FILE_KEYWORDS = {
    "DESTINATION",
    "TYPE",
    "PERMISSIONS",
    "CONFIGURATIONS",
    "COMPONENT",
    "RENAME",
    "OPTIONAL",
    "EXCLUDE_FROM_ALL",
}
_DIR_KEYWORDS = {
    "DESTINATION",
    "TYPE",
    "FILE_PERMISSIONS",
    "DIRECTORY_PERMISSIONS",
    "USE_SOURCE_PERMISSIONS",
    "OPTIONAL",
    "MESSAGE_NEVER",
    "CONFIGURATIONS",
    "COMPONENT",
    "EXCLUDE_FROM_ALL",
    "FILES_MATCHING",
    "PATTERN",
    "REGEX",
}
_AMENT_AUTO_KEYWORDS = {"INSTALL_TO_PATH", "INSTALL_TO_SHARE", "CONFIG_EXTRAS", "USE_SCOPED_HEADER_INSTALL_DIR"}
# install(… TYPE X) without DESTINATION: CMake's default directories.
_TYPE_DESTINATIONS = {
    "BIN": "bin",
    "SBIN": "sbin",
    "LIB": "lib",
    "INCLUDE": "include",
    "SYSCONF": "etc",
    "DATA": "share",
    "DOC": "share/doc",
}


@dataclass(frozen=True)
class InstalledFile:
    destination: str  # posix path relative to the install prefix, e.g. share/demo/launch/a.launch.py
    source: Path
    program: bool = False  # installed with PROGRAMS (mode 755)


@dataclass
class InstallIndex:
    files: dict[str, InstalledFile] = field(default_factory=dict)
    problems: list[str] = field(default_factory=list)  # rules that install nothing, one line each
    # ament_python console scripts: executable name → "module:function" (installed to lib/<pkg>/<name>)
    console_scripts: dict[str, str] = field(default_factory=dict)

    def add(self, destination: str, source: Path, program: bool = False) -> None:
        # A later rule installing to the same place overwrites the earlier one, as at install time.
        self.files[destination] = InstalledFile(destination, source, program)

    def under(self, prefix: str) -> dict[str, InstalledFile]:
        start = prefix.rstrip("/") + "/"
        return {d: f for d, f in self.files.items() if d.startswith(start)}


@dataclass(frozen=True)
class _Match:
    regex: re.Pattern[str] | None
    glob: str | None
    exclude: bool

    def matches(self, full_path: str) -> bool:
        if self.regex is not None:
            return self.regex.search(full_path) is not None
        # CMake matches PATTERN against the end of the full path after a '/': the name, or a tail of it.
        return fnmatch.fnmatchcase(full_path, "*/" + str(self.glob))


def _sources(args: list[str], keywords: set[str]) -> tuple[list[str], list[str]]:
    for i, a in enumerate(args):
        if a in keywords:
            return args[:i], args[i:]
    return args, []


def _option(rest: list[str], key: str) -> str | None:
    if key in rest:
        i = rest.index(key)
        if i + 1 < len(rest):
            return rest[i + 1]
    return None


class _Collector:
    def __init__(self, package_dir: Path, package_name: str, index: InstallIndex) -> None:
        self.package_dir = package_dir
        self.package_name = package_name
        self.index = index

    def where(self, call: Call) -> str:
        try:
            rel = call.source.relative_to(self.package_dir)
        except ValueError:
            rel = call.source
        return f"{rel}:{call.line}"

    def __call__(self, call: Call) -> None:
        if call.name in ("ament_package", "ament_auto_package"):
            manifest = self.package_dir / "package.xml"
            if manifest.is_file():
                self.index.add(f"share/{self.package_name}/package.xml", manifest)
            if call.name == "ament_auto_package" and "INSTALL_TO_SHARE" in call.args:
                # ament_cmake_auto: INSTALL_TO_SHARE dirs… is install(DIRECTORY dirs… DESTINATION share/<pkg>)
                start = call.args.index("INSTALL_TO_SHARE") + 1
                dirs, _ = _sources(call.args[start:], _AMENT_AUTO_KEYWORDS)
                self._directories(call, [*dirs, "DESTINATION", f"share/{self.package_name}"])
        elif call.name == "install" and call.args:
            kind, args = call.args[0], call.args[1:]
            if kind in ("FILES", "PROGRAMS"):
                self._files(call, args, program=kind == "PROGRAMS")
            elif kind == "DIRECTORY":
                self._directories(call, args)

    def destination(self, call: Call, rest: list[str]) -> str | None:
        dest = _option(rest, "DESTINATION")
        if dest is None:
            type_ = _option(rest, "TYPE")
            dest = _TYPE_DESTINATIONS.get(type_ or "")
            if dest is None:
                self.index.problems.append(f"{self.where(call)}: install() has no DESTINATION")
                return None
        if dest.startswith(PREFIX_SENTINEL):
            dest = dest[len(PREFIX_SENTINEL) :].lstrip("/") or "."
        if "$<" in dest or os.path.isabs(dest):
            self.index.problems.append(f"{self.where(call)}: DESTINATION {dest} is outside the install prefix")
            return None
        dest = posixpath.normpath(dest.replace("\\", "/"))
        if dest == ".." or dest.startswith("../"):
            self.index.problems.append(f"{self.where(call)}: DESTINATION {dest} is outside the install prefix")
            return None
        return "" if dest == "." else dest

    def _files(self, call: Call, args: list[str], *, program: bool) -> None:
        sources, rest = _sources(args, _FILE_KEYWORDS)
        dest = self.destination(call, rest)
        if dest is None:
            return
        rename = _option(rest, "RENAME")
        if rename is not None and len(sources) != 1:
            self.index.problems.append(f"{self.where(call)}: RENAME needs exactly one file")
            return
        for s in sources:
            path = Path(s) if os.path.isabs(s) else call.current_dir / s
            if not path.is_file():
                if "OPTIONAL" not in rest:
                    what = "is a directory (use install(DIRECTORY))" if path.is_dir() else "does not exist"
                    self.index.problems.append(f"{self.where(call)}: {s} {what}")
                continue
            self.index.add(posixpath.join(dest, rename or path.name), path, program)

    def _directories(self, call: Call, args: list[str]) -> None:
        sources, rest = _sources(args, _DIR_KEYWORDS)
        dest = self.destination(call, rest)
        if dest is None:
            return
        matches, files_matching = _patterns(rest)
        for s in sources:
            path = Path(s) if os.path.isabs(s) else call.current_dir / s
            if not path.is_dir():
                if "OPTIONAL" not in rest:
                    self.index.problems.append(f"{self.where(call)}: directory {s} does not exist")
                continue
            # `dir` installs the directory itself, `dir/` only what it holds.
            base = dest if s.endswith("/") else posixpath.join(dest, Path(os.path.normpath(s)).name)
            self._tree(path, base, matches, files_matching)

    def _tree(self, root: Path, base: str, matches: list[_Match], files_matching: bool) -> None:
        for dirpath, dirnames, filenames in os.walk(root, followlinks=True):
            full_dir = dirpath.replace(os.sep, "/")
            dirnames[:] = sorted(
                d for d in dirnames if not any(m.exclude and m.matches(f"{full_dir}/{d}") for m in matches)
            )
            rel_dir = os.path.relpath(dirpath, root)
            for name in sorted(filenames):
                full = f"{full_dir}/{name}"
                hits = [m for m in matches if m.matches(full)]
                if any(m.exclude for m in hits):
                    continue
                if files_matching and not hits:
                    continue
                rel = name if rel_dir == "." else posixpath.join(rel_dir.replace(os.sep, "/"), name)
                self.index.add(posixpath.normpath(posixpath.join(base, rel)), Path(dirpath) / name)


def _patterns(rest: list[str]) -> tuple[list[_Match], bool]:
    matches: list[_Match] = []
    files_matching = "FILES_MATCHING" in rest
    i = 0
    while i < len(rest):
        word = rest[i]
        if word in ("PATTERN", "REGEX") and i + 1 < len(rest):
            value = rest[i + 1]
            exclude = i + 2 < len(rest) and rest[i + 2] == "EXCLUDE"
            try:
                regex = re.compile(value) if word == "REGEX" else None
            except re.error:
                regex = re.compile(re.escape(value))
            matches.append(_Match(regex, value if word == "PATTERN" else None, exclude))
            i += 3 if exclude else 2
        else:
            i += 1
    return matches, files_matching


def cmake_install_index(package_dir: Path, package_name: str) -> InstallIndex:
    """The files the package's CMakeLists.txt would install, keyed by destination under the prefix."""
    index = InstallIndex()
    lists = package_dir / "CMakeLists.txt"
    if lists.is_file():
        collector = _Collector(package_dir, package_name, index)
        Script(package_dir, collector).run_file(lists)
    return index
