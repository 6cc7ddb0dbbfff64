# Which rclpy modules typical imports load (so `rclpy.executors`, `rclpy.logging`… are attributes of rclpy).
import json
import sys

out = []


def loaded():
    return sorted(k for k in sys.modules if k.startswith("rclpy"))


import rclpy  # noqa: E402

out.append(["import rclpy", loaded()])
import rclpy.node  # noqa: E402

out.append(["from rclpy.node import Node", loaded()])
out.append(["attributes", [hasattr(rclpy, m) for m in ("executors", "logging", "qos", "time", "duration", "clock",
                                                        "timer", "task", "callback_groups", "parameter")]])
import rclpy.action  # noqa: E402
import rclpy.lifecycle  # noqa: E402

out.append(["rclpy.action, rclpy.lifecycle", loaded()])
print(json.dumps(out))
