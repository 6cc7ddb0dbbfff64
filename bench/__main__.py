"""`python -m bench [name ...]`: run the benchmarks, write bench/results/latest.json, print the budget table."""

from __future__ import annotations

import importlib
import json
import os
import platform
import sys
import time
import traceback
from pathlib import Path

from bench.budget import BUDGET, verdict

MODULES = ["bus", "launch", "control", "sim", "stack", "fleet", "client", "messages", "testing", "localization"]
RESULTS = Path(__file__).resolve().parent / "results"


def machine() -> dict:
    import psutil

    cpu = platform.processor() or ""
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return {"cpu": cpu, "cores": os.cpu_count(), "memory_gb": round(psutil.virtual_memory().total / 2**30, 1),
            "python": platform.python_version(), "kernel": platform.release()}


def _merged(doc: dict, names: list[str]) -> dict:
    """A partial run (`python -m bench sim`) keeps the other benchmarks' figures of the previous run: its own
    replace theirs, and the file says which keys came from which run."""
    try:
        old = json.loads((RESULTS / "latest.json").read_text())
    except (OSError, ValueError):
        return doc
    if not isinstance(old, dict) or not isinstance(old.get("results"), dict):
        return doc
    kept = {k: v for k, v in old["results"].items() if k not in doc["results"]}
    runs = dict(old.get("partial_runs") or {})
    for name in names:
        runs[name] = doc["when"]
    errors = {k: v for k, v in (old.get("errors") or {}).items() if k not in names} | doc["errors"]
    return doc | {"results": kept | doc["results"], "errors": errors, "partial_runs": runs}


def main(argv: list[str]) -> int:
    from diffctl.console import make_console, table

    console = make_console(sys.stdout, width=150)

    names = argv or MODULES
    results: dict[str, object] = {}
    errors: dict[str, str] = {}
    for name in names:
        try:
            mod = importlib.import_module(f"bench.{name}")
        except ModuleNotFoundError as e:
            errors[name] = f"not available: {e}"
            continue
        console.print(f"running bench/{name}.py …", markup=False)
        t0 = time.monotonic()
        try:
            results.update(mod.run())
        except Exception as e:
            errors[name] = f"{type(e).__name__}: {e}"
            traceback.print_exc()
        console.print(f"  done in {time.monotonic() - t0:.1f} s", markup=False)
    RESULTS.mkdir(parents=True, exist_ok=True)
    doc = {"when": time.strftime("%Y-%m-%dT%H:%M:%S%z"), "machine": machine(), "results": results,
           "errors": errors}
    if argv:
        doc = _merged(doc, names)
    (RESULTS / "latest.json").write_text(json.dumps(doc, indent=2) + "\n")
    rows = []
    for key, (op, limit, label) in BUDGET.items():
        value = results.get(key)
        rows.append((label, key, f"{op} {limit:g}", "—" if value is None else f"{value:g}", verdict(value, op, limit)))
    console.print(table("diffctl benchmarks vs. budget (ARCHITECTURE.md)", ["what", "metric", "budget", "measured",
                                                                          ""], rows))
    extra = {k: v for k, v in results.items() if k not in BUDGET}
    if extra:
        console.print(table("other figures", ["metric", "value"], sorted(extra.items())))
    for name, err in errors.items():
        console.print(f"bench/{name}: {err}", markup=False)
    console.print(f"machine: {doc['machine']}\nwritten: {RESULTS / 'latest.json'}", markup=False)
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
