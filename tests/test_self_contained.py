"""Tests run from the repository alone: none reads the project's sibling folders (../shared holds the seed and
reference texts the project was built from; a user's clone of the repository has no such folder)."""

from __future__ import annotations

import re
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
OUTSIDE = re.compile(r"""\.\./shared|/work/shared|["']shared["']\s*/|parent\s*/\s*["']shared""")


def test_no_test_or_benchmark_reads_files_outside_the_repository() -> None:
    offenders = [
        f"{path.relative_to(REPO)}:{n}: {line.strip()}"
        for folder in ("tests", "bench")
        for path in sorted((REPO / folder).rglob("*.py"))
        if path != Path(__file__).resolve()
        for n, line in enumerate(path.read_text().splitlines(), 1)
        if OUTSIDE.search(line)
    ]
    assert offenders == [], "copy what these need into tests/ (data files):\n" + "\n".join(offenders)
