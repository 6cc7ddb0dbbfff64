"""`diffctl laser-filters scan_to_scan_filter_chain`: the executable of package laser_filters."""

from __future__ import annotations

import click


@click.group("laser-filters")
def laser_filters() -> None:
    """laser_filters' scan_to_scan_filter_chain: `scan` through a YAML filter chain to `scan_filtered`.

    \b
    Example:
      diffctl run laser_filters scan_to_scan_filter_chain --ros-args --params-file box_filter.yaml
    """


@laser_filters.command("scan_to_scan_filter_chain", context_settings={"ignore_unknown_options": True})
def scan_to_scan_filter_chain() -> None:
    """Filter `scan` through filter1, filter2, … (name, type, params) and publish `scan_filtered`."""
    from diffctl.laser_filters.node import run

    raise SystemExit(run())
