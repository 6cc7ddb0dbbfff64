"""An rclpy listener: prints 'I heard: [text]' for every String on chatter."""

import rclpy
from rclpy.executors import ExternalShutdownException
from std_msgs.msg import String


def main():
    rclpy.init()
    node = rclpy.create_node("listener")
    node.create_subscription(String, "chatter", lambda msg: print(f"I heard: [{msg.data}]", flush=True), 10)
    try:
        rclpy.spin(node)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        node.destroy_node()
        rclpy.try_shutdown()


if __name__ == "__main__":
    main()
