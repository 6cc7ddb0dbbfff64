"""JUnit XML of launch test files: launch_testing's layout (one testsuite per run, one testcase per test
method), with each process's output of the run as the testsuite's `system-out`; a file that could not run
is one testcase in error; `merge` makes one document of several files' (`diffctl test --junit-xml`)."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING
from xml.etree import ElementTree as ET

if TYPE_CHECKING:
    from diffctl.testing.runner import FileResult


def to_xml(file_result: FileResult) -> ET.ElementTree:
    from diffctl.launch_testing.junitxml import unittestResultsToXml

    name = f"{file_result.package_name}.{file_result.path.name[:-3]}"
    results = {r.run: r.result for r in file_result.runs if r.result is not None}
    tree = unittestResultsToXml(name=name, test_results=results)
    root = tree.getroot()
    for suite, record in zip(root, [r for r in file_result.runs if r.result is not None], strict=True):
        logs = "\n".join(f"===== {log} =====\n{text}" for log, text in record.logs.items())
        if logs:
            ET.SubElement(suite, "system-out").text = logs
    if file_result.error is not None:
        suite = ET.SubElement(root, "testsuite", name=f"{name}.launch_tests", tests="1", failures="0", errors="1",
                              skipped="0", time="0")
        case = ET.SubElement(suite, "testcase", classname=file_result.package_name,
                             name="generate_test_description", time="0")
        ET.SubElement(case, "error", message=file_result.error)
        root.set("tests", str(int(root.get("tests", "0")) + 1))
        root.set("errors", str(int(root.get("errors", "0")) + 1))
    return tree


def write(file_result: FileResult, path: Path) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    to_xml(file_result).write(path, encoding="utf-8", xml_declaration=True)


def merge(paths: list[Path], target: Path) -> None:
    """One document of several files' results."""
    root = ET.Element("testsuites", name="diffctl test")
    totals = {"tests": 0, "failures": 0, "errors": 0}
    seconds = 0.0
    for path in paths:
        if not path.is_file():
            continue
        other = ET.parse(path).getroot()
        suites = [other] if other.tag == "testsuite" else list(other)  # pytest writes <testsuites><testsuite>
        for key in totals:
            totals[key] += int(other.get(key, "0")) if other.get(key) else sum(int(s.get(key, "0")) for s in suites)
        seconds += float(other.get("time", "0") or 0) or sum(float(s.get("time", "0") or 0) for s in suites)
        root.extend(suites)
    for key, value in totals.items():
        root.set(key, str(value))
    root.set("time", f"{round(seconds, 3)}")
    target.parent.mkdir(parents=True, exist_ok=True)
    ET.ElementTree(root).write(target, encoding="utf-8", xml_declaration=True)
