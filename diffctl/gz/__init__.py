"""Gazebo's `gz` command line in front of diffctl's simulator: `gz sim`, `gz topic`, `gz service`, `gz model`."""
