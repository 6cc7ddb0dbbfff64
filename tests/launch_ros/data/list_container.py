"""Waits until the container named by argv[1] lists argv[2] loaded nodes, prints their names, exits 0."""

import sys
import time

import rclpy
from composition_interfaces.srv import ListNodes

container, wanted = sys.argv[1], int(sys.argv[2])
rclpy.init()
node = rclpy.create_node("list_container")
client = node.create_client(ListNodes, f"{container}/_container/list_nodes")
while not client.wait_for_service(timeout_sec=1.0):
    pass
while True:
    future = client.call_async(ListNodes.Request())
    rclpy.spin_until_future_complete(node, future)
    names = sorted(future.result().full_node_names)
    if len(names) >= wanted:
        break
    time.sleep(0.05)
print("LOADED " + " ".join(names), flush=True)
node.destroy_node()
rclpy.shutdown()
