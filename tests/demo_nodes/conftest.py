"""The launch test file under launch_tests/ is data: the tests here run it."""

collect_ignore = ["launch_tests"]
