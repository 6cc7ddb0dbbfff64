"""Bad URDF: one DescriptionError naming the file, the line and what would be valid; exit code 2 from the CLI."""

from __future__ import annotations

import io
import subprocess
import sys
from pathlib import Path

import pytest

from diffctl.description.robot_files import load_description, parse_description
from diffctl.description.urdf.parse import parse_urdf
from diffctl.errors import DescriptionError

MASS = '<inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>'


def robot(body: str) -> str:
    # Line 1 is the <robot> header, so the body starts on line 2.
    return f'<robot name="r">\n{body}\n</robot>'


LINKS = f'<link name="a">{MASS}</link>\n<link name="b">{MASS}</link>'
INERTIA = '<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>'


def joint(kind: str, inner: str = "", name: str = "j", parent: str = "a", child: str = "b") -> str:
    return f'<joint name="{name}" type="{kind}"><parent link="{parent}"/><child link="{child}"/>{inner}</joint>'


def shape(tag: str, geometry: str, extra: str = "") -> str:
    """A link 'a' (with mass) holding one <tag> whose geometry starts on a new line (line 3)."""
    return robot(f'<link name="a">{MASS}<{tag}><geometry>\n{geometry}</geometry>{extra}</{tag}></link>')


CASES = [
    ("malformed", '<robot name="r">\n<link name="a">\n</robot>', 3, ["malformed XML"]),
    ("wrong_root", "<model name='m'/>", 1, ["<sdf> or <robot>", "<model>"]),
    ("no_name", "<robot>\n<link name='a'/></robot>", 1, ["'name' attribute"]),
    (
        "revolute_without_limit",
        robot(f"{LINKS}\n{joint('revolute')}"),
        4,
        ["'j' is revolute but has no <limit>", "effort"],
    ),
    (
        "limit_without_effort",
        robot(LINKS + "\n" + joint("prismatic", '\n<limit velocity="1"/>')),
        5,
        ["needs a 'effort' attribute"],
    ),
    (
        "unknown_parent",
        robot(f'{LINKS}\n<joint name="j" type="fixed">\n<parent link="base"/><child link="b"/></joint>'),
        5,
        ["parent link 'base' is not defined"],
    ),
    (
        "bad_joint_type",
        robot(f"{LINKS}\n{joint('revolut')}"),
        4,
        ["'revolut' is not a URDF joint type", "did you mean 'revolute'", "valid:"],
    ),
    ("two_roots", robot(LINKS), 1, ["2 root links: a, b", "one tree"]),
    (
        "joint_named_like_a_link",
        robot(LINKS + "\n" + joint("continuous", name="b")),
        4,
        ["joint 'b' has the name of link 'b' (line 3)", "'b_joint'"],
    ),
    (
        "two_parents",
        robot(
            f'{LINKS}\n<link name="c"/>\n<joint name="j1" type="fixed"><parent link="a"/><child link="c"/></joint>'
            '\n<joint name="j2" type="fixed"><parent link="b"/><child link="c"/></joint>'
        ),
        6,
        ["'c' is the child of joints 'j1' and 'j2'"],
    ),
    (
        "bad_origin",
        robot(LINKS + "\n" + joint("fixed", '\n<origin xyz="0 nan 0"/>')),
        5,
        ["finite numbers"],
    ),
    ("bad_rpy", robot('<link name="a"><visual>\n<origin rpy="0 0"/></visual></link>'), 3, ["must be 3 numbers"]),
    ("no_geometry", robot('<link name="a">\n<collision/></link>'), 3, ["needs a <geometry>"]),
    ("capsule", robot('<link name="a"><visual><geometry>\n<capsule/></geometry></visual></link>'), 2, ["<capsule>"]),
    (  # urdfdom checks no inertia, but Gazebo (sdformat) does when it spawns the robot
        "invalid_inertia_when_simulated",
        robot('<link name="a"><inertial><mass value="1"/>\n<inertia ixx="-1" ixy="0" ixz="0" iyy="1" iyz="0" '
              'izz="1"/></inertial></link>'),
        2,  # the converted <inertial> carries its URDF element's line
        ["A link named a has invalid inertia", "ixx -1"],
    ),
    ("no_mass", robot(f'<link name="a">\n<inertial>{INERTIA}</inertial></link>'), 3, ["<mass value"]),
    (
        "bad_inertia",
        robot('<link name="a"><inertial><mass value="1"/>\n<inertia ixx="1" iyy="1" izz="1"/></inertial></link>'),
        3,
        ["'ixy'"],
    ),
    (
        "material_not_unique",
        robot(f'<material name="m"><color rgba="1 0 0 1"/></material>\n<material name="m"/>\n{LINKS}'),
        3,
        ["material 'm' is not unique"],
    ),
    (
        "bad_gazebo_number",
        robot(f'<link name="a">{MASS}</link>\n<gazebo reference="a"><mu1>high</mu1></gazebo>'),
        3,
        ["<mu1> must be a finite number", "'high'"],
    ),
    (
        "mimic_unknown",
        robot(LINKS + "\n" + joint("continuous", '\n<mimic joint="k"/>')),
        5,
        ["mimics 'k'"],
    ),
    (
        "no_mass_anywhere",
        robot(f'<link name="a"/>\n<link name="b"/>\n{joint("fixed")}'),
        2,
        ["no link has mass", "<inertial>"],
    ),
]


def _capture_errors(monkeypatch: pytest.MonkeyPatch) -> io.StringIO:
    """diffctl.console's error lines of this test (its stderr console may be bound to an earlier test's stream)."""
    import diffctl.console

    buf = io.StringIO()
    monkeypatch.setattr(diffctl.console, "err_console", diffctl.console.make_console(buf))
    return buf


def _take(buf: io.StringIO) -> str:
    text = buf.getvalue()
    buf.seek(0)
    buf.truncate()
    return text


@pytest.mark.parametrize(("text", "line", "fragments"), [c[1:] for c in CASES], ids=[c[0] for c in CASES])
def test_bad_urdf_names_file_line_and_fix(tmp_path: Path, text: str, line: int, fragments: list[str]) -> None:
    path = tmp_path / "robot.urdf"
    path.write_text(text)
    with pytest.raises(DescriptionError) as info:
        load_description(path)
    message = str(info.value)
    assert info.value.source == str(path)
    assert info.value.line == line, message
    assert info.value.exit_code == 2
    assert "\n" not in message
    for fragment in fragments:
        assert fragment in message


def test_values_urdfdom_accepts_load_for_robot_state_publisher() -> None:
    """urdfdom checks no size, inertia, dynamics or axis; robot_state_publisher takes such a robot whole."""
    text = robot(
        '<link name="a"><inertial><mass value="-1"/><inertia ixx="0" ixy="0" ixz="0" iyy="-2" iyz="0" izz="0"/>'
        '</inertial><visual><geometry><box size="0 -1 1"/></geometry></visual><collision><geometry>'
        '<sphere radius="0"/></geometry></collision></link><link name="b"/>\n'
        + joint("revolute", '<axis xyz="0 0 0"/><limit effort="1" velocity="1"/><dynamics damping="-1"/>')
    )
    m = parse_description(text, source="robot.urdf", simulation=False)
    assert [link.name for link in m.links] == ["a", "b"]
    assert m.joints[0].name == "j"


def test_materials_urdfdom_only_warns_about(monkeypatch: pytest.MonkeyPatch) -> None:
    """urdfdom logs an undefined material and a colourless top-level one and keeps the robot; a named inline
    material serves the visuals after it."""
    errors = _capture_errors(monkeypatch)

    def visual(material: str, rgba: str = "") -> str:
        color = f'<color rgba="{rgba}"/>' if rgba else ""
        sphere = '<geometry><sphere radius="1"/></geometry>'
        return f'<visual>{sphere}<material name="{material}">{color}</material></visual>'

    text = robot(
        '<material name="plain"/>\n'
        f'<link name="a">{MASS}{visual("red", "1 0 0 1")}</link>\n'
        f'<link name="b">{MASS}{visual("red")}\n{visual("redd")}{visual("plain")}</link>\n' + joint("fixed")
    )
    m = parse_urdf(text, source="robot.urdf")
    assert [v.rgba for v in m.links["b"].visuals] == [(1.0, 0.0, 0.0, 1.0), None, None]
    err = _take(errors)
    assert "robot.urdf:2: Material [plain] color has no rgba" in err
    assert "robot.urdf:5: link 'b' material 'redd' undefined" in err
    assert "red" in err.split("redd")[1].splitlines()[0]  # the close match
    assert len(err.strip().splitlines()) == 2


def test_missing_mesh_names_the_uri_and_where_it_looked(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    errors = _capture_errors(monkeypatch)
    box = '<box size="1 1 1"/>'
    text = robot(
        f'<link name="a">{MASS}<visual><geometry>\n<mesh filename="meshes/body.stl"/></geometry></visual>'
        f"<visual><geometry>{box}</geometry></visual><collision><geometry>{box}</geometry></collision></link>"
    )
    path = tmp_path / "robot.urdf"
    path.write_text(text)
    link = load_description(path).links[0]  # Gazebo spawns it: the missing visual is only an error line
    assert len(link.visuals) == 1 and type(link.visuals[0].geometry).__name__ == "Box"
    assert len(link.collisions) == 1
    message = _take(errors)
    assert f"{path}:3: mesh: mesh 'meshes/body.stl' not found" in message
    assert str(tmp_path / "meshes" / "body.stl") in message
    assert "the model loads without this visual" in message


def test_mesh_of_an_unknown_package(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(tmp_path)
    errors = _capture_errors(monkeypatch)
    monkeypatch.delenv("AMENT_PREFIX_PATH", raising=False)
    text = shape("collision", '<mesh filename="package://no_such_pkg/m.stl"/>')
    # as gz-sim's physics ("Failed to load mesh"): the robot loads without that collision
    assert parse_description(text, source="robot.urdf").link("a").collisions == ()
    err = _take(errors)
    assert "robot.urdf:3: mesh: mesh 'package://no_such_pkg/m.stl' not found: package 'no_such_pkg' not found" in err
    assert "searched: " in err and "the model loads without this collision" in err
    # TF and the visualizer do not need the file: the kinematic view keeps the URI as written
    model = parse_description(text, simulation=False, check_files=False)
    assert model.link("a").collisions[0].geometry.uri == "package://no_such_pkg/m.stl"


def test_mesh_in_a_format_pybullet_cannot_read(tmp_path: Path) -> None:
    (tmp_path / "part.ply").write_text("ply\n")
    path = tmp_path / "robot.urdf"
    path.write_text(shape("visual", '<mesh filename="part.ply"/>'))
    with pytest.raises(DescriptionError, match=r"format '\.ply'.*supported: \.obj, \.stl, \.dae"):
        load_description(path)


def test_cli_reports_one_line_and_exits_2(tmp_path: Path) -> None:
    path = tmp_path / "robot.urdf"
    path.write_text(robot(f"{LINKS}\n{joint('revolute')}"))
    run = subprocess.run(
        [sys.executable, "-m", "diffctl", "robot-state-publisher", "--description", str(path)],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert run.returncode == 2
    lines = [line for line in run.stderr.splitlines() if line.strip()]
    assert len(lines) == 1, run.stderr
    assert ":4:" in lines[0] and "'j' is revolute but has no <limit>" in lines[0]
