"""interactive_markers: the InteractiveMarkerServer side of RViz's interactive markers, on a client Node."""
