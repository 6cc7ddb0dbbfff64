"""Recording and replay: rosbag2-compatible bags (metadata.yaml + MCAP) written and read by diffctl."""
