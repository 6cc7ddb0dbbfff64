"""ament_python data_files read without running setup.py, against setuptools' own reading of the same files."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from diffctl.workspace.setup_py import python_install_index
from tests.workspace.conftest import package_xml, write_tree

FILES = {
    "package.xml": package_xml("py_robot", "ament_python"),
    "resource/py_robot": "",
    "launch/a.launch.py": "a",
    "launch/b.launch.xml": "b",
    "launch/sub/deep.launch.py": "deep",
    "config/c.yaml": "c",
    "urdf/r.urdf": "r",
    "py_robot/__init__.py": "",
    "py_robot/node.py": "def main():\n    print('hello from node')\n",
}

SETUPS = {
    "ros2_template": """
import os
from glob import glob
from setuptools import find_packages, setup

package_name = 'py_robot'

setup(
    name=package_name,
    version='0.0.1',
    packages=find_packages(exclude=['test']),
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml']),
        (os.path.join('share', package_name, 'launch'), glob(os.path.join('launch', '*launch.[pxy][yma]*'))),
        (os.path.join('share', package_name, 'config'), glob('config/*.yaml')),
    ],
    entry_points={'console_scripts': ['talker = py_robot.node:main']},
)
""",
    "variables_fstrings_comprehension": """
import glob
import os
import setuptools

package_name = "py_robot"
share = f"share/{package_name}"
data_files = [("share/ament_index/resource_index/packages", ["resource/" + package_name])]
data_files.append((share, ["package.xml"]))
data_files += [(os.path.join(share, d), glob.glob(d + "/*")) for d in ["config", "urdf"]]
data_files.extend([("share/%s/launch/sub" % package_name, sorted(glob.glob("launch/sub/*.py")))])

setuptools.setup(name=package_name, data_files=data_files)
""",
}


def setuptools_data_files(pkg: Path) -> dict[str, str]:
    """Destination → source as setuptools itself reads setup.py/setup.cfg (run in a child: it executes them)."""
    code = (
        "import json, os, sys\n"
        "from distutils.core import run_setup\n"
        "os.chdir(sys.argv[1])\n"
        "d = run_setup('setup.py', script_args=['--dry-run'], stop_after='config')\n"
        "print(json.dumps([[dest, list(files)] for dest, files in (d.data_files or [])]))\n"
    )
    out = subprocess.run(
        [sys.executable, "-c", code, str(pkg)], check=True, capture_output=True, text=True, timeout=120
    ).stdout
    mapping = {}
    for dest, files in json.loads(out.strip().splitlines()[-1]):
        for f in files:
            mapping[f"{dest.rstrip('/')}/{Path(f).name}"] = str((pkg / f).resolve())
    return mapping


def ours(pkg: Path) -> dict[str, str]:
    index = python_install_index(pkg, "py_robot")
    assert not index.problems, index.problems
    return {dest: str(f.source.resolve()) for dest, f in index.files.items()}


@pytest.mark.parametrize("case", sorted(SETUPS))
def test_data_files_match_what_setuptools_reads(case: str, tmp_path: Path) -> None:
    pkg = write_tree(tmp_path / "py_robot", {**FILES, "setup.py": SETUPS[case]})
    expected = setuptools_data_files(pkg)
    assert len(expected) >= 4
    assert ours(pkg) == expected


def test_setup_cfg_data_files_match_what_setuptools_reads(tmp_path: Path) -> None:
    pkg = write_tree(
        tmp_path / "py_robot",
        {
            **FILES,
            "setup.py": "from setuptools import setup\nsetup()\n",
            "setup.cfg": "[metadata]\nname = py_robot\n\n[options.data_files]\n"
            "share/py_robot = package.xml\nshare/py_robot/launch =\n    launch/*.py\n    launch/b.launch.xml\n",
        },
    )
    expected = setuptools_data_files(pkg)
    assert "share/py_robot/launch/a.launch.py" in expected
    assert ours(pkg) == expected


def test_console_scripts_and_the_manifest_without_data_files(tmp_path: Path) -> None:
    pkg = write_tree(
        tmp_path / "py_robot",
        {**FILES, "setup.py": "from setuptools import setup\nsetup(name='py_robot', "
         "entry_points={'console_scripts': ['talker = py_robot.node:main']})\n"},
    )
    index = python_install_index(pkg, "py_robot")
    assert index.console_scripts == {"talker": "py_robot.node:main"}
    # colcon installs package.xml itself when data_files leaves it out
    assert list(index.files) == ["share/py_robot/package.xml"]


def test_code_diffctl_will_not_run_is_reported_not_guessed(tmp_path: Path) -> None:
    pkg = write_tree(
        tmp_path / "py_robot",
        {
            **FILES,
            "setup.py": """import os
from setuptools import setup

def package_files(directory):
    return [os.path.join(p, f) for p, _, fs in os.walk(directory) for f in fs]

setup(name='py_robot',
      data_files=[('share/py_robot', ['package.xml']),
                  ('share/py_robot/launch', package_files('launch')),
                  ('share/py_robot/missing', ['nope.yaml']),
                  ('share/py_robot/dir', ['launch/sub'])])
""",
        },
    )
    marker = tmp_path / "ran"
    (pkg / "setup.py").write_text((pkg / "setup.py").read_text() + f"\nopen({str(marker)!r}, 'w')\n")
    index = python_install_index(pkg, "py_robot")
    assert not marker.exists(), "setup.py was executed"
    assert "share/py_robot/package.xml" in index.files
    assert index.problems == [
        "setup.py:9: data_files uses code diffctl does not run (it never executes setup.py)",
        "setup.py:10: data file nope.yaml does not exist",
        "setup.py:11: data_files names the directory launch/sub (only files are installed)",
    ]


def test_entries_naming_missing_files_or_directories_are_problems(tmp_path: Path) -> None:
    pkg = write_tree(
        tmp_path / "py_robot",
        {**FILES, "setup.py": "from setuptools import setup\nsetup(data_files=[('share/py_robot/x', "
         "['nope.yaml', 'launch/sub'])])\n"},
    )
    problems = python_install_index(pkg, "py_robot").problems
    assert problems == [
        "setup.py:2: data file nope.yaml does not exist",
        "setup.py:2: data_files names the directory launch/sub (only files are installed)",
    ]
