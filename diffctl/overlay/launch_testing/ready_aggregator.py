"""`launch_testing.ready_aggregator` (diffctl/testing/ready_aggregator.py)."""

from diffctl.testing.ready_aggregator import ReadyAggregator

__all__ = ["ReadyAggregator"]
