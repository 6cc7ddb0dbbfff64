"""Programs that end right after rclpy.shutdown(), or without it, exit with their own code, silently, with no
thread of diffctl's or Zenoh's left running into interpreter finalization (one caught inside a Zenoh call there
was cancelled and aborted the process: "FATAL: exception not rethrown", exit 134 or -6)."""

from __future__ import annotations

import subprocess
import sys
import textwrap

import pytest

# Printed by the program's own atexit handler, which runs after threading's exit hooks, right before the
# interpreter finalizes: every thread still alive then is one finalization would cancel.
PRELUDE = textwrap.dedent("""
    import atexit, os, signal, sys, threading, time
    import rclpy
    from rclpy.executors import ExternalShutdownException, MultiThreadedExecutor
    from std_msgs.msg import String
    atexit.register(lambda: print("ALIVE", sorted(t.name for t in threading.enumerate()), file=sys.stderr))
    rclpy.init()
    n = rclpy.create_node('exit_clean')
    p = n.create_publisher(String, 'chatter', 10)
""")

VARIANTS = {
    "destroy-then-shutdown": """
        p.publish(String(data='a'))
        n.destroy_node()
        rclpy.shutdown()
    """,
    "no-destroy": """
        p.publish(String(data='a'))
        n.get_logger().info('last words')
        rclpy.shutdown()
    """,
    "timer-running": """
        n.set_parameters([rclpy.parameter.Parameter('use_sim_time', value=False)])
        n.create_timer(0.001, lambda: (p.publish(String(data='a')), n.get_logger().info('tick')))
        for _ in range(30):
            rclpy.spin_once(n, timeout_sec=0.01)
        rclpy.shutdown()
    """,
    "executor-in-thread": """
        def tick():
            if rclpy.ok():
                p.publish(String(data='a'))
                n.get_logger().info('tick')
        n.create_timer(0.002, tick)
        ex = MultiThreadedExecutor()
        ex.add_node(n)
        threading.Thread(target=ex.spin, name="user-spin", daemon=True).start()
        time.sleep(0.3)
        rclpy.shutdown()
    """,
    # The program simply returns: the exit itself ends the contexts, the spinning thread (rclpy.spin watches only
    # its context) and the Zenoh callback thread still busy with the node's own samples.
    "never-shut-down": """
        n.create_timer(0.002, lambda: (p.publish(String(data='a')), n.get_logger().info('tick')))
        n.create_subscription(String, 'chatter', lambda m: None, 10)
        threading.Thread(target=rclpy.spin, args=(n,), name="user-spin", daemon=True).start()
        time.sleep(0.3)
    """,
    "keyboard-interrupt": """
        n.create_timer(0.002, lambda: (p.publish(String(data='a')), n.get_logger().info('tick')))
        threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT)).start()
        try:
            rclpy.spin(n)
        except (KeyboardInterrupt, ExternalShutdownException):  # which one depends on the race, as in rclpy
            pass
        rclpy.try_shutdown()
    """,
}
RUNS = 3


@pytest.mark.parametrize("variant", sorted(VARIANTS))
def test_exit_right_after_shutdown_is_clean(router: str, variant: str) -> None:
    code = PRELUDE + textwrap.dedent(VARIANTS[variant])
    for run in range(RUNS):
        r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
        where = f"{variant} run {run}: exit {r.returncode}\n{r.stderr}"
        assert r.returncode == 0, where
        for bad in ("FATAL", "WARN", "session closed", "Traceback", "Exception"):
            assert bad not in r.stderr + r.stdout, where
        alive = [ln for ln in r.stderr.splitlines() if ln.startswith("ALIVE ")]
        assert alive == ["ALIVE ['MainThread']"], where
