"""The performance budget of ARCHITECTURE.md, as (comparison, limit, label) per metric; how each figure is taken
(`HOW`: runs, statistic, clock, warm or cold), printed beside it and written into the results files; and the
figures derived from others of the same run (`derived`)."""

from __future__ import annotations

BUDGET: dict[str, tuple[str, float, str]] = {
    "stack_launch_to_active_s": ("<=", 0.5, "launch sim_control → both controllers active"),
    "stack_launch_to_ready_s": ("<=", 0.8, "launch sim_control → first /odom"),
    "stack_ctrl_c_to_reaped_s": ("<=", 0.5, "Ctrl-C → every process reaped"),
    "stack_rtf_vs_bare": (">=", 0.6, "full-stack RTF at rtf:=0 ÷ bare stepping of its own world and robot (same run)"),
    "stack_cmd_vel_to_wheel_p99_ms": ("<=", 60.0, "cmd_vel → wheel command latency at real time, p99"),
    "stack_rss_mb": ("<=", 300.0, "all processes of sim_control, resident memory (PSS)"),
    "bus_rtt_p50_vs_zenoh": ("<=", 1.1, "bus round trip TwistStamped p50 ÷ bare zenoh-python's (same run)"),
    "bus_rtt_p99_vs_zenoh": ("<=", 1.1, "bus round trip TwistStamped p99 ÷ bare zenoh-python's (same run)"),
    "bus_throughput_msgs_s": (">=", 100_000.0, "bus one-way throughput, decoded, drain timed"),
    "rclpy_rtt_p50_vs_real": ("<=", 0.67, "rclpy Twist round trip p50 ÷ the real rclpy's (Fast DDS, same run)"),
    "rclpy_pubsub_msgs_per_s_vs_real": (">=", 1.5, "rclpy Twist pub→sub throughput ÷ the real rclpy's (same run)"),
    "rclpy_node_start_vs_real": ("<=", 0.67, "rclpy.init → first publish ÷ the real rclpy's (same run)"),
    "msgs_twist_serialize_vs_real": ("<=", 1.0, "Twist serialize ÷ the real rclpy.serialization's (same run)"),
    "msgs_twist_deserialize_vs_real": ("<=", 1.0, "Twist deserialize ÷ the real rclpy.serialization's (same run)"),
    "control_jitter_p99_ms": ("<=", 1.0, "controller manager 100 Hz wall, period jitter p99"),
    "control_update_us": ("<=", 60.0, "controller manager update cost per tick, the tutorial's two controllers"),
    "sim_rtf_lidar": (">=", 50.0, "sim fast mode, car + lidar 10 Hz"),
    "sim_rtf_camera": (">=", 8.0, "sim fast mode, car + camera 320x240 10 Hz"),
    "launch_50_all_started_s": ("<=", 0.5, "launch 50 processes: all started"),
    "launch_50_all_reaped_s": ("<=", 0.5, "launch 50 processes: all reaped"),
    "launcher_rss_mb": ("<=", 80.0, "launcher resident memory"),
    "fleet_rtf_ratio_10": (">=", 0.2, "ten cars in one world: RTF ÷ one car's"),
    "fleet_rss_mb_per_car": ("<=", 30.0, "memory per added car"),
    "smoke_test_wall_s": ("<=", 2.0, "the tutorial car's --init smoke test: launch, drive 2 s sim, down"),
    "smoke_tests_parallel_wall_s": ("<=", 8.0, "diffctl test -j 2: 8 copies of that smoke test"),
}

# "cold" is a fresh process (the OS's file caches warm from what ran before it), "warm" a figure taken after a
# warm-up in a process that has run the same work already.
HOW: dict[str, str] = {
    "stack_launch_to_active_s": "one cold start: exec of diffctl launch → list_controllers shows both active "
                                "(polled every 20 ms), wall",
    "stack_launch_to_ready_s": "the same start: exec → the first odometry received, wall",
    "stack_ctrl_c_to_reaped_s": "one stop: SIGINT → the launcher gone and every descendant reaped, wall",
    "stack_rtf_vs_bare": "median of the world's own RTF over 3 s of driving at rtf 0 ÷ the faster of two 5 s runs of "
                         "bare stepping (before and after the stack), wall",
    "stack_cmd_vel_to_wheel_p99_ms": "p99 of 200 commands at real time after a ramp to steady speed (warm), wall",
    "stack_rss_mb": "PSS of the launcher and every descendant, once, while driving (warm)",
    "bus_rtt_p50_vs_zenoh": "median of 5000 round trips after 500 warm-up ÷ bare zenoh-python's, same router, "
                            "the two in alternating blocks of 250, wall",
    "bus_rtt_p99_vs_zenoh": "p99 of the same 5000 round trips ÷ bare zenoh-python's",
    "bus_throughput_msgs_s": "one 3 s flood (warm sessions), decoded messages ÷ the window up to the last one "
                             "received",
    "rclpy_rtt_p50_vs_real": "median of 2000 round trips after 200 warm-up, each side its own run, wall",
    "rclpy_pubsub_msgs_per_s_vs_real": "one 3 s flood per side, counted in the subscription callback, wall",
    "rclpy_node_start_vs_real": "median of 5 cold processes: rclpy.init → first publish returned, wall",
    "msgs_twist_serialize_vs_real": "best of 5 timeit repeats of 20000 calls (warm), wall",
    "msgs_twist_deserialize_vs_real": "best of 5 timeit repeats of 20000 calls (warm), wall",
    "control_jitter_p99_ms": "p99 of |period − 10 ms| over 10 s at 100 Hz after a 1 s warm-up, one run, wall",
    "control_update_us": "mean over the same 1000 cycles, wake → end of write, wall (SCHED_FIFO when permitted); "
                         "each cycle follows a 10 ms sleep, so its caches are as the machine left them; "
                         "control_update_cpu_us is the same cycles' thread CPU time",
    "sim_rtf_lidar": "best of 3 interleaved 20 s (sim) runs, wall",
    "sim_rtf_camera": "best of 3 interleaved 5 s (sim) runs, wall",
    "launch_50_all_started_s": "one cold launch, as the launcher logs it (first action → last process started)",
    "launch_50_all_reaped_s": "the same launch: SIGINT → launcher exit with every process reaped, wall",
    "launcher_rss_mb": "the peak of 5 samples over 100 ms with 50 children running (RSS)",
    "fleet_rtf_ratio_10": "one launch per fleet size, median of the world's RTF over 6 s at rtf 0 each",
    "fleet_rss_mb_per_car": "(PSS of 10 cars − PSS of 1 car) ÷ 9, one launch each, once every controller is active",
    "smoke_test_wall_s": "best of 2 runs after one warm-up run (each a cold diffctl test process), wall",
    "smoke_tests_parallel_wall_s": "one run of diffctl test -j 2 on 8 copies, wall",
}


def derived(results: dict) -> dict:
    """Figures computed from others of the same run (budget rows stated as ratios)."""
    out = {}
    for ratio, ours, floor in (("bus_rtt_p50_vs_zenoh", "bus_rtt_p50_us", "zenoh_raw_rtt_p50_us"),
                               ("bus_rtt_p99_vs_zenoh", "bus_rtt_p99_us", "zenoh_raw_rtt_p99_us")):
        a, b = results.get(ours), results.get(floor)
        if isinstance(a, (int, float)) and isinstance(b, (int, float)) and b > 0:
            out[ratio] = round(a / b, 3)
    return out


def verdict(value: object, op: str, limit: float) -> str:
    if not isinstance(value, (int, float)):
        return "not measured"
    ok = value <= limit if op == "<=" else value >= limit
    return "ok" if ok else "OVER BUDGET"
