"""`launch_testing.junitxml` (diffctl/testing/junit.py)."""

from diffctl.testing.junit import unittestResultsToXml

__all__ = ["unittestResultsToXml"]
