"""Composable nodes in diffctl's container, loaded over its load_node service as launch_ros does: the
container's own descriptions and a LoadComposableNodes naming the container from a scoped group (its
namespace and SetParameter apply); a C++ plugin fails alone, with launch_ros's message."""

from __future__ import annotations

import os
import sys
from pathlib import Path

import pytest

from diffctl.launch.actions import ExecuteProcess, GroupAction, RegisterEventHandler, Shutdown
from diffctl.launch.event_handlers import OnProcessIO
from diffctl.launch_ros.actions import ComposableNodeContainer, LoadComposableNodes, PushRosNamespace, SetParameter
from diffctl.launch_ros.descriptions import ComposableNode
from diffctl.launch_ros.utilities import get_node_name_count

from .conftest import DATA, Records, run


@pytest.mark.slow
def test_components_load_into_a_running_container(router: str, tmp_path: Path) -> None:
    log = tmp_path / "components.log"
    env = {"PYTHONPATH": os.pathsep.join([str(DATA), os.environ.get("PYTHONPATH", "")]), "COMPONENT_LOG": str(log)}
    container = ComposableNodeContainer(
        package="rclcpp_components",
        executable="component_container",
        name="box",
        namespace="",
        additional_env=env,
        composable_node_descriptions=[
            ComposableNode(
                package="demo",
                plugin="components:Greeter",
                name="first",
                namespace="ns",
                parameters=[{"greeting": "hello"}],
                remappings=[("chatter", "talk")],
            )
        ],
    )
    loader = LoadComposableNodes(
        target_container="/box",
        composable_node_descriptions=[
            ComposableNode(package="image_tools", plugin="image_tools::ShowImage", name="cpp"),
            ComposableNode(package="demo", plugin="components:Greeter", name="second"),
        ],
    )
    # ends the launch once the container lists both Python nodes
    checker = ExecuteProcess(cmd=[sys.executable, str(DATA / "list_container.py"), "/box", "2"], on_exit=[Shutdown()])
    listed: list[str] = []

    def record(event) -> None:
        listed.append(event.text.decode())

    with Records("launch_ros.actions.load_composable_nodes") as records:
        code, context = run([
            RegisterEventHandler(OnProcessIO(target_action=checker, on_stdout=record)),
            container,
            GroupAction([PushRosNamespace("group"), SetParameter("greeting", "scoped"), loader], scoped=True),
            checker,
        ])  # fmt: skip
    assert code == 0
    assert "LOADED /group/second /ns/first" in "".join(listed)
    assert sorted(log.read_text().splitlines()) == [
        "/group/second greeting=scoped chatter=/group/chatter",
        "/ns/first greeting=hello chatter=/ns/talk",
    ]
    assert (
        "Failed to load node 'cpp' of type 'image_tools::ShowImage' in container '/box': "
        "Failed to find class with the requested plugin name." in records.messages
    )
    assert [get_node_name_count(context, n) for n in ("/box", "/ns/first", "/group/second", "/cpp")] == [1, 1, 1, 0]


@pytest.mark.slow
def test_the_composition_tutorial_s_talker_and_listener_talk_in_one_container(router: str) -> None:
    heard: list[str] = []

    def on_output(event) -> list | None:
        heard.extend(line for line in event.text.decode().splitlines() if "I heard: [Hello World: 1]" in line)
        return [Shutdown(reason="heard")] if heard else None

    container = ComposableNodeContainer(
        package="rclcpp_components",
        executable="component_container",
        name="ComponentManager",
        namespace="",
        output="screen",
        composable_node_descriptions=[
            ComposableNode(package="composition", plugin="composition::Talker"),
            ComposableNode(package="composition", plugin="composition::Listener"),
        ],
    )
    code, context = run([
        RegisterEventHandler(OnProcessIO(target_action=container, on_stdout=on_output, on_stderr=on_output)),
        container,
    ])  # fmt: skip
    assert code == 0
    assert "[listener]: I heard: [Hello World: 1]" in heard[0]
    assert [get_node_name_count(context, n) for n in ("/talker", "/listener")] == [1, 1]
