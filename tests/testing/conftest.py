"""The launch test files under launch_tests/ are data: the tests here run them (some fail on purpose)."""

collect_ignore = ["launch_tests"]
