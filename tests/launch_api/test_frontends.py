"""A third-party frontend extension: an action and a substitution exposed to XML and YAML.

The extension is a module registered in the `launch.frontend.launch_extension` entry point group of a
distribution on sys.path, found by launch's Parser as ros2/launch finds launch_ros.
"""

from __future__ import annotations

import io
import sys
import textwrap

import pytest

from diffctl.launch import LaunchService
from diffctl.launch.frontend import Parser

EXTENSION = '''
"""A launch extension: <say text=".."/> appends to SAID, $(upper text) upper-cases."""
from diffctl.launch import Action, Substitution
from diffctl.launch.frontend import expose_action, expose_substitution
from diffctl.launch.utilities import perform_substitutions

SAID = []


@expose_substitution('upper')
class Upper(Substitution):
    def __init__(self, text):
        self.text = text

    @classmethod
    def parse(cls, data):
        return cls, {'text': data[0]}

    def perform(self, context):
        return perform_substitutions(context, self.text).upper()


@expose_action('say')
class Say(Action):
    def __init__(self, *, text, **kwargs):
        super().__init__(**kwargs)
        self.text = text

    @classmethod
    def parse(cls, entity, parser):
        _, kwargs = super().parse(entity, parser)
        kwargs['text'] = parser.parse_substitution(entity.get_attr('text'))
        return cls, kwargs

    def execute(self, context):
        SAID.append(perform_substitutions(context, self.text))
'''


@pytest.fixture(scope='module')
def installed_extension(tmp_path_factory: pytest.TempPathFactory):
    """The extension installed once: its `expose_*` registrations are global to the process, as in ROS."""
    root = tmp_path_factory.mktemp('ext')
    (root / 'diffctl_test_launch_ext.py').write_text(EXTENSION)
    dist = root / 'diffctl_test_launch_ext-1.0.dist-info'
    dist.mkdir()
    (dist / 'METADATA').write_text('Metadata-Version: 2.1\nName: diffctl-test-launch-ext\nVersion: 1.0\n')
    (dist / 'entry_points.txt').write_text(
        '[launch.frontend.launch_extension]\ndiffctl_test_launch_ext = diffctl_test_launch_ext\n')
    with pytest.MonkeyPatch.context() as patch:
        patch.syspath_prepend(str(root))
        patch.setattr(Parser, 'extensions_loaded', False)  # read the entry points again
        Parser.load_launch_extensions()
        yield sys.modules['diffctl_test_launch_ext']


@pytest.fixture
def extension(installed_extension):
    installed_extension.SAID.clear()
    return lambda: installed_extension.SAID


XML = '''
<launch>
  <let name="who" value="xml"/>
  <say text="hi $(upper $(var who))" if="true"/>
  <group><say text="$(upper 'in group')"/></group>
</launch>
'''

YAML = '''
launch:
- let: {name: who, value: yaml}
- say: {text: 'hi $(upper $(var who))', if: 'true'}
- group:
    children:
    - say: {text: "$(upper 'in group')"}
'''


@pytest.mark.parametrize(('text', 'frontend'), [(XML, 'xml'), (YAML, 'yaml')])
def test_exposed_action_and_substitution_from_markup(extension, text: str, frontend: str) -> None:
    stream = io.StringIO(textwrap.dedent(text))
    stream.name = f'ext.launch.{frontend}'
    root, parser = Parser.load(stream)
    assert type(parser).__module__ == f'diffctl.launch_{frontend}.parser'
    description = parser.parse_description(root)
    service = LaunchService()
    service.include_launch_description(description)
    assert service.run() == 0
    assert extension() == [f'hi {frontend.upper()}', 'IN GROUP']


def test_unknown_tag_and_substitution_name_their_place(extension) -> None:
    root, parser = Parser.load(io.StringIO('<launch>\n  <say text="a"/>\n  <shout text="b"/>\n</launch>\n'))
    with pytest.raises(RuntimeError, match=r'^<string>:3: Unrecognized entity of the type: shout'):
        parser.parse_description(root)
    root, parser = Parser.load(io.StringIO('<launch>\n  <say text="$(lower b)"/>\n</launch>\n'))
    with pytest.raises(RuntimeError, match='Unknown substitution: lower') as raised:
        parser.parse_description(root)
    assert raised.value.launch_location == '<string>:2'


def test_yaml_scalars_where_text_is_expected_are_read_as_written(capsys: pytest.CaptureFixture[str]) -> None:
    # launch_yaml refuses all three (`expected to be of type '<class 'str'>', got '<class 'bool'>'`, …); the same
    # attributes in XML are text, and so are they here
    stream = io.StringIO(textwrap.dedent('''
        launch:
        - executable:
            cmd: sh -c 'echo "$DIFFCTL_T"'
            name: t
            output: screen
            respawn: false
            respawn_delay: 1
            sigterm_timeout: 3
            env: [{name: DIFFCTL_T, value: 1e3}]
    '''))
    stream.name = 'scalars.launch.yaml'
    root, parser = Parser.load(stream)
    service = LaunchService()
    service.include_launch_description(parser.parse_description(root))
    assert service.run() == 0
    assert '] 1e3\n' in capsys.readouterr().out  # as written, not YAML's 1000.0
