"""The XML frontend, tag by tag, against what ROS 2's launch_xml does; errors name file and line.

Oracles where they exist: xacro itself for `$(command 'xacro …')`, the YAML frontend for "one model behind
all frontends" (the same description written in both resolves to the same plan), and PyYAML for the types
launch gives untyped `<param>` values.
"""

from __future__ import annotations

import signal
import textwrap
from pathlib import Path

import pytest
import yaml
from hypothesis import given, settings
from hypothesis import strategies as st
from lxml import etree

from diffctl.errors import LaunchError
from diffctl.launch_legacy import commandline
from diffctl.launch_legacy.loader import load
from diffctl.launch_legacy.plan import AddHandler, LogMessage, RequestShutdown, Skipped, StartProcess, StartTimer
from diffctl.launch_legacy.resolver import resolve


def write(tmp_path: Path, text: str, name: str = "t.launch.xml") -> Path:
    path = tmp_path / name
    path.write_text(textwrap.dedent(text).strip() + "\n")
    return path


def plan_of(tmp_path: Path, text: str, arguments: dict[str, str] | None = None, name: str = "t.launch.xml"):
    path = write(tmp_path, text, name)
    return resolve(load(path), arguments or {}, str(path))


def error_of(tmp_path: Path, text: str, **kw) -> LaunchError:
    with pytest.raises(LaunchError) as info:
        plan_of(tmp_path, text, **kw)
    return info.value


def processes(plan) -> dict:
    return {s.spec.name: s.spec for s in plan.steps if isinstance(s, StartProcess)}


def logs(plan) -> list[str]:
    return [s.message for s in plan.steps if isinstance(s, LogMessage)]


def params_of(spec) -> dict:
    out: dict = {}
    for entry in spec.node.params:
        assert isinstance(entry, dict)
        out.update(entry)
    return out


# ---- arg / let / log ------------------------------------------------------------------------------------------


def test_arg_default_description_choices_and_let(tmp_path: Path) -> None:
    text = """
        <launch>
          <arg name="mode" default="fast" description="how to run">
            <choice value="fast"/>
            <choice value="slow"/>
          </arg>
          <let name="greeting" value="mode is $(var mode)"/>
          <log message="$(var greeting)"/>
        </launch>
    """
    plan = plan_of(tmp_path, text)
    assert logs(plan) == ["mode is fast"]
    (arg,) = plan.arguments
    assert (arg.name, arg.default, arg.description, arg.choices) == ("mode", "fast", "how to run", ("fast", "slow"))
    assert logs(plan_of(tmp_path, text, {"mode": "slow"})) == ["mode is slow"]
    e = error_of(tmp_path, text, arguments={"mode": "medium"})
    assert "not one of its choices" in str(e) and "fast, slow" in str(e)
    assert ":2" in str(e)  # the <arg> line


def test_a_required_argument_missing_is_named(tmp_path: Path) -> None:
    e = error_of(tmp_path, '<launch>\n  <arg name="robot"/>\n  <log message="$(var robot)"/>\n</launch>')
    assert "missing required launch argument 'robot'" in str(e)


# ---- node -----------------------------------------------------------------------------------------------------


NODE = """
    <launch>
      <arg name="rate" default="50"/>
      <node pkg="robot_state_publisher" exec="robot_state_publisher" name="rsp" namespace="robot1"
            args="--flag 'two words'" ros_args="--log-level debug" output="both" respawn="true"
            respawn_delay="2" launch-prefix="nice -n 5">
        <param name="robot_description" value="$(command 'echo 1.5')" type="str"/>
        <param name="publish_frequency" value="$(var rate)"/>
        <param name="ignore_timestamp" value="yes" type="bool"/>
        <param name="names" value="a;b;c" value-sep=";"/>
        <param name="gains" value="[1, 2.5]" type="list_of_float"/>
        <param name="plain" value="hello"/>
        <param name="limits">
          <param name="max" value="1.5"/>
          <param name="inner"><param name="deep" value="true"/></param>
        </param>
        <remap from="joint_states" to="/js"/>
        <env name="NODE_ENV" value="$(var rate)"/>
      </node>
    </launch>
"""


def test_node_attributes_become_the_process_and_its_ros_arguments(tmp_path: Path) -> None:
    spec = processes(plan_of(tmp_path, NODE))["rsp"]
    assert spec.argv[:3] == ("nice", "-n", "5")
    i = spec.argv.index("--flag")
    assert spec.argv[i : i + 2] == ("--flag", "two words")
    assert spec.argv[spec.argv.index("--ros-args") + 1 : spec.argv.index("--ros-args") + 3] == ("--log-level", "debug")
    assert (spec.node.node_name, spec.node.namespace) == ("rsp", "/robot1")
    assert spec.node.remaps == (("joint_states", "/js"),)
    assert spec.env["NODE_ENV"] == "50"
    assert (spec.output, spec.respawn, spec.respawn_delay_s) == ("both", True, 2.0)


def test_param_values_are_typed_as_launch_xml_types_them(tmp_path: Path) -> None:
    params = params_of(processes(plan_of(tmp_path, NODE))["rsp"])
    assert params["robot_description"] == "1.5\n"  # type="str": the text, even when it looks like a number
    assert params["publish_frequency"] == yaml.safe_load("50") == 50  # untyped: YAML decides, after substitution
    assert params["ignore_timestamp"] is True  # YAML 1.1 boolean words with type="bool"
    assert params["names"] == ["a", "b", "c"]
    assert params["gains"] == [1.0, 2.5] and all(isinstance(g, float) for g in params["gains"])
    assert params["plain"] == "hello"
    assert params["limits"] == {"max": 1.5, "inner": {"deep": True}}


def test_param_from_a_file_and_set_parameter_come_before_the_nodes_own(tmp_path: Path) -> None:
    (tmp_path / "p.yaml").write_text("/**:\n  ros__parameters:\n    a: 1\n")
    text = """
        <launch>
          <set_parameter name="use_sim_time" value="true"/>
          <set_remap from="cmd_vel" to="/cmd_vel"/>
          <node pkg="robot_state_publisher" exec="robot_state_publisher" name="n">
            <param from="$(dirname)/p.yaml"/>
            <remap from="odom" to="/odom"/>
          </node>
        </launch>
    """
    spec = processes(plan_of(tmp_path, text))["n"]
    assert spec.node.global_params == (("use_sim_time", "True"),)
    assert spec.node.params[0] == str(tmp_path / "p.yaml")
    assert spec.node.remaps == (("cmd_vel", "/cmd_vel"), ("odom", "/odom"))
    # launch_ros's command line: -p for SetParameter's, then the node's files, then remaps
    tail = commandline.argv(spec)[-11:]
    assert tail == [
        "--ros-args",
        "-r",
        "__node:=n",
        "-p",
        "use_sim_time:=True",
        "--params-file",
        str(tmp_path / "p.yaml"),
        "-r",
        "cmd_vel:=/cmd_vel",
        "-r",
        "odom:=/odom",
    ]
    text = """
        <launch>
          <group>
            <set_parameters_from_file filename="p.yaml"/>
            <set_use_sim_time value="true"/>
            <node pkg="robot_state_publisher" exec="robot_state_publisher" name="in"/>
          </group>
          <node pkg="robot_state_publisher" exec="robot_state_publisher" name="out"/>
        </launch>
    """
    procs = processes(plan_of(tmp_path, text))
    # set_use_sim_time is launch's own node's (launch_ros): not a parameter of the nodes
    assert procs["in"].node.global_params == (str(tmp_path / "p.yaml"),)
    assert procs["out"].node.global_params == ()


@pytest.mark.parametrize(
    ("param", "pattern"),
    [
        ('<param name="a" from="x.yaml"/>', "mutually exclusive"),
        ('<param name="a"/>', "either a value attribute or nested params"),
        ('<param name="a" value="[1, x]"/>', "non-uniform list"),
        ('<param name="a" value="{b: 1}"/>', "neither a scalar nor a list"),
        ('<param name="a" value="x" type="integer"/>', "type 'integer' is not valid.*list_of_int"),
        ('<param name="a" value="1.5" type="int"/>', "not a valid int"),
        ('<param name="a" vaule="1"/>', "unknown attribute 'vaule'.*did you mean 'value'"),
    ],
)
def test_bad_params_are_one_located_message(tmp_path: Path, param: str, pattern: str) -> None:
    node = '<node pkg="robot_state_publisher" exec="robot_state_publisher">'
    text = f"<launch>\n  {node}\n    {param}\n  </node>\n</launch>"
    e = error_of(tmp_path, text)
    assert e.source and e.source.endswith("t.launch.xml") and e.line in (2, 3)
    import re

    assert re.search(pattern, str(e)), str(e)


# ---- executable -----------------------------------------------------------------------------------------------


def test_executable_with_cwd_shell_env_and_on_exit_shutdown(tmp_path: Path) -> None:
    text = f"""
        <launch>
          <executable cmd="echo one two" cwd="{tmp_path}" name="ex" shell="true" sigterm_timeout="2"
                      sigkill_timeout="3" emulate_tty="true" on_exit="shutdown">
            <env name="A" value="1"/>
          </executable>
        </launch>
    """
    spec = processes(plan_of(tmp_path, text))["ex"]
    assert spec.argv == ("/bin/sh", "-c", "echo one two")
    assert (spec.cwd, spec.env["A"], spec.required) == (str(tmp_path), "1", True)
    assert (spec.sigterm_timeout_s, spec.sigkill_timeout_s) == (2.0, 3.0)


# ---- group / push-ros-namespace / set_env / include -----------------------------------------------------------


def test_scoped_group_keeps_namespace_env_remaps_and_lets_inside(tmp_path: Path) -> None:
    text = """
        <launch>
          <let name="x" value="outer"/>
          <group>
            <push-ros-namespace namespace="robot1"/>
            <set_env name="INNER" value="1"/>
            <set_remap from="a" to="b"/>
            <let name="x" value="inner"/>
            <node pkg="robot_state_publisher" exec="robot_state_publisher" name="in"/>
          </group>
          <group scoped="false">
            <let name="y" value="leaks"/>
          </group>
          <group forwarding="false">
            <keep name="kept" value="$(var x)"/>
            <log message="kept=$(var kept) x=$(var x 'unset')"/>
          </group>
          <append_env name="PATHLIKE" value="/b"/>
          <append_env name="PATHLIKE" value="/a" prepend="true"/>
          <node pkg="robot_state_publisher" exec="robot_state_publisher" name="out"/>
          <log message="$(var x) $(var y)"/>
        </launch>
    """
    plan = plan_of(tmp_path, text)
    procs = processes(plan)
    assert procs["in"].node.namespace == "/robot1" and procs["in"].env.get("INNER") == "1"
    assert procs["in"].node.remaps == (("a", "b"),)
    assert procs["out"].node.namespace == "/" and "INNER" not in procs["out"].env and procs["out"].node.remaps == ()
    assert procs["out"].env["PATHLIKE"].startswith("/a:") and procs["out"].env["PATHLIKE"].endswith(":/b")
    assert logs(plan) == ["kept=outer x=unset", "outer leaks"]


def test_include_passes_args_between_xml_and_yaml_files(tmp_path: Path) -> None:
    write(
        tmp_path, '<launch>\n  <arg name="who"/>\n  <log message="xml got $(var who)"/>\n</launch>', "inner.launch.xml"
    )
    (tmp_path / "inner.yaml").write_text("launch:\n- arg: {name: who}\n- log: {message: yaml got $(var who)}\n")
    text = """
        <launch>
          <include file="$(dirname)/inner.launch.xml"><arg name="who" value="one"/></include>
          <include file="inner.yaml"><arg name="who" value="two"/></include>
        </launch>
    """
    assert logs(plan_of(tmp_path, text)) == ["xml got one", "yaml got two"]


# ---- timer / shutdown / if / unless ---------------------------------------------------------------------------


def test_timer_shutdown_and_conditions(tmp_path: Path) -> None:
    text = """
        <launch>
          <arg name="on" default="true"/>
          <timer period="1.5"><log message="later"/></timer>
          <log message="shown" if="$(var on)"/>
          <log message="hidden" unless="$(var on)"/>
          <log message="and" if="$(and $(var on) $(not false))"/>
          <shutdown reason="bye" if="$(equals $(var on) 1)"/>
        </launch>
    """
    plan = plan_of(tmp_path, text)
    timer = next(s for s in plan.steps if isinstance(s, StartTimer))
    assert timer.period_s == 1.5 and [s.message for s in timer.steps] == ["later"]
    assert logs(plan) == ["shown", "and"]
    assert any(isinstance(s, Skipped) and "hidden" in s.what for s in plan.steps)
    assert [s.reason for s in plan.steps if isinstance(s, RequestShutdown)] == ["bye"]
    e = error_of(tmp_path, '<launch>\n  <log message="x" if="maybe"/>\n</launch>')
    assert "not a boolean" in str(e) and e.line == 2
    e = error_of(tmp_path, '<launch>\n  <log message="x" if="1" unless="0"/>\n</launch>')
    assert "not both" in str(e)


# ---- substitutions --------------------------------------------------------------------------------------------


def test_substitutions_of_launch_xml(tmp_path: Path, monkeypatch) -> None:
    monkeypatch.setenv("DIFFCTL_XML_T", "from-env")
    text = """
        <launch>
          <arg name="n" default="3"/>
          <log message="$(env DIFFCTL_XML_T) $(env DIFFCTL_XML_UNSET 'dflt')"/>
          <log message="$(eval '$(var n) * 2')"/>
          <log message="$(eval 'pi > 3')"/>
          <log message="$(filename)|$(dirname)"/>
          <log message="$(anon a)=$(anon a)"/>
          <log message="$(find-exec sh)"/>
          <log message="$(if $(equals $(var n) 3.0) yes no)"/>
          <log message="$(eval '\\'$(var n)\\' == \\'3\\'')"/>
          <log message="$(eval &quot;'$(var n)' in ('2', '3')&quot;)"/>
          <log message="$(eval 'os.sep' 'os')"/>
          <log message="a\\d+"/>
        </launch>
    """
    path = str(tmp_path / "t.launch.xml")
    got = logs(plan_of(tmp_path, text))
    assert got[:4] == ["from-env dflt", "6", "True", f"{path}|{tmp_path}"]
    left, right = got[4].split("=")
    assert left == right and left.startswith("a_")
    assert got[5].endswith("/sh") and Path(got[5]).is_file()
    assert got[6:] == ["yes", "True", "True", "/", "a\\d+"]  # backslashes escape inside arguments only


def test_command_runs_xacro_as_xacro_itself_expands(tmp_path: Path) -> None:
    import xacro

    (tmp_path / "robot.urdf.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:arg name="w" default="0.3"/>\n'
        '  <xacro:property name="half" value="${$(arg w) / 2}"/>\n'
        '  <link name="base"><visual><geometry><box size="${half} 1 1"/></geometry></visual></link>\n'
        "</robot>\n"
    )
    text = """
        <launch>
          <let name="urdf" value="$(command 'xacro $(dirname)/robot.urdf.xacro w:=0.5')"/>
          <node pkg="robot_state_publisher" exec="robot_state_publisher" name="rsp">
            <param name="robot_description" value="$(var urdf)" type="str"/>
          </node>
        </launch>
    """
    got = params_of(processes(plan_of(tmp_path, text))["rsp"])["robot_description"]
    expected = xacro.process_file(str(tmp_path / "robot.urdf.xacro"), mappings={"w": "0.5"}).toxml()

    def canon(s):
        return etree.tostring(etree.fromstring(s.encode(), etree.XMLParser(remove_blank_text=True)), method="c14n")

    assert canon(got) == canon(expected)
    e = error_of(tmp_path, "<launch>\n  <log message=\"$(command 'false')\"/>\n</launch>")
    assert "executed command failed" in str(e) and e.line == 2


# ---- one model; errors ----------------------------------------------------------------------------------------


def test_the_same_description_in_xml_and_yaml_resolves_to_the_same_plan(tmp_path: Path) -> None:
    xml = """
        <launch>
          <arg name="ns" default="r1"/>
          <group>
            <push-ros-namespace namespace="$(var ns)"/>
            <node pkg="robot_state_publisher" exec="robot_state_publisher" name="rsp" args="-a b" respawn="true">
              <param name="rate" value="10"/>
              <param name="frame" value="base"/>
              <remap from="a" to="b"/>
            </node>
          </group>
          <executable cmd="sleep 5" name="sl" on_exit="shutdown"/>
          <timer period="2"><log message="t"/></timer>
        </launch>
    """
    yml = """
        launch:
        - arg: {name: ns, default: r1}
        - group:
            children:
            - push_ros_namespace: {namespace: $(var ns)}
            - node:
                pkg: robot_state_publisher
                exec: robot_state_publisher
                name: rsp
                args: -a b
                respawn: "true"
                param: [{name: rate, value: 10}, {name: frame, value: base}]
                remap: [{from: a, to: b}]
        - executable: {cmd: sleep 5, name: sl, on_exit: shutdown}
        - timer: {period: 2, children: [{log: {message: t}}]}
    """
    a = plan_of(tmp_path, xml)
    b = plan_of(tmp_path, yml, name="t.yaml")
    import re

    def strip(steps: tuple) -> str:  # the same but for where each was written
        return re.sub(r"where='[^']*'|origin=\d+", "", repr(steps))

    assert strip(a.steps) == strip(b.steps)
    assert a.processes.keys() == b.processes.keys()


@pytest.mark.parametrize(
    ("body", "line", "pattern"),
    [
        ('<nod pkg="a" exec="b"/>', 2, r"unknown tag <nod>.*did you mean 'node'"),
        ('<log mesage="x"/>', 2, r"unknown attribute 'mesage'.*did you mean 'message'"),
        ('<node pkg="a" exec="b"><parm name="x" value="1"/></node>', 2, r"unexpected nested tag <parm>.*'param'"),
        ('<log message="$(vra x)"/>', 2, r"unknown substitution \$\(vra\).*did you mean"),
        ('<log message="$(var x"/>', 2, r"unterminated"),
        ("<log message='x'>\n</lg>", 3, r"malformed XML"),
        ('<timer><log message="x"/></timer>', 2, r"needs the attribute `period`"),
        ('<node exec="no-such-exe-xyz"/>', 2, r"'no-such-exe-xyz' not found on PATH"),
        ('<node pkg="a" exec="b" remap="x:=y"/>', 2, r"`remap` is written as nested elements"),
        ('<executable cmd="x" launch-prefix="a" launch_prefix="b"/>', 2, r"given twice"),
        ('<node pkg="robot_state_publisher"/>', 2, r"needs the attribute `exec`"),
    ],
)
def test_bad_xml_is_one_message_with_file_and_line(tmp_path: Path, body: str, line: int, pattern: str) -> None:
    import re

    e = error_of(tmp_path, f"<launch>\n  {body}\n</launch>")
    assert e.source and e.source.endswith("t.launch.xml")
    assert e.line == line, str(e)
    assert re.search(pattern, str(e), re.S), str(e)
    assert "\n" not in e.message


def test_the_root_must_be_launch(tmp_path: Path) -> None:
    e = error_of(tmp_path, "<robot/>")
    assert "not <launch>" in str(e) and e.line == 1


def test_launch_runs_an_xml_file_and_the_handlers_of_the_model(launch_run, tmp_path: Path) -> None:
    path = write(
        tmp_path,
        """
        <launch>
          <arg name="word" default="hello"/>
          <executable cmd="sh -c 'echo $(var word) from xml; sleep 60'" name="talker" output="screen"/>
          <timer period="0.2"><log message="timer fired"/></timer>
        </launch>
        """,
    )
    run = launch_run(str(path), "word:=howdy")
    run.wait_for(r"\[talker\] howdy from xml", timeout_s=30)
    run.wait_for(r"timer fired", timeout_s=30)
    run.signal(signal.SIGINT)
    assert run.wait(30) == 0
    assert run.leftovers() == []
    assert "[talker] stopped" in run.text()


def test_the_cli_reports_a_bad_xml_file_in_one_line_with_exit_code_2(launch_run, tmp_path: Path) -> None:
    path = write(tmp_path, '<launch>\n  <log mesage="x"/>\n</launch>')
    run = launch_run(str(path))
    assert run.wait(30) == 2
    lines = [line for line in run.text().splitlines() if line.strip()]
    assert any(f"{path}:2" in line and "mesage" in line for line in lines), run.text()


def test_handlers_in_plan_are_from_the_shared_registry(tmp_path: Path) -> None:
    # diffctl's declarative handlers are registry tags too, so XML can write them.
    text = """
        <launch>
          <executable cmd="true" name="a"/>
          <on_exit target="a" exit_code="0"><log message="a done"/></on_exit>
        </launch>
    """
    plan = plan_of(tmp_path, text)
    (handler,) = [s.handler for s in plan.steps if isinstance(s, AddHandler)]
    assert handler.event == "exit" and handler.exit_code == 0 and [t.name for t in handler.targets] == ["a"]


def test_readiness_in_xml_as_nested_wait_for_elements(tmp_path: Path) -> None:
    text = """
        <launch>
          <executable cmd="sleep 1" name="a"/>
          <executable cmd="sleep 1" name="b" wait_timeout="5">
            <wait_for exited="a"/>
            <wait_for log="a" regex="ready"/>
            <wait_for topic="/robot_description"/>
          </executable>
        </launch>
    """
    gate = next(s.gate for s in plan_of(tmp_path, text).steps if isinstance(s, StartProcess) and s.spec.name == "b")
    assert [(w.kind, str(w.target), w.pattern) for w in gate.waits] == [
        ("exited", "a", None),
        ("log", "a", "ready"),
        ("topic", "/robot_description", None),
    ]
    assert gate.timeout_s == 5.0
    e = error_of(tmp_path, '<launch>\n  <log message="x">\n    <wait_for exited="a" started="b"/>\n  </log>\n</launch>')
    assert "takes one condition" in str(e) and e.line == 3


def test_reset_env_and_reset_keep(tmp_path: Path, monkeypatch) -> None:
    monkeypatch.setenv("DIFFCTL_XML_KEEP", "original")
    text = """
        <launch>
          <let name="a" value="1"/>
          <let name="b" value="2"/>
          <set_env name="DIFFCTL_XML_KEEP" value="changed"/>
          <set_env name="DIFFCTL_XML_NEW" value="new"/>
          <reset_env/>
          <reset><keep name="b" value="$(var b)"/></reset>
          <log message="$(env DIFFCTL_XML_KEEP) $(env DIFFCTL_XML_NEW 'unset') $(var a 'gone') $(var b)"/>
        </launch>
    """
    assert logs(plan_of(tmp_path, text)) == ["original unset gone 2"]


_PIECES = [
    "<launch>",
    "</launch>",
    "<node ",
    'pkg="robot_state_publisher" ',
    'exec="robot_state_publisher" ',
    "/>",
    ">",
    "</node>",
    "<param ",
    'name="a" ',
    'value="1" ',
    'type="int" ',
    'value-sep="," ',
    "</param>",
    "<group>",
    "</group>",
    "<arg ",
    'default="x" ',
    "<let ",
    "<log ",
    'message="$(var a)" ',
    'if="true" ',
    "<timer ",
    'period="1" ',
    "</timer>",
    "<include ",
    'file="nope.xml" ',
    "<!-- c -->",
    "&amp;",
    "<",
    '"',
]


@settings(max_examples=200, deadline=None)
@given(st.lists(st.sampled_from(_PIECES), max_size=14))
def test_any_xml_is_a_plan_or_one_located_launch_error(tmp_path_factory, pieces: list[str]) -> None:
    path = tmp_path_factory.mktemp("fuzz") / "f.launch.xml"
    path.write_text("".join(pieces))
    try:
        resolve(load(path), {}, str(path))
    except LaunchError as e:
        assert e.source == str(path) and "\n" not in e.message, str(e)


def test_args_split_the_written_text_never_a_substitutions_value(tmp_path: Path) -> None:
    # As launch's _parse_cmdline: a share directory under a folder with spaces stays one argument.
    text = """
        <launch>
          <let name="dir" value="/path with space"/>
          <let name="none" value=""/>
          <executable cmd="echo -d $(var dir)/x.rviz 'two words' pre$(var dir)post $(var none) last" name="e"/>
          <executable cmd="echo '$(var dir) quoted' tail" name="q"/>
        </launch>
    """
    procs = processes(plan_of(tmp_path, text))
    assert procs["e"].argv == ("echo", "-d", "/path with space/x.rviz", "two words", "pre/path with spacepost", "last")
    assert procs["q"].argv == ("echo", "/path with space quoted", "tail")
