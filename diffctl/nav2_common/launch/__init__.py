"""nav2_common.launch: the substitutions and argument parser of nav2_common, on diffctl's launch."""

from .has_node_params import HasNodeParams
from .parse_multirobot_pose import ParseMultiRobotPose
from .replace_string import ReplaceString
from .rewritten_yaml import RewrittenYaml

__all__ = ["HasNodeParams", "ParseMultiRobotPose", "ReplaceString", "RewrittenYaml"]
