"""rclpy.impl (diffctl)."""
