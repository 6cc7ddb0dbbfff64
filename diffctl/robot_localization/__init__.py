"""robot_localization (Jazzy): ekf_node, ukf_node and navsat_transform_node on diffctl's client Node.

The filters' math (`state`, `motion_model`, `ekf`, `ukf`, `measurements`, `estimator`, `navsat`) is pure numpy;
`filter_node` and `navsat_node` are the ROS nodes around it, with upstream's parameters, topics and services.
"""
