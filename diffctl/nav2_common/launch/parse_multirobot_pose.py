"""`ParseMultiRobotPose`: robots and their poses from a launch argument such as
`robots:="robot1={x: 1.0, y: 1.0, yaw: 0.0}; robot2={x: 2.0, y: 1.0}"` on the command line."""

from __future__ import annotations

import sys
from typing import Any

import yaml

_POSE_KEYS = ("x", "y", "z", "roll", "pitch", "yaw")


class ParseMultiRobotPose:
    """The value of the command-line argument `target_argument:=…`, read from this process's arguments."""

    def __init__(self, target_argument: str) -> None:
        prefix = f"{target_argument}:="
        # ros2 launch's own words come first; diffctl launch may take options there too, never `NAME:=…`
        self._text = next((a[len(prefix):] for a in sys.argv[1:] if a.startswith(prefix)), "")

    def value(self) -> dict[str, dict[str, Any]]:
        """Robot name → its pose: x, y, z, roll, pitch, yaw (0.0 where not given) and any other keys given."""
        robots: dict[str, dict[str, Any]] = {}
        for entry in self._text.split(";") if self._text else []:
            parts = entry.strip().split("=")
            if len(parts) != 2:
                continue  # not `name={…}`: skipped, as upstream skips it
            pose = yaml.safe_load(parts[1].strip())
            for key in _POSE_KEYS:
                pose.setdefault(key, 0.0)
            robots[parts[0].strip()] = pose
        return robots
