"""launch_testing's pytest plugin (pytest11 entry point `launch_testing`: launch_testing.pytest.hooks)."""
