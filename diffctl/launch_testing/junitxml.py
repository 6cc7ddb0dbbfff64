"""JUnit XML of launch test results: one <testsuite> per TestRun, one <testcase> per test method."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from typing import Any


def unittestResultsToXml(*, name: str = "launch_test", test_results: dict[Any, Any] | None = None) -> ET.ElementTree:
    """{TestRun: result} (LaunchTestRunner.run's answer) as a <testsuites> document named `name`."""
    results = test_results or {}
    root = ET.Element("testsuites", name=name)
    root.set("tests", str(sum(r.testsRun for r in results.values())))
    root.set("failures", str(sum(len(r.failures) for r in results.values())))
    root.set("errors", str(sum(len(r.errors) for r in results.values())))
    root.set("time", str(round(sum(sum(r.testTimes.values()) for r in results.values()), 3)))
    for run, result in results.items():
        root.append(unittestResultToXml(str(run), result))
    return ET.ElementTree(root)


def unittestResultToXml(name: str, test_result: Any) -> ET.Element:
    """One result (its testCases and testTimes: a launch_testing result) as a <testsuite>."""
    counts = {"tests": test_result.testsRun}
    counts.update((outcome, len(getattr(test_result, outcome))) for outcome in ("failures", "errors", "skipped"))
    suite = ET.Element("testsuite", {"name": name, **{key: str(n) for key, n in counts.items()}})
    suite.set("time", str(round(sum(test_result.testTimes.values()), 3)))
    suite.extend(unittestCaseToXml(test_result, case) for case in test_result.testCases)
    return suite


def unittestCaseToXml(test_result: Any, test_case: Any) -> ET.Element:
    """One case as a <testcase>: 'module.Class' as its classname, the method (and any subtest text after
    the id's first space) as its name, a <failure>, <error> or <skipped> for how it went."""
    method_id, _, qualifiers = test_case.id().partition(" ")
    classname, _, method = method_id.rpartition(".")
    element = ET.Element("testcase", classname=classname, name=f"{method} {qualifiers}".strip())
    element.set("time", str(round(test_result.testTimes[test_case], 3)))
    for tag, outcomes in (("failure", test_result.failures), ("error", test_result.errors),
                          ("skipped", test_result.skipped)):
        for case, text in outcomes:
            if case == test_case:
                ET.SubElement(element, tag, message=text)
    return element
