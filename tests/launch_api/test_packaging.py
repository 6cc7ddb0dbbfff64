"""The ROS names of the launch packages, what importing them costs, and what the core may import."""

from __future__ import annotations

import subprocess
import sys
import textwrap


def run(code: str) -> str:
    result = subprocess.run([sys.executable, '-W', 'error', '-c', textwrap.dedent(code)],
                            capture_output=True, text=True, timeout=60)
    assert result.returncode == 0, result.stderr
    return result.stdout


def test_ros_names_are_the_same_modules() -> None:
    out = run('''
        import sys
        import launch
        print('asyncio' in sys.modules)  # `import launch` alone stays cheap
        import launch_xml, launch_yaml  # the launcher makes them so for every file: their parsers wait for use
        print(sorted(m for m in sys.modules if m.startswith(('diffctl.launch_xml.', 'diffctl.launch_yaml.'))))
        import launch.actions.execute_process as ros
        import diffctl.launch.actions.execute_process as ours
        from launch.actions import ExecuteProcess
        from launch.actions.execute_local import _Run  # private names too
        from launch_xml.launch_description_sources import XMLLaunchDescriptionSource
        from diffctl.launch_xml.launch_description_sources import XMLLaunchDescriptionSource as Ours
        assert ros is ours and ExecuteProcess is ours.ExecuteProcess and XMLLaunchDescriptionSource is Ours
        assert launch.LaunchService is sys.modules['diffctl.launch.launch_service'].LaunchService
        try:
            import launch.no_such_module
        except ModuleNotFoundError as e:
            print(e)
    ''')
    assert out.splitlines() == ['False', '[]', "No module named 'launch.no_such_module'"]


def test_the_core_imports_no_other_layer() -> None:
    out = run('''
        import importlib, pkgutil, sys
        import diffctl.launch, diffctl.launch_xml, diffctl.launch_yaml
        for package in (diffctl.launch, diffctl.launch_xml, diffctl.launch_yaml):
            for info in pkgutil.walk_packages(package.__path__, package.__name__ + '.'):
                importlib.import_module(info.name)
        layers = ('diffctl.launch_legacy', 'diffctl.launch_ros', 'diffctl.bus', 'diffctl.client', 'diffctl.sim',
                  'diffctl.control', 'diffctl.cli')
        print(sorted(m for m in sys.modules if m.startswith(layers)))
    ''')
    assert out.strip() == '[]'
