"""diffctl's launch-file extensions, on a LaunchService as any user of launch's API runs one: event handler tags,
readiness, `let` with a file, `choices`, `optenv` — the same chain in YAML, XML and Python."""

from __future__ import annotations

import asyncio
import sys
from pathlib import Path
from typing import Any

import pytest

from diffctl.launch import LaunchDescription, LaunchService
from diffctl.launch.actions import IncludeLaunchDescription
from diffctl.launch.launch_description_sources import AnyLaunchDescriptionSource

DATA = Path(__file__).parent / "data"
STEP = Path(__file__).parents[1] / "launch" / "data" / "step.py"


def run_launch(path: Path, arguments: dict[str, str] | None = None, timeout_s: float = 30.0) -> tuple[int, Any]:
    """Run a launch file to its end on a LaunchService (shut down, and failed, after `timeout_s`); return the
    return code and the context."""
    service = LaunchService(argv=[f"{k}:={v}" for k, v in (arguments or {}).items()], noninteractive=True)
    include = IncludeLaunchDescription(
        AnyLaunchDescriptionSource(str(path)), launch_arguments=(arguments or {}).items()
    )
    service.include_launch_description(LaunchDescription([include]))

    async def bounded() -> int:
        task = asyncio.ensure_future(service.run_async())
        try:
            return await asyncio.wait_for(asyncio.shield(task), timeout_s)
        except TimeoutError:
            pending = service.shutdown()
            if pending is not None:
                await pending
            await task
            raise AssertionError(f"{path.name} still running after {timeout_s} s") from None

    loop = asyncio.new_event_loop()
    try:
        code = loop.run_until_complete(bounded())
    finally:
        loop.close()
    return code, service.context


@pytest.mark.parametrize("name", ["chain.yaml", "chain.launch.xml", "chain.launch.py"])
def test_readiness_and_handler_tags_order_the_tutorials_start_up_chain(name: str, tmp_path: Path) -> None:
    record = tmp_path / "record"
    code, _ = run_launch(DATA / name, {"python": sys.executable, "step": str(STEP), "record": str(record)})
    assert code == 0
    # spawn_entity waited for sim's line, base_spawner for spawn_entity's clean exit, jsb_spawner for
    # base_spawner's exit, viz for jsb_spawner's exit with 0, and `viz_up` for viz's start (the two race).
    ran = record.read_text().split()
    assert ran[:5] == ["sim", "sim:printed", "spawn_entity", "base_spawner", "jsb_spawner"]
    assert sorted(ran[5:]) == ["viz", "viz_up"]


def write(tmp_path: Path, text: str, name: str = "t.yaml") -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


@pytest.mark.parametrize(
    ("body", "message"),
    [
        (
            "- executable: {name: spawn, cmd: 'sh -c \"exit 3\"'}\n"
            "- wait_for: {exited: spawn, children: [{log: {message: never}}]}\n",
            "WaitFor(exited spawn): cannot wait for exited spawn: spawn exited with code 3",
        ),
        (
            "- executable: {name: sim, cmd: 'sh -c \"echo loading\"'}\n"
            "- wait_for: {log: sim, regex: loaded, children: [{log: {message: never}}]}\n",
            "cannot wait for log of sim matching /loaded/: sim ended without printing /loaded/",
        ),
        (
            "- executable: {name: sim, cmd: 'sleep 30'}\n"
            "- wait_for: {started: nobody, timeout: 0.3, children: [{log: {message: never}}]}\n",
            "WaitFor(started nobody): still waiting for started nobody after 0.3 s",
        ),
        (
            "- wait_for: {topic: /robot_description, children: [{log: {message: never}}]}\n",
            "nothing answers topic conditions here",
        ),
    ],
)
def test_a_wait_that_cannot_be_met_fails_the_launch_naming_it(body: str, message: str, tmp_path, caplog) -> None:
    code, _ = run_launch(write(tmp_path, "launch:\n" + body))
    assert code == 1
    assert message in caplog.text
    assert "never" not in [r.getMessage() for r in caplog.records]


def test_a_file_with_placeholders_replaced_choices_and_optenv(tmp_path: Path, monkeypatch) -> None:
    monkeypatch.delenv("DIFFCTL_T_UNSET", raising=False)
    (tmp_path / "robot.sdf").write_text("<plugin><parameters>PLACEHOLDER</parameters></plugin>")
    path = write(
        tmp_path,
        """
launch:
- arg: {name: mode, default: sim, choices: [sim, real]}
- let:
    name: description
    file: $(dirname)/robot.sdf
    replace: {PLACEHOLDER: $(dirname)/$(var mode).yaml}
- let: {name: direct, value: "$(file-content $(dirname)/robot.sdf PLACEHOLDER=x)"}
- let: {name: env, value: "[$(optenv DIFFCTL_T_UNSET)|$(optenv DIFFCTL_T_UNSET dflt)]"}
""",
    )
    code, context = run_launch(path, {"mode": "real"})
    assert code == 0
    assert (
        context.launch_configurations["description"]
        == f"<plugin><parameters>{tmp_path}/real.yaml</parameters></plugin>"
    )
    assert context.launch_configurations["direct"] == "<plugin><parameters>x</parameters></plugin>"
    assert context.launch_configurations["env"] == "[|dflt]"
    code, _ = run_launch(path, {"mode": "fake"})
    assert code == 1  # DeclareLaunchArgument refuses a value not among its choices, as ros2 launch does


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("- wait_for: {timeout: 3, children: []}", "wait_for needs a condition"),
        ("- wait_for: {log: sim, children: []}", "`log` and `regex` go together"),
        ("- wait_for: {exited: a, timeout: -1, children: []}", "must be a positive number of seconds"),
        ("- on_shutdown: {target: a, do: [{log: {message: x}}]}", "on_shutdown takes no target"),
        ("- on_exit: {target: a}", "on_exit needs the actions to run"),
        ("- arg: {name: a, choices: [x], choice: [{value: x}]}", "give `choice` or `choices`, not both"),
        ("- let: {name: a, value: x, file: y}", "either `value` or `file`"),
        ("- let: {name: a, value: x, replace: {A: b}}", "`replace` needs `file`"),
    ],
)
def test_a_malformed_extension_tag_is_one_error_naming_it(text: str, message: str, tmp_path: Path) -> None:
    from diffctl.launch.launch_description_sources import get_launch_description_from_any_launch_file

    with pytest.raises(Exception, match=message.replace("`", ".").replace("(", ".").replace(")", ".")):
        get_launch_description_from_any_launch_file(str(write(tmp_path, "launch:\n" + text + "\n")))


def test_a_node_is_named_by_its_node_name(tmp_path: Path) -> None:
    from tests.launch_requests import started

    path = write(
        tmp_path,
        """
launch:
- node: {pkg: demo_nodes_py, exec: talker, name: chatty}
- on_exit: {target: chatty, do: [{executable: {cmd: "true", name: after_exit}}]}
- wait_for: {exited: chatty, children: [{executable: {cmd: "true", name: gated}}]}
""",
    )
    run = started(path)  # every process a stand-in that exits at once
    assert run.started[0].base == "talker"  # ros2 launch labels a node by its executable
    assert sorted(s.base for s in run.started[1:]) == ["after_exit", "gated"]
