"""From a robot description (SDF or URDF text) to the manager's inputs: HardwareInfo per `<ros2_control>`
block, and the gz_ros2_control plugin's `<parameters>` files.

`plugin_override` swaps every block's hardware plugin (e.g. to mock_components/GenericSystem, to run the
tutorial's robot without a simulator); `extra_params` adds hardware `<param>`s (calculate_dynamics=true).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path

from diffctl.control.hardware_interface import ComponentInfo, HardwareInfo, InterfaceInfo
from diffctl.description.model import Ros2Control, Ros2ControlInterface, Ros2ControlJoint
from diffctl.description.ros2_control import gz_ros2_control_parameters, ros2_control_blocks
from diffctl.errors import DescriptionError

PLACEHOLDER = "PARAMETERS_CONFIG_FILE_PLACEHOLDER"


def _iface(it: Ros2ControlInterface) -> InterfaceInfo:
    return InterfaceInfo(
        it.name,
        min=-math.inf if it.min is None else it.min,
        max=math.inf if it.max is None else it.max,
        initial_value=it.initial_value,
        data_type=it.data_type,
        parameters=dict(it.params),
        enable_limits=it.enable_limits,
    )


def _component(c: Ros2ControlJoint, kind: str) -> ComponentInfo:
    return ComponentInfo(
        c.name,
        kind,
        tuple(_iface(i) for i in c.command_interfaces),
        tuple(_iface(i) for i in c.state_interfaces),
        dict(c.params),
        c.enable_limits,
    )


def hardware_infos(
    description: str,
    source: str = "robot_description",
    *,
    plugin_override: str | None = None,
    extra_params: dict[str, str] | None = None,
) -> list[HardwareInfo]:
    blocks = ros2_control_blocks(description, source)
    if not blocks:
        raise DescriptionError(
            "the robot description has no <ros2_control> block",
            source=source,
            hint='add <ros2_control name=… type="system"> with <hardware><plugin>…</plugin></hardware> and joints',
        )
    return infos_from_blocks(blocks, source, plugin_override=plugin_override, extra_params=extra_params)


def infos_from_blocks(
    blocks: Sequence[Ros2Control],
    source: str | None,
    *,
    plugin_override: str | None = None,
    extra_params: dict[str, str] | None = None,
) -> list[HardwareInfo]:
    """HardwareInfo of each parsed `<ros2_control>` block (as the simulator's model already holds them)."""
    out = []
    for b in blocks:
        params = {**dict(b.hardware_params), **(extra_params or {})}
        out.append(
            HardwareInfo(
                name=b.name,
                type=b.type,
                plugin_name=plugin_override or b.hardware_plugin,
                hardware_parameters=params,
                joints=tuple(_component(j, "joint") for j in b.joints),
                sensors=tuple(_component(s, "sensor") for s in b.sensors),
                gpios=tuple(_component(g, "gpio") for g in b.gpios),
                source=source,
            )
        )
    return out


def parameter_files(description: str, source: str = "robot_description") -> tuple[list[str], list[str]]:
    """(usable files, problems): the plugin's `<parameters>` that exist; the placeholder and missing files
    are reported as problems for the caller to warn about or refuse."""
    files, problems = [], []
    for f in gz_ros2_control_parameters(description, source):
        if f == PLACEHOLDER:
            problems.append(f"gz_ros2_control <parameters> is still {PLACEHOLDER} (the launch file substitutes it)")
        elif not Path(f).is_file():
            problems.append(f"gz_ros2_control <parameters> file {f!r} does not exist")
        else:
            files.append(f)
    return files, problems
