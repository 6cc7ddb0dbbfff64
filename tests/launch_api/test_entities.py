"""Users' own actions, substitutions, conditions and handlers, run by a LaunchService from a script."""

from __future__ import annotations

import threading

import pytest

from diffctl.launch import Action, Condition, LaunchContext, LaunchDescription, LaunchService, Substitution
from diffctl.launch.actions import (
    DeclareLaunchArgument,
    GroupAction,
    OpaqueFunction,
    RegisterEventHandler,
    SetLaunchConfiguration,
    TimerAction,
)
from diffctl.launch.conditions import IfCondition
from diffctl.launch.event_handlers import OnExecutionComplete, OnShutdown
from diffctl.launch.substitutions import (
    EnvironmentVariable,
    LaunchConfiguration,
    PathJoinSubstitution,
    PathSubstitution,
    SubstitutionFailure,
)
from diffctl.launch.utilities import normalize_to_list_of_substitutions, perform_substitutions


class Greeting(Substitution):
    """'hello <who>', from the launch configuration `who`."""

    def perform(self, context: LaunchContext) -> str:
        return 'hello ' + context.launch_configurations['who']


class Record(Action):
    """Appends its text to `seen` and yields one more entity, as a custom action may."""

    def __init__(self, seen: list[str], text, **kwargs) -> None:
        super().__init__(**kwargs)
        self.seen = seen
        self.text = normalize_to_list_of_substitutions(text)

    def execute(self, context: LaunchContext):
        self.seen.append(perform_substitutions(context, self.text))
        return [OpaqueFunction(function=lambda ctx: self.seen.append('yielded'))]


def test_custom_entities_run_in_order_with_scopes_and_conditions() -> None:
    seen: list[str] = []
    who_is_set = Condition(predicate=lambda context: 'who' in context.launch_configurations)
    description = LaunchDescription([
        DeclareLaunchArgument('who', default_value='world'),
        Record(seen, [Greeting(), '!'], condition=who_is_set),
        Record(seen, 'never', condition=IfCondition('false')),
        GroupAction([SetLaunchConfiguration('who', 'group'), Record(seen, Greeting())]),
        Record(seen, LaunchConfiguration('who')),  # the group's `let` stayed in the group
    ])
    service = LaunchService()
    service.include_launch_description(description)
    assert service.run() == 0
    assert seen == ['hello world!', 'yielded', 'hello group', 'yielded', 'world', 'yielded']
    arguments = description.get_launch_arguments()
    assert [(a.name, a._conditionally_included) for a in arguments] == [('who', False)]


def test_perform_substitutions_in_a_bare_context(monkeypatch: pytest.MonkeyPatch) -> None:
    context = LaunchContext()
    context.launch_configurations['who'] = 'you'
    monkeypatch.setenv('DIFFCTL_LAUNCH_API_TEST', 'env')
    subs = normalize_to_list_of_substitutions(
        ['[', Greeting(), '|', EnvironmentVariable('DIFFCTL_LAUNCH_API_TEST'), '|',
         LaunchConfiguration('missing', default=3), ']'])
    assert perform_substitutions(context, subs) == '[hello you|env|3]'
    with pytest.raises(SubstitutionFailure, match="launch configuration 'missing' does not exist"):
        perform_substitutions(context, [LaunchConfiguration('missing')])


def test_paths_joined_from_substitution_lists_and_with_slash() -> None:
    # ros2_control_demos' jazzy launch files: PathSubstitution(FindPackageShare(p)) / 'urdf' / 'x.xacro';
    # a component may itself be a list (ros2/launch#838's documented 'robot_description/urdf/my_model.xacro')
    context = LaunchContext()
    context.launch_configurations['model'] = 'my_model'
    listed = PathJoinSubstitution(['robot_description', 'urdf', [LaunchConfiguration('model'), '.xacro']])
    assert listed.perform(context) == 'robot_description/urdf/my_model.xacro'
    slashed = PathSubstitution(Greeting()) / 'urdf' / [LaunchConfiguration('model'), '.xacro']
    assert isinstance(slashed, PathJoinSubstitution)
    context.launch_configurations['who'] = 'share'
    assert slashed.perform(context) == 'hello share/urdf/my_model.xacro'
    assert (PathSubstitution('/opt') / '/abs').perform(context) == '/abs'  # os.path.join's rule
    # Text pieces need no context, as in Jazzy, where each piece performs itself.
    assert PathJoinSubstitution(['share', 'urdf', 'x.xacro']).perform(None) == 'share/urdf/x.xacro'


def test_handlers_timers_and_events_from_another_thread() -> None:
    happened: list[str] = []
    marker = OpaqueFunction(function=lambda context: happened.append('marker'))
    description = LaunchDescription([
        RegisterEventHandler(OnExecutionComplete(
            target_action=marker, on_completion=[OpaqueFunction(function=lambda c: happened.append('completed'))])),
        RegisterEventHandler(OnShutdown(on_shutdown=lambda event, c: happened.append(f'shutdown: {event.reason}'))),
        marker,
        TimerAction(period=0.05, actions=[OpaqueFunction(function=lambda c: happened.append('timer'))]),
    ])
    service = LaunchService()
    service.include_launch_description(description)

    def from_elsewhere() -> None:
        # waits for the service's own progress (10 s at most), then stops it from this thread
        for _ in range(1000):
            if 'timer' in happened:
                break
            threading.Event().wait(0.01)
        service.shutdown()

    helper = threading.Thread(target=from_elsewhere, daemon=True)
    helper.start()
    assert service.run(shutdown_when_idle=False) == 0
    helper.join(5)
    assert happened == ['marker', 'completed', 'timer', 'shutdown: LaunchService.shutdown() called']
