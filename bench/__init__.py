"""Benchmarks: `make bench` runs every module's `run()` and compares the results with the budget."""
