"""interactive_marker_twist_server: marker_server, an RViz interactive marker dragged into Twist commands."""
