"""The linter tests `ros2 pkg create --build-type ament_python` writes (test_copyright.py, test_flake8.py,
test_pep257.py) run under `diffctl test` with no path as under `colcon test`: ament_flake8 / ament_pep257 are
Jazzy's own wheels, ament_copyright is diffctl's (diffctl/testing/copyright.py)."""

from __future__ import annotations

import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

HEADER = """\
# Copyright 2024 Jane Roboticist
#
# Licensed under the Apache License, Version 2.0 (the "License");
# you may not use this file except in compliance with the License.
# You may obtain a copy of the License at
#
#     http://www.apache.org/licenses/LICENSE-2.0
#
# Unless required by applicable law or agreed to in writing, software
# distributed under the License is distributed on an "AS IS" BASIS,
# WITHOUT WARRANTIES OR CONDITIONS OF ANY KIND, either express or implied.
# See the License for the specific language governing permissions and
# limitations under the License.

"""

# As ros2pkg's ament_python templates write them (the copyright test with its `skip` removed, as the template
# says to once the sources have a header).
TEST_COPYRIGHT = HEADER + """\
from ament_copyright.main import main
import pytest


@pytest.mark.copyright
@pytest.mark.linter
def test_copyright():
    rc = main(argv=['.', 'test'])
    assert rc == 0, 'Found errors'
"""
TEST_FLAKE8 = HEADER + """\
from ament_flake8.main import main_with_errors
import pytest


@pytest.mark.flake8
@pytest.mark.linter
def test_flake8():
    rc, errors = main_with_errors(argv=[])
    assert rc == 0, \\
        'Found %d code style errors / warnings:\\n' % len(errors) + \\
        '\\n'.join(errors)
"""
TEST_PEP257 = HEADER + """\
from ament_pep257.main import main
import pytest


@pytest.mark.linter
@pytest.mark.pep257
def test_pep257():
    rc = main(argv=['.', 'test'])
    assert rc == 0, 'Found code style errors / warnings'
"""
NODE = HEADER + '''\
import sys


def main(args=None):
    """Print a greeting."""
    print('Hi from my_pkg.', file=sys.stderr)


if __name__ == '__main__':
    main()
'''


def ament_python_package(root: Path) -> Path:
    pkg = root / "ws" / "src" / "my_pkg"
    for folder in ("my_pkg", "resource", "test"):
        (pkg / folder).mkdir(parents=True)
    (pkg / "package.xml").write_text(textwrap.dedent("""\
        <?xml version="1.0"?>
        <package format="3"><name>my_pkg</name><version>0.0.0</version><description>TODO</description>
        <maintainer email="jane@example.com">jane</maintainer><license>Apache-2.0</license>
        <test_depend>ament_copyright</test_depend><test_depend>ament_flake8</test_depend>
        <test_depend>ament_pep257</test_depend><test_depend>python3-pytest</test_depend>
        <export><build_type>ament_python</build_type></export></package>
        """))
    (pkg / "setup.py").write_text(
        "from setuptools import find_packages, setup\n\npackage_name = 'my_pkg'\n\nsetup(\n    name=package_name,\n"
        "    version='0.0.0',\n    packages=find_packages(exclude=['test']),\n)\n")
    (pkg / "setup.cfg").write_text(
        "[develop]\nscript_dir=$base/lib/my_pkg\n[install]\ninstall_scripts=$base/lib/my_pkg\n")
    (pkg / "resource" / "my_pkg").write_text("")
    (pkg / "my_pkg" / "__init__.py").write_text("")
    (pkg / "my_pkg" / "my_node.py").write_text(NODE)
    (pkg / "test" / "test_copyright.py").write_text(TEST_COPYRIGHT)
    (pkg / "test" / "test_flake8.py").write_text(TEST_FLAKE8)
    (pkg / "test" / "test_pep257.py").write_text(TEST_PEP257)
    return root / "ws"


def _diffctl_test(ws: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "diffctl", "test", "-j", "2"], cwd=ws, capture_output=True,
                          text=True, timeout=120, start_new_session=True)


def test_generated_linter_tests_pass_and_a_planted_flake8_error_fails(tmp_path: Path) -> None:
    ws = ament_python_package(tmp_path)
    r = _diffctl_test(ws)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "3 test files, 3 passed, 0 failed" in r.stdout
    assert r.stdout.count("1 passed") == 3, r.stdout  # each linter ran (none skipped)

    node = ws / "src" / "my_pkg" / "my_pkg" / "my_node.py"
    node.write_text(NODE.replace("import sys\n", "import os\nimport sys\n"))
    r = _diffctl_test(ws)
    assert r.returncode == 1, r.stdout
    assert "FAILED my_pkg/test_flake8.py" in r.stdout
    assert "F401 'os' imported but unused" in r.stdout
    assert "3 test files, 2 passed, 1 failed" in r.stdout


def _copyright(tmp_path: Path, name: str, text: str, capsys: pytest.CaptureFixture[str]) -> tuple[int, str]:
    from diffctl.testing.copyright import main

    (tmp_path / name).write_text(text)
    rc = main(["--verbose", str(tmp_path / name)])
    out = capsys.readouterr()
    return rc, out.out + out.err


def test_copyright_header_rules(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    rc, out = _copyright(tmp_path, "a.py", "#!/usr/bin/env python3\n# -*- coding: utf-8 -*-\n\n" + HEADER, capsys)
    assert rc == 0 and "copyright=Jane Roboticist (2024), license=apache2" in out
    rc, out = _copyright(tmp_path, "b.py", "import os\n", capsys)
    assert rc == 1 and "could not find copyright notice" in out and "1 errors, checked 1 files" in out
    rc, out = _copyright(tmp_path, "c.py", "# Copyright 2020-2023, 2024 Someone\n# All mine.\n", capsys)
    assert rc == 1 and "license=<unknown>" in out
    rc, out = _copyright(tmp_path, "d.cpp", "/*\n * Copyright (c) 2019 ACME\n *\n * Use of this source code is "
                         "governed by an MIT-style\n * license that can be found in the LICENSE file or at\n"
                         " * https://opensource.org/licenses/MIT.\n */\nint x;\n", capsys)
    assert rc == 0 and "license=mit" in out
    rc, out = _copyright(tmp_path, "e.py", "", capsys)
    assert rc == 0 and "file empty" in out
    # a license text that is rearranged is not that license
    swapped = HEADER.replace("# You may obtain a copy of the License at\n", "").replace(
        "# limitations under the License.\n", "# limitations under the License.\n# You may obtain a copy of the "
        "License at\n")
    rc, out = _copyright(tmp_path, "f.py", swapped, capsys)
    assert rc == 1 and "license=<unknown>" in out


def test_copyright_repository_root_needs_license_and_contributing(tmp_path: Path,
                                                                  capsys: pytest.CaptureFixture[str]) -> None:
    from diffctl.testing.copyright import main

    (tmp_path / ".git").mkdir()
    (tmp_path / "a.py").write_text(HEADER)
    assert main([str(tmp_path)]) == 1
    out = capsys.readouterr().err
    assert "CONTRIBUTING.md: file not found" in out and "LICENSE: file not found" in out
    (tmp_path / "LICENSE").write_text("\n                                 Apache License\n                   "
                                      "        Version 2.0, January 2004\n        http://www.apache.org/licenses/\n")
    (tmp_path / "CONTRIBUTING.md").write_text(
        "Any contribution that you make to this repository will\nbe under the Apache 2 License, as dictated by that\n"
        "[license](http://www.apache.org/licenses/LICENSE-2.0.html):\n")
    assert main([str(tmp_path)]) == 0, capsys.readouterr().err


def test_a_missing_ament_linter_is_named_with_its_install_line(tmp_path: Path) -> None:
    test_dir = tmp_path / "test"
    test_dir.mkdir()
    (test_dir / "test_cppcheck.py").write_text(
        "from ament_cppcheck.main import main\n\n\ndef test_cppcheck():\n    assert main(argv=[]) == 0\n")
    r = subprocess.run([sys.executable, "-m", "diffctl", "test", str(test_dir / "test_cppcheck.py")], cwd=tmp_path,
                       capture_output=True, text=True, timeout=60, start_new_session=True)
    assert r.returncode == 2  # the file cannot run (it does not import)
    assert "hint: ament_cppcheck (an ament linter) is not installed; try: pip install ros-jazzy-ament-cppcheck" \
        in r.stdout, r.stdout
    from diffctl.testing.cli import missing_linter_hint

    assert "pip install 'diffctl[lint]'" in missing_linter_hint("ModuleNotFoundError: No module named 'ament_pep257'")
