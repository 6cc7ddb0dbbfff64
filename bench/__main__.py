"""`python -m bench [--reference] [name ...]`: run the benchmarks, write bench/results/latest.json, print the budget
table.

Every results file says where its figures come from: the machine (CPU model, core count, memory, kernel, Python),
the load average at the start and at the end of the run, the UTC start and end, and the git commit measured
(with `dirty: true` when the work tree had uncommitted changes), and beside the figures how each budgeted one is
taken (`how`, from bench/budget.py). `--reference` also writes bench/results/reference-<UTC date>-<commit>.json,
the one kind of results file git keeps: the README's figures cite such a file. A reference is a whole run (no
module names) of a clean checkout, on a machine as quiet as can be had; the run says so when it was not.
"""

from __future__ import annotations

import importlib
import json
import os
import platform
import subprocess
import sys
import time
import traceback
from pathlib import Path

from bench.budget import BUDGET, HOW, derived, verdict

MODULES = ["bus", "launch", "control", "sim", "stack", "fleet", "client", "messages", "testing", "localization"]
RESULTS = Path(__file__).resolve().parent / "results"
REPO = RESULTS.parent.parent
USAGE = ("usage: python -m bench [--reference] [name ...]\n  name: a module of bench/ with a run() (all of "
         + ", ".join(MODULES) + " by default)\n  --reference: also write bench/results/reference-<date>-<commit>.json")


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
            "python": platform.python_version(), "kernel": platform.release(), "host": platform.node()}


def _load() -> list[float]:
    """The 1, 5 and 15 minute load averages."""
    return [round(x, 2) for x in os.getloadavg()]


def _cpu_s() -> tuple[float, float]:
    """(CPU seconds the whole machine has spent busy since boot, CPU seconds of this run: this process and the
    children it has reaped, theirs included). Their difference over a run is what other programs took: the
    load average at the end counts the benchmarks' own processes, so it cannot tell a quiet machine."""
    import resource

    fields = Path("/proc/stat").read_text().split("\n", 1)[0].split()[1:]
    ticks = [int(x) for x in fields]
    busy = sum(ticks) - ticks[3] - (ticks[4] if len(ticks) > 4 else 0)  # all but idle and iowait
    own = sum(resource.getrusage(who).ru_utime + resource.getrusage(who).ru_stime
              for who in (resource.RUSAGE_SELF, resource.RUSAGE_CHILDREN))
    return busy / os.sysconf("SC_CLK_TCK"), own


def _other_cores(start: tuple[float, float], end: tuple[float, float], wall_s: float) -> float:
    """Cores' worth of CPU that programs outside this run used on average between `start` and `end` (an upper
    bound: a benchmark's process left unreaped counts as another program)."""
    return round(max(0.0, (end[0] - start[0]) - (end[1] - start[1])) / max(wall_s, 1e-9), 2)


def source() -> dict:
    """The commit measured, and whether the work tree differed from it (bench/results aside)."""
    def git(*args: str) -> str:
        r = subprocess.run(["git", "-C", str(REPO), *args], capture_output=True, text=True, timeout=30)
        return r.stdout.strip() if r.returncode == 0 else ""

    commit = git("rev-parse", "HEAD")
    changed = [ln for ln in git("status", "--porcelain", "--untracked-files=no").splitlines()
               if not ln[3:].startswith("bench/results/")]
    return {"commit": commit or None, "branch": git("rev-parse", "--abbrev-ref", "HEAD") or None,
            "dirty": bool(changed)}


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

    console = make_console(sys.stdout, width=170)
    reference = "--reference" in argv
    argv = [a for a in argv if a != "--reference"]
    if "-h" in argv or "--help" in argv:
        print(USAGE)
        return 0
    unknown = [a for a in argv if a.startswith("-")]
    if unknown:
        print(f"bench: unknown benchmark or option {unknown[0]!r}\n{USAGE}", file=sys.stderr)
        return 2
    names = argv or MODULES
    started = {"when": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()), "load_avg": _load(), "cpu": _cpu_s(),
               "t": time.monotonic()}
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
    results.update(derived(results))
    RESULTS.mkdir(parents=True, exist_ok=True)
    doc = {"when": started["when"], "ended": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
           "load_avg_start": started["load_avg"], "load_avg_end": _load(),
           "other_programs_cores": _other_cores(started["cpu"], _cpu_s(), time.monotonic() - started["t"]),
           "machine": machine(),
           "source": source(), "modules": names, "results": results, "errors": errors,
           "how": {k: v for k, v in HOW.items() if k in results}}
    if argv:
        doc = _merged(doc, names)
    (RESULTS / "latest.json").write_text(json.dumps(doc, indent=2) + "\n")
    rows = []
    for key, (op, limit, label) in BUDGET.items():
        value = results.get(key)
        rows.append((label, key, f"{op} {limit:g}", "—" if value is None else f"{value:g}", verdict(value, op, limit),
                     HOW.get(key, "")))
    console.print(table("diffctl benchmarks vs. budget (ARCHITECTURE.md)", ["what", "metric", "budget", "measured",
                                                                          "", "how"], rows))
    extra = {k: v for k, v in results.items() if k not in BUDGET}
    if extra:
        console.print(table("other figures", ["metric", "value"], sorted(extra.items())))
    for name, err in errors.items():
        console.print(f"bench/{name}: {err}", markup=False)
    console.print(f"machine: {doc['machine']}\nload average (1, 5, 15 min) at start {doc['load_avg_start']}, at end "
                  f"{doc['load_avg_end']} (the run's own processes included); other programs used "
                  f"{doc['other_programs_cores']} cores on average\nsource: {doc['source']}\n"
                  f"written: {RESULTS / 'latest.json'}", markup=False)
    if reference:
        path = write_reference(doc, console)
        console.print(f"reference: {path}", markup=False)
    return 1 if errors else 0


def write_reference(doc: dict, console: object) -> Path:
    """bench/results/reference-<date>-<commit>.json from a run's document; what makes it a weak reference
    (a partial run, a dirty tree, a busy machine, failed benchmarks) is written into it and said."""
    caveats = []
    if doc.get("partial_runs") or set(doc["modules"]) != set(MODULES):
        caveats.append("partial run: not every benchmark ran in this run (see partial_runs)")
    if doc["source"]["dirty"]:
        caveats.append("the work tree had uncommitted changes")
    cores = doc["machine"]["cores"] or 1
    other = doc.get("other_programs_cores")
    # The load at the end counts the run's own last benchmark (eight smoke tests at once); what other programs
    # took during the run says whether the machine was shared.
    if doc["load_avg_start"][0] > 0.5 * cores or (other is not None and other > 0.25):
        caveats.append(f"busy machine: 1-minute load {doc['load_avg_start'][0]} at start on {cores} cores, other "
                       f"programs used {other} cores on average during the run")
    if doc["errors"]:
        caveats.append(f"benchmarks failed: {', '.join(doc['errors'])}")
    commit = (doc["source"]["commit"] or "nocommit")[:10]
    path = RESULTS / f"reference-{doc['when'][:10]}-{commit}.json"
    path.write_text(json.dumps(doc | {"caveats": caveats}, indent=2) + "\n")
    for c in caveats:
        console.print(f"reference caveat: {c}", markup=False)  # type: ignore[attr-defined]
    return path


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
