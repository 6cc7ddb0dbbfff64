"""A Gazebo package laid out as community ones are (test helper): models/ and worlds/ made findable by an
environment hook, a world including Fuel's ground plane and sun, a robot model with a COLLADA mesh and a
merged-in sensor kit, and a launch file that runs `gz sim` through ExecuteProcess next to GUI-only tools."""

from __future__ import annotations

import shutil
from pathlib import Path

DATA = Path(__file__).resolve().parent / "data"
PKG = "wedge_gazebo"

FILES: dict[str, str] = {
    "package.xml": f"""<?xml version="1.0"?>
<package format="3">
  <name>{PKG}</name>
  <version>0.1.0</version>
  <description>Worlds and models for the wedge robot</description>
  <maintainer email="a@b.c">a</maintainer>
  <license>Apache-2.0</license>
  <buildtool_depend>ament_cmake</buildtool_depend>
  <exec_depend>ros_gz_sim</exec_depend>
  <exec_depend>rqt_graph</exec_depend>
  <export><build_type>ament_cmake</build_type></export>
</package>
""",
    "CMakeLists.txt": f"""cmake_minimum_required(VERSION 3.8)
project({PKG})
find_package(ament_cmake REQUIRED)
install(DIRECTORY launch models worlds DESTINATION share/${{PROJECT_NAME}})
ament_environment_hooks("${{CMAKE_CURRENT_SOURCE_DIR}}/hooks/${{PROJECT_NAME}}.dsv.in")
ament_environment_hooks("${{CMAKE_CURRENT_SOURCE_DIR}}/hooks/${{PROJECT_NAME}}.sh.in")
ament_package()
""",
    # as in ros_gz_project_template: the .dsv wins over its .sh sibling
    f"hooks/{PKG}.dsv.in": "prepend-non-duplicate;GZ_SIM_RESOURCE_PATH;share/@PROJECT_NAME@/models\n"
    "prepend-non-duplicate;GZ_SIM_RESOURCE_PATH;share/@PROJECT_NAME@/worlds\n",
    f"hooks/{PKG}.sh.in": 'ament_prepend_unique_value GZ_SIM_RESOURCE_PATH "$AMENT_CURRENT_PREFIX/nowhere"\n',
    "models/sensor_kit/model.config": '<?xml version="1.0"?>\n<model><name>sensor_kit</name>'
    '<sdf version="1.9">model.sdf</sdf></model>\n',
    "models/sensor_kit/model.sdf": """<?xml version="1.0"?>
<sdf version="1.9">
  <model name="sensor_kit">
    <link name="mast">
      <pose>0 0 0.05 0 0 0</pose>
      <inertial><mass>0.05</mass><inertia><ixx>1e-5</ixx><iyy>1e-5</iyy><izz>1e-5</izz></inertia></inertial>
      <visual name="v"><geometry><cylinder><radius>0.01</radius><length>0.1</length></cylinder></geometry></visual>
    </link>
  </model>
</sdf>
""",
    "models/wedge_bot/model.config": '<?xml version="1.0"?>\n<model><name>wedge_bot</name>'
    '<sdf version="1.9">model.sdf</sdf></model>\n',
    "models/wedge_bot/model.sdf": """<?xml version="1.0"?>
<sdf version="1.9">
  <model name="wedge_bot">
    <link name="body">
      <inertial><mass>2</mass><inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.01</izz></inertia></inertial>
      <collision name="c">
        <geometry><mesh><uri>model://wedge_bot/meshes/wedge.dae</uri><scale>2 2 2</scale></mesh></geometry>
      </collision>
      <visual name="v">
        <geometry><mesh><uri>model://wedge_bot/meshes/wedge.dae</uri><scale>2 2 2</scale></mesh></geometry>
      </visual>
    </link>
    <include merge="true">
      <uri>model://sensor_kit</uri>
      <pose relative_to="body">0.1 0.05 0.1 0 0 0</pose>
    </include>
    <joint name="mast_mount" type="fixed"><parent>body</parent><child>mast</child></joint>
  </model>
</sdf>
""",
    "worlds/wedge_world.sdf": """<?xml version="1.0" ?>
<!-- Try: gz service -s /world/wedge_world/create --reqtype gz.msgs.EntityFactory -- as Gazebo's examples say -->
<sdf version="1.9">
  <world name="wedge_world">
    <physics name="1ms" type="ignored"><max_step_size>0.001</max_step_size></physics>
    <plugin filename="gz-sim-physics-system" name="gz::sim::systems::Physics"/>
    <plugin filename="gz-sim-user-commands-system" name="gz::sim::systems::UserCommands"/>
    <plugin filename="gz-sim-scene-broadcaster-system" name="gz::sim::systems::SceneBroadcaster"/>
    <include><uri>https://fuel.gazebosim.org/1.0/OpenRobotics/models/Sun</uri></include>
    <include><uri>https://fuel.gazebosim.org/1.0/OpenRobotics/models/Ground Plane</uri></include>
    <include>
      <uri>model://wedge_bot</uri>
      <pose>1 -2 0.3 0 0 0</pose>
    </include>
  </world>
</sdf>
""",
    "launch/sim.launch.py": """from launch import LaunchDescription
from launch.actions import ExecuteProcess
from launch_ros.actions import Node


def generate_launch_description():
    return LaunchDescription([
        ExecuteProcess(cmd=['gz', 'sim', '-r', '-s', 'wedge_world.sdf'], output='screen'),
        Node(package='rqt_graph', executable='rqt_graph'),
    ])
""",
}


def build(root: Path) -> Path:
    """The workspace (root/ws) with the package in src/; returns the workspace root."""
    pkg = root / "ws" / "src" / PKG
    for rel, text in FILES.items():
        path = pkg / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
    (pkg / "models" / "wedge_bot" / "meshes").mkdir()
    shutil.copy(DATA / "wedge.dae", pkg / "models" / "wedge_bot" / "meshes" / "wedge.dae")
    return root / "ws"
