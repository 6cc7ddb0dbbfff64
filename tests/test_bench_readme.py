"""The README's benchmark figures are the committed reference file's (issue 28): the table between its
`bench-table` markers is what `python -m bench.markdown` renders from that file, so no quoted figure can be
typed by hand or outlive a new reference run."""

from __future__ import annotations

import json
import re
import subprocess
from pathlib import Path

from bench.markdown import END, render

REPO = Path(__file__).resolve().parents[1]
MARKED = re.compile(r"<!-- bench-table: (?P<name>[^ ]+) -->.*?" + re.escape(END), re.S)


def test_readme_table_is_rendered_from_a_committed_reference_file() -> None:
    readme = (REPO / "README.md").read_text()
    blocks = list(MARKED.finditer(readme))
    assert len(blocks) == 1, "README.md must hold one bench-table block"
    name = blocks[0]["name"]
    assert re.fullmatch(r"reference-\d{4}-\d\d-\d\d-[0-9a-f]{10}\.json", name), name
    path = REPO / "bench" / "results" / name
    doc = json.loads(path.read_text())
    assert blocks[0][0] == render(doc, name), "README's table differs from `python -m bench.markdown " \
        f"bench/results/{name}`: paste its output between the markers"
    assert not doc["source"]["dirty"] and not doc["errors"]
    tracked = subprocess.run(["git", "-C", str(REPO), "ls-files", "--error-unmatch", str(path)],
                             capture_output=True)
    if (REPO / ".git").exists():
        assert tracked.returncode == 0, f"{path} is not committed"
