"""Helpers of diffctl's launch that are not part of ros2/launch's API."""
