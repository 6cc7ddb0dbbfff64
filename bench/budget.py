"""The performance budget of ARCHITECTURE.md and the issues, as (comparison, limit, label) per metric."""

from __future__ import annotations

BUDGET: dict[str, tuple[str, float, str]] = {
    "stack_launch_to_ready_s": ("<=", 1.0, "launch sim_control → controllers active + first /odom"),
    "stack_ctrl_c_to_reaped_s": ("<=", 0.5, "Ctrl-C → every process reaped"),
    "stack_rtf_vs_bare": (">=", 0.5, "full-stack RTF at rtf:=0 ÷ bare stepping of its own world and robot (same run)"),
    "stack_cmd_vel_to_wheel_p99_ms": ("<=", 60.0, "cmd_vel → wheel command latency at real time, p99"),
    "stack_rss_mb": ("<=", 400.0, "all processes of sim_control, resident memory"),
    "bus_rtt_p50_us": ("<=", 150.0, "bus round trip TwistStamped, p50"),
    "bus_rtt_p99_us": ("<=", 300.0, "bus round trip TwistStamped, p99"),
    "bus_throughput_msgs_s": (">=", 100_000.0, "bus one-way throughput, decoded, drain timed"),
    "rclpy_rtt_p50_vs_real": ("<=", 1.0, "rclpy Twist round trip p50 ÷ the real rclpy's (Fast DDS, same run)"),
    "rclpy_pubsub_msgs_per_s_vs_real": (">=", 1.0, "rclpy Twist pub→sub throughput ÷ the real rclpy's (same run)"),
    "rclpy_node_start_vs_real": ("<=", 1.0, "rclpy.init → first publish ÷ the real rclpy's (same run)"),
    "msgs_twist_serialize_vs_real": ("<=", 1.0, "Twist serialize ÷ the real rclpy.serialization's (same run)"),
    "msgs_twist_deserialize_vs_real": ("<=", 1.0, "Twist deserialize ÷ the real rclpy.serialization's (same run)"),
    "control_jitter_p99_ms": ("<=", 1.0, "controller manager 100 Hz wall, period jitter p99"),
    "control_update_us": ("<=", 100.0, "controller manager update cost per tick, the tutorial's two controllers"),
    "sim_rtf_lidar": (">=", 50.0, "sim fast mode, car + lidar 10 Hz"),
    "sim_rtf_camera": (">=", 8.0, "sim fast mode, car + camera 320x240 10 Hz"),
    "launch_50_all_started_s": ("<=", 0.5, "launch 50 processes: all started"),
    "launch_50_all_reaped_s": ("<=", 0.5, "launch 50 processes: all reaped"),
    "launcher_rss_mb": ("<=", 80.0, "launcher resident memory"),
    "fleet_rtf_ratio_10": (">=", 0.2, "ten cars in one world: RTF ÷ one car's"),
    "fleet_rss_mb_per_car": ("<=", 40.0, "memory per added car"),
    "smoke_test_wall_s": ("<=", 3.0, "the tutorial car's --init smoke test: launch, drive 2 s sim, down"),
    "smoke_tests_parallel_wall_s": ("<=", 10.0, "diffctl test -j 2: 8 copies of that smoke test"),
}


def verdict(value: object, op: str, limit: float) -> str:
    if not isinstance(value, (int, float)):
        return "not measured"
    ok = value <= limit if op == "<=" else value >= limit
    return "ok" if ok else "OVER BUDGET"
