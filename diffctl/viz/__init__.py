"""The browser visualizer (rviz2's counterpart): a self-contained web page fed live from the bus.

`diffctl viz` serves the page in `static/` over HTTP and streams the scene over a WebSocket; the page's
teleop and message publisher panels send commands back, guarded by a token and an Origin check.
"""
