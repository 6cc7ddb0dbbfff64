"""An rclpy talker: 'Hello World: N' on chatter every 0.1 s, printed on stdout too."""

import rclpy
from rclpy.executors import ExternalShutdownException
from std_msgs.msg import String


def main():
    rclpy.init()
    node = rclpy.create_node("talker")
    pub = node.create_publisher(String, "chatter", 10)
    count = [0]

    def tick():
        msg = String(data=f"Hello World: {count[0]}")
        count[0] += 1
        pub.publish(msg)
        print(f"Publishing: '{msg.data}'", flush=True)

    node.create_timer(0.1, tick)
    try:
        rclpy.spin(node)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        node.destroy_node()
        rclpy.try_shutdown()


if __name__ == "__main__":
    main()
