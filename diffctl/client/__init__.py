"""diffctl's rclpy-compatible client library: nodes, executors, QoS, parameters, time and logging on the bus.

Users import it through the overlay's `rclpy` package (`diffctl/overlay/rclpy`), which only maps ROS's names
onto these modules. `API.md` here lists the internals other client modules (actions, lifecycle, tf2) build on.
"""
