"""`launch_testing.pytest`: the pytest plugin (diffctl/testing/pytest_plugin.py)."""
