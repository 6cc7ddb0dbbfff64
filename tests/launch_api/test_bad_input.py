"""Bad launch files: one error naming the file and line, a non-zero return code, nothing left running."""

from __future__ import annotations

import textwrap
from pathlib import Path

import pytest

from diffctl.launch import LaunchDescription, LaunchService
from diffctl.launch.actions import IncludeLaunchDescription
from diffctl.launch.launch_description_sources import FrontendLaunchDescriptionSource, PythonLaunchDescriptionSource

RAISING_ACTION = '''\
from launch import Action, LaunchDescription
from launch.actions import ExecuteProcess


class Explode(Action):
    def execute(self, context):
        raise ValueError('the custom action failed')


def generate_launch_description():
    return LaunchDescription([Explode(), ExecuteProcess(cmd=['sleep', '30'])])
'''


def run_and_read_errors(source, capsys: pytest.CaptureFixture[str]) -> tuple[int, list[str]]:
    """The return code, and each error logged (with the lines that continue it)."""
    service = LaunchService()
    service.include_launch_description(LaunchDescription([IncludeLaunchDescription(source)]))
    code = service.run()
    errors: list[str] = []
    current = None
    for line in capsys.readouterr().out.splitlines():
        if line.startswith('['):
            current = None
        if line.startswith('[ERROR]'):
            errors.append(line)
            current = len(errors) - 1
        elif current is not None:
            errors[current] += '\n' + line
    return code, errors


def test_a_custom_action_that_raises(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = tmp_path / 'explode.launch.py'
    path.write_text(RAISING_ACTION)
    code, errors = run_and_read_errors(PythonLaunchDescriptionSource(str(path)), capsys)
    assert code == 1
    assert errors == [
        '[ERROR] [launch]: Caught exception in launch (see debug for traceback): '
        f'{path}:7: the custom action failed'
    ]  # and the sleep after it never started


@pytest.mark.parametrize(('name', 'text', 'line', 'message'), [
    ('subst.launch.xml', '<launch>\n  <log message="ok"/>\n  <log message="$(var nope)"/>\n</launch>\n', 3,
     "launch configuration 'nope' does not exist"),
    ('tag.launch.yaml', 'launch:\n- log: {message: ok}\n- nope: {a: 1}\n', 3,
     'Unrecognized entity of the type: nope'),
    ('attr.launch.xml', '<launch>\n  <arg name="a" defualt="1"/>\n</launch>\n', 2,
     "Unexpected attribute(s) found in `arg`: {'defualt'}"),
    # what each frontend said, the XML one first (the file's name claims it)
    ('syntax.launch.xml', '<launch>\n  <log message="a">\n</launch>\n', 3, 'mismatched tag'),
])
def test_markup_errors_name_file_and_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], name: str, text: str, line: int, message: str
) -> None:
    path = tmp_path / name
    path.write_text(textwrap.dedent(text))
    code, errors = run_and_read_errors(FrontendLaunchDescriptionSource(str(path)), capsys)
    assert code == 1
    assert len(errors) == 1, errors
    assert f'{path}:{line}: ' in errors[0] and message in errors[0], errors[0]
