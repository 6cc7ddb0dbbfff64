"""Every public module and name of launch_ros (Jazzy 0.26: `__all__`, else the module's top-level definitions, as
written down from its sources) imports under ROS's names as diffctl's own modules; launch's Parser finds
launch_ros's tags and substitutions through the entry point, in a process that never imported launch_ros."""

from __future__ import annotations

import importlib
import subprocess
import sys
import textwrap

import pytest

JAZZY = {
    "launch_ros": "actions descriptions event_handlers events ros_adapters substitutions",
    "launch_ros.actions": (
        "ComposableNodeContainer LifecycleNode LifecycleTransition LoadComposableNodes Node PushROSNamespace "
        "PushRosNamespace ROSTimer RosTimer SetParameter SetParametersFromFile SetRemap SetROSLogDir SetUseSimTime"
    ),
    "launch_ros.actions.composable_node_container": "ComposableNodeContainer",
    "launch_ros.actions.lifecycle_node": "LifecycleNode",
    "launch_ros.actions.lifecycle_transition": "LifecycleTransition match_node_name_start_goal match_node_name_goal",
    "launch_ros.actions.load_composable_nodes": "LoadComposableNodes get_composable_node_load_request",
    "launch_ros.actions.node": "NodeActionExtension Node instantiate_extension g_entry_points_impl get_extensions",
    "launch_ros.actions.push_ros_namespace": "PushROSNamespace",
    "launch_ros.actions.ros_timer": "ROSTimer",
    "launch_ros.actions.set_parameter": "SetParameter",
    "launch_ros.actions.set_parameters_from_file": "SetParametersFromFile",
    "launch_ros.actions.set_remap": "SetRemap",
    "launch_ros.actions.set_ros_log_dir": "SetROSLogDir",
    "launch_ros.actions.set_use_sim_time": "SetUseSimTime",
    "launch_ros.descriptions": "ComposableNode Parameter ParameterFile ParameterValue",
    "launch_ros.descriptions.composable_node": "ComposableNode",
    "launch_ros.event_handlers": "OnStateTransition",
    "launch_ros.event_handlers.on_state_transition": "OnStateTransition",
    "launch_ros.events": "lifecycle matches_node_name",
    "launch_ros.events.lifecycle": "ChangeState matches_node_name StateTransition",
    "launch_ros.events.lifecycle.change_state": "ChangeState",
    "launch_ros.events.lifecycle.lifecycle_node_matchers": "matches_node_name",
    "launch_ros.events.lifecycle.state_transition": "StateTransition",
    "launch_ros.events.matchers": "matches_node_name",
    "launch_ros.events.matchers.matches_node_name": "matches_node_name",
    "launch_ros.parameter_descriptions": "ParameterValue Parameter ParameterFile",
    "launch_ros.parameters_type": (
        "SomeParameterFile SomeParameterName SomeParameterValue SomeParameterValue_types_tuple SomeParametersDict "
        "SomeParameters ParameterFile ParameterName ParameterValue ParametersDict Parameters EvaluatedParameterValue "
        "EvaluatedParameters"
    ),
    "launch_ros.remap_rule_type": "SomeRemapRule SomeRemapRules RemapRule RemapRules",
    "launch_ros.ros_adapters": "ROSAdapter get_ros_adapter get_ros_node",
    "launch_ros.substitutions": "ExecutableInPackage FindPackage FindPackagePrefix FindPackageShare Parameter",
    "launch_ros.substitutions.executable_in_package": "ExecutableInPackage",
    "launch_ros.substitutions.find_package": "FindPackage FindPackagePrefix FindPackageShare",
    "launch_ros.substitutions.parameter": "Parameter",
    # its __all__ also lists evaluate_parameters_dict and normalize_parameters_dict, which it lacks
    "launch_ros.utilities": (
        "add_node_name evaluate_parameters get_node_name_count is_namespace_absolute is_root_namespace "
        "make_namespace_absolute normalize_parameters normalize_remap_rule normalize_remap_rules prefix_namespace "
        "to_parameters_list"
    ),
    "launch_ros.utilities.evaluate_parameters": "evaluate_parameter_dict evaluate_parameters",
    "launch_ros.utilities.namespace_utils": (
        "is_root_namespace is_namespace_absolute prefix_namespace OptionalText make_namespace_absolute"
    ),
    "launch_ros.utilities.normalize_parameters": "normalize_parameter_dict normalize_parameters",
    "launch_ros.utilities.normalize_remap_rule": "normalize_remap_rule normalize_remap_rules",
    "launch_ros.utilities.plugin_support": "PluginException satisfies_version get_upper_bound_caret_version",
    "launch_ros.utilities.to_parameters_list": "to_parameters_list",
    "launch_ros.utilities.track_node_names": "add_node_name get_node_name_count",
}


@pytest.mark.parametrize("module", sorted(JAZZY))
def test_every_jazzy_module_and_name_is_diffctl_s(module: str) -> None:
    imported = importlib.import_module(module)
    assert imported is importlib.import_module("diffctl." + module)
    missing = [name for name in JAZZY[module].split() if not hasattr(imported, name)]
    assert not missing


def test_launch_finds_launch_ros_tags_through_the_entry_point() -> None:
    program = textwrap.dedent('''
        import io, sys
        from launch.frontend import Parser
        xml = io.StringIO("""<launch>
          <push-ros-namespace namespace="a"/><push_ros_namespace namespace="b"/>
          <set_parameter name="p" value="$(param q 1)"/><set_parameters_from_file filename="f.yaml"/>
          <set_remap from="x" to="y"/><set_ros_log_dir new_log_dir="logs"/><set_use_sim_time value="true"/>
          <ros_timer period="1.0"><log message="t"/></ros_timer>
          <node pkg="$(find-pkg-share launch_ros)" exec="$(exec-in-pkg talker demo_nodes_py)"/>
          <node_container pkg="rclcpp_components" exec="component_container" name="c" namespace="">
            <composable_node pkg="p" plugin="m:C" name="n"/>
          </node_container>
          <load_composable_node target="/c"><composable_node pkg="p" plugin="m:C" name="m"/></load_composable_node>
          <lifecycle_node exec="x" name="lc"/>
          <executable cmd="$(find-pkg-prefix launch_ros)"/>
        </launch>""")
        xml.name = "t.launch.xml"
        assert not any(m.startswith(("launch_ros", "diffctl.launch_ros")) for m in sys.modules)
        root, parser = Parser.load(xml)
        for entity in parser.parse_description(root).entities:
            print(type(entity).__module__, type(entity).__name__)
    ''')
    out = subprocess.run([sys.executable, "-c", program], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.split("\n")[:-1] == [
        "diffctl.launch_ros.actions.push_ros_namespace PushROSNamespace",
        "diffctl.launch_ros.actions.push_ros_namespace PushROSNamespace",
        "diffctl.launch_ros.actions.set_parameter SetParameter",
        "diffctl.launch_ros.actions.set_parameters_from_file SetParametersFromFile",
        "diffctl.launch_ros.actions.set_remap SetRemap",
        "diffctl.launch_ros.actions.set_ros_log_dir SetROSLogDir",
        "diffctl.launch_ros.actions.set_use_sim_time SetUseSimTime",
        "diffctl.launch_ros.actions.ros_timer ROSTimer",
        "diffctl.launch_ros.actions.node Node",
        "diffctl.launch_ros.actions.composable_node_container ComposableNodeContainer",
        "diffctl.launch_ros.actions.load_composable_nodes LoadComposableNodes",
        "diffctl.launch_ros.actions.lifecycle_node LifecycleNode",
        "diffctl.launch.actions.execute_process ExecuteProcess",
    ]
