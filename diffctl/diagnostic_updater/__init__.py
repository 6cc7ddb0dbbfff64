"""diagnostic_updater's Updater for diffctl's C++-flavoured nodes: tasks reported on /diagnostics."""
