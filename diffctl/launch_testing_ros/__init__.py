"""launch_testing_ros, module for module (ROS 2 Jazzy): launch tests of ROS nodes, with rclpy helpers for
test bodies (diffctl's rclpy: diffctl.client). Names are imported when first used: pytest loads this
package's plugin in every session.
"""

from __future__ import annotations

from diffctl.launch._private.lazy import lazy_exports

__getattr__, __dir__, __all__ = lazy_exports(__name__, globals(), {
    ".": ["tools/"],
    ".data_republisher": ["DataRepublisher"],
    ".message_pump": ["MessagePump"],
    ".test_runner": ["LaunchTestRunner"],
    ".wait_for_topics": ["WaitForTopics"],
})
