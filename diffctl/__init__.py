"""diffctl: a simulated differential-drive robot stack over Zenoh, without ROS."""

__version__ = "0.1.0"
