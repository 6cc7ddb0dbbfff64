"""The Foxglove WebSocket server (foxglove_bridge): live ROS topics and bags for the Foxglove app."""
