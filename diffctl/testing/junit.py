"""JUnit XML of a launch test file, laid out as launch_testing's junitxml: one testsuite per run, one
testcase per test method; diffctl adds each process's log of that run as the testsuite's `system-out`."""

from __future__ import annotations

import unittest
from pathlib import Path
from xml.etree import ElementTree as ET

from diffctl.testing.loader import iterate_cases
from diffctl.testing.runner import FileResult, RunResult


def _outcomes(one: RunResult) -> dict[int, tuple[str, str, float]]:
    """case id → (kind, message, seconds): kind is '' (passed), 'failure', 'error' or 'skipped'."""
    out: dict[int, tuple[str, str, float]] = {}
    for result in one.results:
        times = getattr(result, "testTimes", {})
        for case in getattr(result, "successes", []):
            out[id(case)] = ("", "", times.get(case, 0.0))
        for kind, items in (("failure", result.failures), ("error", result.errors), ("skipped", result.skipped)):
            for case, text in items:
                out[id(case)] = (kind, text, times.get(case, 0.0))
        for case, text in result.expectedFailures:
            out[id(case)] = ("", text, times.get(case, 0.0))
        for case in result.unexpectedSuccesses:
            out[id(case)] = ("failure", "unexpected success", times.get(case, 0.0))
    return out


def _logs(one: RunResult) -> str:
    return "\n".join(f"===== {name} =====\n{text}" for name, text in one.logs.items())


def to_xml(file_result: FileResult) -> ET.ElementTree:
    name = f"{file_result.package_name}.{file_result.path.name[:-3]}"
    root = ET.Element("testsuites", name=name)
    totals = {"tests": 0, "failures": 0, "errors": 0, "time": 0.0}
    if file_result.error is not None:
        suite = ET.SubElement(root, "testsuite", name=f"{name}.launch_tests", tests="1", failures="0",
                              errors="1", skipped="0", time="0.0")
        case = ET.SubElement(suite, "testcase", classname=file_result.package_name, name="generate_test_description",
                             time="0.0")
        ET.SubElement(case, "error", message=file_result.error)
        totals["tests"], totals["errors"] = 1, 1
    for one in file_result.runs:
        outcomes = _outcomes(one)
        suite = ET.SubElement(root, "testsuite", name=str(one.run))
        counts = {"tests": 0, "failures": 0, "errors": 0, "skipped": 0}
        total_s = 0.0
        cases = [*iterate_cases(one.run.pre_shutdown_tests), *iterate_cases(one.run.post_shutdown_tests)]
        for case in cases:
            kind, message, seconds = outcomes.get(id(case), ("skipped", "not run", 0.0))
            cls = type(case)
            element = ET.SubElement(suite, "testcase", classname=f"{file_result.package_name}.{cls.__name__}",
                                    name=case._testMethodName, time=f"{round(seconds, 3)}")
            counts["tests"] += 1
            total_s += seconds
            if kind:
                ET.SubElement(element, kind, message=message)
                counts["failures" if kind == "failure" else "errors" if kind == "error" else "skipped"] += 1
        for key, value in counts.items():
            suite.set(key, str(value))
        suite.set("time", f"{round(one.seconds, 3)}")
        logs = _logs(one)
        if logs:
            ET.SubElement(suite, "system-out").text = logs
        for key in ("tests", "failures", "errors"):
            totals[key] += counts[key]
        totals["time"] += one.seconds
    for key in ("tests", "failures", "errors"):
        root.set(key, str(totals[key]))
    root.set("time", f"{round(totals['time'], 3)}")
    return ET.ElementTree(root)


def write(file_result: FileResult, path: Path) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    to_xml(file_result).write(path, encoding="utf-8", xml_declaration=True)


def merge(paths: list[Path], target: Path) -> None:
    """One file of several files' results (`diffctl test --junit-xml` over many test files)."""
    root = ET.Element("testsuites", name="diffctl test")
    totals = {"tests": 0, "failures": 0, "errors": 0}
    seconds = 0.0
    for path in paths:
        if not path.is_file():
            continue
        other = ET.parse(path).getroot()
        for key in totals:
            totals[key] += int(other.get(key, "0"))
        seconds += float(other.get("time", "0"))
        root.extend(list(other))
    for key, value in totals.items():
        root.set(key, str(value))
    root.set("time", f"{round(seconds, 3)}")
    target.parent.mkdir(parents=True, exist_ok=True)
    ET.ElementTree(root).write(target, encoding="utf-8", xml_declaration=True)


def case_failed(result: unittest.TestResult) -> bool:
    return not result.wasSuccessful()


def unittestResultsToXml(*, name: str = "launch_test", test_results: dict | None = None) -> ET.ElementTree:
    """launch_testing.junitxml's entry: {TestRun: its result} (LaunchTestRunner.run()'s answer) as JUnit XML."""
    file_result = FileResult(Path(f"{name}.py"), name)
    for run, result in (test_results or {}).items():
        file_result.runs.append(RunResult(run, results=[result]))
    tree = to_xml(file_result)
    tree.getroot().set("name", name)
    return tree
