"""`ament_copyright`'s check: every source file starts with a copyright notice and a known license's notice.

As Jazzy's ament_copyright decides it: files ending in a C/C++/CMake/Python extension under the given paths
(not in folders starting with `.` or `_`, not below an `AMENT_IGNORE`, not a `setup.py` beside a package.xml);
past a shebang/coding line and blank lines, the first `#`/`//`/`///` comment block (else the first `/* */` or
`<!-- -->` block) must hold `Copyright [(c)] YEAR[-YEAR][, …] HOLDER` lines followed by a license notice of
`license_notices.LICENSES` (whitespace-insensitive, parts in order). A repository root (`.git`/`.hg`) also needs
`LICENSE` and `CONTRIBUTING.md` naming a known license. Empty files pass. Returns 0, or 1 on any error.
"""

from __future__ import annotations

import argparse
import glob
import os
import re
import sys
import time
from dataclasses import dataclass, field
from xml.sax.saxutils import quoteattr

from diffctl.testing.license_notices import COPYRIGHT_NAMES, LICENSES

EXTENSIONS = ("c", "cc", "cpp", "cxx", "h", "hh", "hpp", "hxx", "cmake", "py")
UNKNOWN = "<unknown>"
SOURCE, CONTRIBUTING, LICENSE = "source", "CONTRIBUTING.md", "LICENSE"

_YEARS = r"(?:\d{4}-\d{4}|\d{4})"
_COPYRIGHT_LINE = re.compile(
    rf"^[^\n\r]?\s*(?:\\copyright\s*)?copyright(?:\s+\(c\))?\s+({_YEARS}(?:,\s*{_YEARS})*),?\s+([^\n\r]+)$",
    re.IGNORECASE | re.MULTILINE | re.DOTALL)


@dataclass
class Checked:
    path: str
    kind: str
    exists: bool = True
    content: str = ""
    copyrights: list[tuple[str, str]] = field(default_factory=list)  # (holder, years)
    license: str = UNKNOWN


def _flat(text: str) -> str:
    return " ".join(text.split())


def _matches_in_order(content: str, template: str) -> bool:
    last = -1
    for part in re.split(r"\{copyright_holder\}|\{copyright\}", _flat(template)):
        if not part.strip():
            continue
        at = content.find(part.strip())
        if at <= last:  # missing (-1) or out of order
            return False
        last = at
    return True


def identify_header_license(text: str) -> str:
    flat = _flat(text)
    for key, lic in LICENSES.items():
        if any(_matches_in_order(flat, t) for t in lic.file_headers):
            return key
    return UNKNOWN


def _line_end(content: str, index: int) -> int:
    ends = [i for i in (content.find("\n", index), content.find("\r", index)) if i != -1]
    if not ends:
        return len(content)
    end = min(ends)
    return end + 2 if content.startswith("\r\n", end) else end + 1


def _start_of_header(content: str) -> int:
    index = 0
    # shebang and coding lines are not the header (a BOM may come first)
    while index < len(content):
        at = 1 if index == 0 and content.startswith("\ufeff") else index
        line = content[index:_line_end(content, index)]
        if content.startswith(("#", "//"), at) and (
                content.startswith("#!", at) or "coding=" in line or "coding:" in line):
            index = _line_end(content, index)
            continue
        break
    while index < len(content) and _line_end(content, index) == index + 1:
        index += 1
    return index


def _comment_block(content: str, index: int) -> str | None:
    match = re.compile(r"^\ufeff?(#|///|//)", re.MULTILINE).search(content, index)
    if not match:
        return None
    token, start = match.group(1), match.start(1)
    end = start
    while True:
        end = _line_end(content, end)
        if content[end:end + len(token)] != token:
            break
    return "\n".join(line[len(token) + 1:] for line in content[start:end].splitlines())


def _multiline_block(content: str, index: int) -> str | None:
    for opening, closing in ((r"^\ufeff?(/[*])", r"([*]/)$"), (r"^\ufeff?(<!--)", r"(-->)$")):
        start = re.compile(opening, re.MULTILINE).search(content, index)
        end = re.compile(closing, re.MULTILINE).search(content, index)
        if not start or not end:
            continue
        lines = content[start.start(1):end.start(1)].splitlines()
        inner = lines if len(lines) == 1 else lines[1:] if len(lines) == 2 else lines[1:-1]
        if len(inner) > 1:
            prefix = os.path.commonprefix(inner)  # noqa: RUF071  (a text prefix such as " * ")
            inner = [line[len(prefix):] for line in inner]
        return "\n".join(inner)
    return None


def _copyright_lines(block: str | None) -> tuple[list[tuple[str, str]], str]:
    found: list[tuple[str, str]] = []
    rest = block or ""
    while block is not None:
        match = _COPYRIGHT_LINE.search(rest)
        if not match:
            break
        found.append((match.group(2), match.group(1)))
        rest = rest[match.end(2):]
    return found, rest


def check_file(path: str, kind: str) -> Checked:
    checked = Checked(path, kind, os.path.exists(path))
    if not checked.exists:
        return checked
    with open(path, encoding="utf-8") as f:
        checked.content = f.read()
    if not checked.content:
        return checked
    flat = _flat(checked.content)
    if kind == LICENSE:
        checked.license = next((k for k, lic in LICENSES.items() if _flat(lic.license_file) in flat), UNKNOWN)
    elif kind == CONTRIBUTING:
        checked.license = next((k for k, lic in LICENSES.items() if _flat(lic.contributing_file) in flat), UNKNOWN)
    else:
        start = _start_of_header(checked.content)
        found, rest = _copyright_lines(_comment_block(checked.content, start))
        if not found:
            found, rest = _copyright_lines(_multiline_block(checked.content, start))
        if found:
            checked.copyrights = found
            checked.license = identify_header_license("{copyright}" + rest)
    return checked


def _is_repository_root(path: str) -> bool:
    return os.path.exists(os.path.join(path, ".git")) or os.path.exists(os.path.join(path, ".hg"))


def _has_extension(name: str) -> bool:
    return os.path.splitext(name)[1] in {"." + e for e in EXTENSIONS}


def collect(paths: list[str], exclude_patterns: list[str]) -> dict[str, str]:
    excluded = {os.path.realpath(p) for pattern in exclude_patterns for p in glob.glob(pattern)}
    files: dict[str, str] = {}

    def repository_files(folder: str) -> None:
        files[os.path.join(folder, CONTRIBUTING)] = CONTRIBUTING
        files[os.path.join(folder, LICENSE)] = LICENSE

    for path in paths:
        if os.path.isdir(path):
            if _is_repository_root(path):
                repository_files(path)
            for folder, dirs, names in os.walk(path):
                if "AMENT_IGNORE" in dirs + names:
                    dirs[:] = []
                    continue
                if _is_repository_root(folder):
                    repository_files(folder)
                dirs[:] = sorted(d for d in dirs if d[0] not in "._")
                package_root = os.path.exists(os.path.join(folder, "package.xml"))
                for name in sorted(names):
                    if name == "setup.py" and package_root:
                        continue
                    full = os.path.join(folder, name)
                    if _has_extension(name) and os.path.realpath(full) not in excluded:
                        files[full] = SOURCE
        if os.path.isfile(path) and _has_extension(path) and os.path.realpath(path) not in excluded:
            files[path] = SOURCE
        if _is_repository_root(os.path.dirname(path)) and os.path.basename(path) in (CONTRIBUTING, LICENSE):
            files[path] = os.path.basename(path)
    return {os.path.normpath(p): kind for p, kind in files.items()}


def verdict(checked: Checked) -> tuple[bool, str]:
    """(error, message) for one file, as ament_copyright reports it."""
    if not checked.exists:
        return True, "file not found"
    if not checked.content:
        return checked.kind != SOURCE, "file empty"
    if checked.kind != SOURCE:
        return checked.license == UNKNOWN, checked.license
    if not checked.copyrights:
        return True, "could not find copyright notice"
    holders = ", ".join(f"{name} ({years})" if years else name for name, years in checked.copyrights)
    return checked.license == UNKNOWN, f"copyright={holders}, license={checked.license}"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="ament_copyright", description="Check code files for copyright and license information.")
    parser.add_argument("paths", nargs="*", default=[os.curdir], help="files or folders to check")
    parser.add_argument("--exclude", metavar="filename", nargs="*", default=[], dest="excludes")
    parser.add_argument("--verbose", action="store_true", help="show every file, not only the ones with errors")
    group = parser.add_mutually_exclusive_group()
    group.add_argument("--list-copyright-names", action="store_true")
    group.add_argument("--list-licenses", action="store_true")
    group.add_argument("--xunit-file", help="write a JUnit XML file")
    args = parser.parse_args(sys.argv[1:] if argv is None else argv)
    if args.list_copyright_names:
        for key in sorted(COPYRIGHT_NAMES):
            print(f"{key}: {COPYRIGHT_NAMES[key]}")
        return 0
    if args.list_licenses:
        for key in sorted(LICENSES):
            print(f"{key}: {LICENSES[key].name}")
        return 0
    started = time.time()
    files = collect(args.paths, args.excludes)
    if not files:
        print("No repository roots and files found")
    report = []
    for path in sorted(files):
        error, message = verdict(check_file(path, files[path]))
        if args.verbose or error:
            print(f"{path}: {message}", file=sys.stderr if error else sys.stdout)
        report.append((path, not error, message))
    errors = sum(1 for _, ok, _ in report if not ok)
    if errors:
        print(f"{errors} errors, checked {len(report)} files", file=sys.stderr)
    else:
        print(f"No problems found, checked {len(report)} files")
    if args.xunit_file:
        _write_xunit(args.xunit_file, report, time.time() - started)
    return 1 if errors else 0


def _write_xunit(path: str, report: list[tuple[str, bool, str]], seconds: float) -> None:
    name = os.path.basename(path).removesuffix(".xml").removesuffix(".xunit")
    suite = f"{os.path.basename(os.path.dirname(path))}.{name}"
    cases = []
    for file, ok, message in report:
        body = "" if ok else f"\n    <failure message={quoteattr(message)}/>\n  "
        cases.append(f'  <testcase name={quoteattr(file)} classname="{suite}">{body}</testcase>')
    failures = sum(1 for _, ok, _ in report if not ok)
    xml = (f'<?xml version="1.0" encoding="UTF-8"?>\n<testsuite name="{suite}" tests="{len(report)}" '
           f'failures="{failures}" time="{seconds:.3f}">\n' + "\n".join(cases) + "\n</testsuite>\n")
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    with open(path, "w", encoding="utf-8") as f:
        f.write(xml)
