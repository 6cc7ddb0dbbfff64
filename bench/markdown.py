"""`python -m bench.markdown FILE`: the README's benchmark table, rendered from one results file.

The README quotes its figures by pasting this output between its `bench-table` markers; a test renders the
committed reference file again and compares, so every quoted figure traces to a file with its machine, load,
date and commit, and a new reference run cannot leave stale figures behind."""

from __future__ import annotations

import json
import re
import sys
from pathlib import Path

from bench.budget import BUDGET, HOW, verdict

BEGIN = "<!-- bench-table: {name} -->"
END = "<!-- /bench-table -->"
_FLEET_ROW = re.compile(r"fleet_(rtf|rss_mb)_\d+")


def _figure(value: object) -> str:
    if not isinstance(value, (int, float)):
        return "not measured"
    if isinstance(value, float) and abs(value) < 10:
        return f"{value:.3g}"
    return f"{value:,.0f}" if abs(value) >= 1000 else f"{value:g}"


def provenance(doc: dict) -> str:
    """One sentence: when, where, under what load and from which commit the figures were taken."""
    m, src = doc["machine"], doc["source"]
    dirty = ", uncommitted changes" if src.get("dirty") else ""
    caveats = doc.get("caveats") or []
    said = ("; caveats: " + "; ".join(caveats)) if caveats else ""
    other = doc.get("other_programs_cores")
    other = "" if other is None else f", other programs {other} cores on average"
    return (f"{doc['when']}–{doc['ended']}, {m['cores']}-core {m['cpu']}, {m['memory_gb']} GiB, Python {m['python']}, "
            f"Linux {m['kernel']}; 1-minute load {doc['load_avg_start'][0]} at start, {doc['load_avg_end'][0]} at "
            f"end (its own processes included){other}; commit {str(src.get('commit'))[:10]}{dirty}{said}")


def render(doc: dict, name: str) -> str:
    """The table between its markers: one row per budget, with how its figure is taken."""
    results = doc.get("results") or {}
    lines = [BEGIN.format(name=name), "", f"From `bench/results/{name}` ({provenance(doc)}).", "",
             "| what | budget | measured | | how it is taken |", "|---|---|---|---|---|"]
    for key, (op, limit, label) in BUDGET.items():
        value = results.get(key)
        lines.append(f"| {label} (`{key}`) | {op} {limit:g} | {_figure(value)} | {verdict(value, op, limit)} "
                     f"| {HOW.get(key, '')} |")
    lines += _fleet(results)
    others = sorted((k, v) for k, v in results.items() if k not in BUDGET and not _FLEET_ROW.fullmatch(k))
    if others:
        lines += ["", "<details><summary>every other figure of the same run</summary>", "",
                  "| figure | value |", "|---|---|", *(f"| `{k}` | {_figure(v)} |" for k, v in others), "",
                  "</details>"]
    return "\n".join([*lines, "", END])


def _fleet(results: dict) -> list[str]:
    """Several cars in one world (bench/fleet.py): RTF and memory per fleet size."""
    sizes = sorted(int(k.rsplit("_", 1)[1]) for k in results if _FLEET_ROW.fullmatch(k) and "rtf" in k)
    one = results.get("fleet_rtf_1")
    if not sizes:
        return []
    rows = ["", "| cars | RTF at rtf 0 | × one car's | memory of the launch (PSS, MB) |", "|---|---|---|---|"]
    for n in sizes:
        rtf = results.get(f"fleet_rtf_{n}")
        ratio = _figure(rtf / one) if isinstance(rtf, (int, float)) and isinstance(one, (int, float)) and one else "—"
        rows.append(f"| {n} | {_figure(rtf)} | {ratio} | {_figure(results.get(f'fleet_rss_mb_{n}'))} |")
    return rows


def main(argv: list[str]) -> int:
    if len(argv) != 1:
        print("usage: python -m bench.markdown bench/results/<results file>.json", file=sys.stderr)
        return 2
    path = Path(argv[0])
    try:
        doc = json.loads(path.read_text())
    except (OSError, ValueError) as e:
        print(f"bench.markdown: {path}: {e}", file=sys.stderr)
        return 2
    print(render(doc, path.name))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
