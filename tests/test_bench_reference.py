"""`python -m bench --reference` writes a results file git keeps, saying where its figures come from (issue 28):
the machine, the load at the start and the end, the dates, the commit, and how each budgeted figure is taken."""

from __future__ import annotations

import json
import subprocess
import sys
import types
from pathlib import Path

from bench import __main__ as bench_main
from bench.budget import BUDGET, HOW

REPO = Path(__file__).resolve().parents[1]


def test_every_budgeted_figure_says_how_it_is_taken() -> None:
    assert set(HOW) == set(BUDGET)
    assert all(len(text) > 20 for text in HOW.values())


def test_reference_file_records_its_provenance_and_is_not_ignored(tmp_path: Path, monkeypatch, capsys) -> None:
    fake = types.ModuleType("bench._reference_probe")
    fake.run = lambda: {"control_update_us": 42.0, "bus_rtt_p50_us": 220.0, "zenoh_raw_rtt_p50_us": 200.0}
    monkeypatch.setitem(sys.modules, "bench._reference_probe", fake)
    monkeypatch.setattr(bench_main, "RESULTS", tmp_path)

    assert bench_main.main(["--reference", "_reference_probe"]) == 0
    written = list(tmp_path.glob("reference-*.json"))
    assert len(written) == 1, capsys.readouterr().out
    doc = json.loads(written[0].read_text())
    assert doc["results"]["control_update_us"] == 42.0
    assert doc["results"]["bus_rtt_p50_vs_zenoh"] == 1.1  # derived in the same run
    assert doc["how"]["control_update_us"] == HOW["control_update_us"]
    assert doc["machine"]["cores"] >= 1 and doc["machine"]["cpu"]
    assert len(doc["load_avg_start"]) == 3 and len(doc["load_avg_end"]) == 3
    assert doc["other_programs_cores"] >= 0.0
    assert doc["when"].endswith("Z") and doc["ended"] >= doc["when"]
    assert any("partial run" in c for c in doc["caveats"])
    head = subprocess.run(["git", "-C", str(REPO), "rev-parse", "HEAD"], capture_output=True, text=True)
    if head.returncode == 0:
        assert doc["source"]["commit"] == head.stdout.strip()
        assert written[0].name == f"reference-{doc['when'][:10]}-{head.stdout.strip()[:10]}.json"
        # git keeps reference files and ignores every other results file
        kept = REPO / "bench" / "results" / written[0].name
        ignored = subprocess.run(["git", "-C", str(REPO), "check-ignore", "-q", str(kept)])
        assert ignored.returncode == 1
        latest = subprocess.run(["git", "-C", str(REPO), "check-ignore", "-q", str(REPO / "bench/results/latest.json")])
        assert latest.returncode == 0


def test_bench_refuses_an_unknown_option(capsys) -> None:
    assert bench_main.main(["--refrence"]) == 2
    assert "--refrence" in capsys.readouterr().err


def test_other_programs_are_the_machine_busy_time_less_the_runs_own() -> None:
    # the machine busy 3 CPU-s, the run itself 1 CPU-s, over 2 s of wall time: others used 1 core
    assert bench_main._other_cores((100.0, 10.0), (103.0, 11.0), 2.0) == 1.0
    # the run's own processes reaped late may count more than the machine's tick-rounded busy time
    assert bench_main._other_cores((100.0, 10.0), (100.5, 11.0), 2.0) == 0.0
    busy, own = bench_main._cpu_s()
    assert busy > 0 and own > 0
