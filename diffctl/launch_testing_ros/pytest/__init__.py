"""launch_testing_ros' pytest collectors (used by the `launch_ros` pytest plugin for `rostest` files)."""
