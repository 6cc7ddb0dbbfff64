"""Bad SDF: one DescriptionError naming file, line and element, never a crash of the interpreter."""

from __future__ import annotations

import io
import random
import subprocess
import sys
from pathlib import Path

import pytest
from lxml import etree

from diffctl.description.sdf_loader import load_model, load_world, parse_model
from diffctl.errors import DescriptionError

REPO = Path(__file__).resolve().parents[2]

INERTIAL = "<inertial><mass>1</mass></inertial>"


def model(body: str, version: str = "1.8", static: bool = False) -> str:
    # Line 1 is the <sdf>/<model> header, so the body starts on line 2.
    return (
        f'<sdf version="{version}"><model name="m">{"<static>true</static>" if static else ""}\n{body}\n</model></sdf>'
    )


CASES = [
    ("malformed_xml", '<sdf version="1.8"><model name="m">\n<link name="a">\n</model></sdf>', 3, ["malformed XML"]),
    # libxml2 ends this message with a newline before lxml's ", line N, column M": still one line, the place first
    ("xml_illegal_char", model("<link name='a'>\x00</link>"), 2, ["robot.sdf:2:16: malformed XML: Invalid character"]),
    ("empty_pose", model("<link name='a'><pose/></link>", static=True), 2, ["empty <pose/>", "x y z roll pitch yaw"]),
    ("short_pose", model("<link name='a'><pose>1 2 3</pose></link>", static=True), 2, ["<pose>", "'1 2 3'"]),
    ("nan_pose", model("<link name='a'><pose>1 2 nan 0 0 0</pose></link>", static=True), 2, ["finite"]),
    (
        "unknown_joint_type",
        model(
            f"<link name='a'>{INERTIAL}</link><link name='b'>{INERTIAL}</link>\n"
            "<joint name='j' type='revolut'><parent>a</parent><child>b</child></joint>"
        ),
        3,
        ["'revolut'", "did you mean 'revolute'", "valid: revolute, continuous"],
    ),
    (
        "unsupported_joint_type",
        model(
            f"<link name='a'>{INERTIAL}</link><link name='b'>{INERTIAL}</link>\n"
            "<joint name='j' type='screw'><parent>a</parent><child>b</child></joint>"
        ),
        3,
        ["'screw' is not supported"],
    ),
    (
        "invalid_inertia",  # sdformat's MassMatrix3 check: principal moments break the triangle inequality
        model("<link name='a'><inertial>\n<mass>1</mass><inertia><ixx>1</ixx><iyy>1</iyy><izz>3</izz></inertia>"
              "</inertial></link>"),
        3,
        ["A link named a has invalid inertia", "izz 3"],
    ),
    (
        "zero_axis",
        model(
            f"<link name='a'>{INERTIAL}</link><link name='b'>{INERTIAL}</link><joint name='j' type='revolute'>"
            "<parent>a</parent><child>b</child><axis>\n<xyz>0 0 0</xyz></axis></joint>"
        ),
        3,
        ["The norm of the xyz vector cannot be zero"],
    ),
    (
        "two_shapes",
        model(
            "<link name='a'><visual name='v'>\n<geometry><box><size>1 1 1</size></box><sphere><radius>1</radius>"
            "</sphere></geometry></visual></link>",
            static=True,
        ),
        3,
        ["exactly one of"],
    ),
    (
        "missing_inertial",
        model(
            f"<link name='a'>{INERTIAL}</link>\n<link name='wheel'/>\n"
            "<joint name='j' type='continuous'><parent>a</parent><child>wheel</child></joint>"
        ),
        3,
        ["link 'wheel' moves", "continuous joint 'j'", "<inertial>"],
    ),
    ("free_body_without_mass", model("<link name='a'/>"), 2, ["link 'a' moves", "free body"]),
    (
        "unknown_relative_to",
        model("<link name='a'/>\n<link name='b'><pose relative_to='aa'>0 0 0 0 0 0</pose></link>", static=True),
        3,
        ["relative_to 'aa' names no frame", "did you mean 'a'"],
    ),
    (
        "relative_to_cycle",
        model(
            "<link name='a'><pose relative_to='f'>0 0 0 0 0 0</pose></link>\n"
            "<frame name='f' attached_to='a'><pose relative_to='a'>0 0 0 0 0 0</pose></frame>",
            static=True,
        ),
        2,
        ["relative_to cycle: a → f → a"],
    ),
    ("duplicate_name", model("<link name='a'/>\n<frame name='a'/>", static=True), 3, ["'a' is used twice"]),
    (
        "two_parents",
        model(
            f"<link name='a'>{INERTIAL}</link><link name='b'>{INERTIAL}</link><link name='c'>{INERTIAL}</link>\n"
            "<joint name='j1' type='fixed'><parent>a</parent><child>c</child></joint>\n"
            "<joint name='j2' type='fixed'><parent>b</parent><child>c</child></joint>"
        ),
        4,
        ["child of joints 'j1' and 'j2'", "tree"],
    ),
    ("bad_bool", model("<static>yes</static>\n<link name='a'/>"), 2, ["true/false", "'yes'"]),
    ("no_link", model("<frame name='f'/>"), 1, ["has no <link>"]),
    ("bad_version", '<sdf version="2.0"><model name="m"><link name="a"/></model></sdf>', 1, ["2.0", "supported"]),
    ("urdf", '<robot name="r">\n<link name="a"/></robot>', 1, ["<sdf>", "URDF"]),
    (
        "ros2_control_unknown_joint",
        model(
            f"<link name='a'>{INERTIAL}</link><link name='b'>{INERTIAL}</link>"
            "<joint name='wheel' type='continuous'><parent>a</parent><child>b</child></joint>\n"
            "<ros2_control name='r' type='system'><hardware><plugin>x/Y</plugin></hardware>\n"
            "<joint name='wheeel'><command_interface name='velocity'/></joint></ros2_control>"
        ),
        4,
        ["'wheeel'", "did you mean 'wheel'"],
    ),
    (
        "lidar_range",
        model(
            "<link name='a'><sensor name='s' type='gpu_lidar'><lidar>\n<range><min>5</min><max>1</max></range>"
            "</lidar></sensor></link>",
            static=True,
        ),
        3,
        ["<max> 1 must exceed <min> 5"],
    ),
    ("plugin_without_filename", model("<link name='a'/>\n<plugin name='x'/>", static=True), 3, ["'filename'"]),
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


@pytest.mark.parametrize(("text", "line", "needles"), [c[1:] for c in CASES], ids=[c[0] for c in CASES])
def test_bad_sdf_is_one_clear_error(text: str, line: int, needles: list[str]) -> None:
    with pytest.raises(DescriptionError) as info:
        parse_model(text, source="robot.sdf")
    err = info.value
    message = str(err)
    assert err.exit_code == 2
    assert message.startswith(f"robot.sdf:{line}"), message
    assert "\n" not in message, message
    for needle in needles:
        assert needle in message, message


def test_values_sdformat_accepts_load() -> None:
    """sdformat checks no shape size, and inertia only as a whole (zeros pass): such models load; the simulator
    later leaves a shape with no volume out."""
    text = model(
        "<link name='a'><inertial><mass>0.5</mass><inertia><ixx>0</ixx><iyy>0.1</iyy><izz>0.1</izz></inertia>"
        "</inertial><collision name='c'><geometry><box><size>0 1 1</size></box></geometry></collision>"
        "<visual name='v'><geometry><cylinder><radius>-1</radius><length>0</length></cylinder></geometry></visual>"
        "</link><link name='b'><inertial><mass>0</mass><inertia><ixx>0</ixx><iyy>0</iyy><izz>0</izz></inertia>"
        "</inertial></link><joint name='j' type='fixed'><parent>a</parent><child>b</child><axis><dynamics>"
        "<damping>-1</damping></dynamics></axis></joint>"
    )
    m = parse_model(text, source="robot.sdf")
    assert m.link("a").inertial.ixx == 0.0 and m.link("a").collisions[0].geometry.size_m == (0.0, 1.0, 1.0)
    # numbers as sdformat reads them (std::stod / std::stoi of the trimmed text: the number it starts with;
    # "true"/"false" are 1/0; an empty optional element is its default)
    from diffctl.description.sdf_values import c_double, c_int

    assert [c_double(t) for t in ("0.5m", " 2e3 ", "0x1p3", "true", ".5", "1e")] == [0.5, 2000.0, 8.0, 1.0, 0.5, 1.0]
    assert [c_int(t) for t in ("10.0", "0x10", "-3 ", "false")] == [10, 16, -3, 0]
    assert c_double("abc") is None and c_int("x1") is None
    lidar = parse_model(
        model(
            "<link name='a'><inertial><mass></mass></inertial><sensor name='s' type='gpu_lidar'><lidar><scan>"
            "<horizontal><samples>360.0</samples><min_angle>-3.14</min_angle><max_angle>3.14</max_angle>"
            "</horizontal></scan><range><min>0.1</min><max>10 m</max></range></lidar></sensor></link>",
            static=True,
        ),
        source="robot.sdf",
    )
    assert lidar.link("a").inertial.mass_kg == 1.0  # sdformat's default mass
    (spec,) = [s.lidar for s in lidar.sensors()]
    assert (spec.horizontal_samples, spec.range_max_m) == (360, 10.0)


def test_missing_files_and_includes(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    errors = _capture_errors(monkeypatch)
    with pytest.raises(DescriptionError, match="file not found"):
        load_world(tmp_path / "nope.world")
    world = tmp_path / "w.sdf"
    world.write_text('<sdf version="1.8"><world name="w">\n<include><uri>model://ghost</uri></include></world></sdf>')
    with pytest.raises(DescriptionError) as info:
        load_world(world)
    assert f"{world}:2" in str(info.value) and "'model://ghost' not found" in str(info.value)
    assert "GZ_SIM_RESOURCE_PATH" in str(info.value)
    mesh = tmp_path / "m.sdf"
    mesh.write_text(
        model(
            "<link name='a'><visual name='v'><geometry><mesh>\n<uri>meshes/x.stl</uri></mesh>"
            "</geometry></visual></link>",
            static=True,
        )
    )
    # as Gazebo: a missing visual mesh is an error line, and the model loads without that visual
    assert load_model(mesh).links[0].visuals == ()
    err = _take(errors)
    assert f"{mesh}:3: model[m]/link[a]/visual[v]/geometry/mesh/uri: mesh 'meshes/x.stl' not found" in err
    assert "the model loads without this visual" in err
    both = tmp_path / "both.sdf"
    both.write_text(mesh.read_text().replace("</visual>", "</visual><collision name='c'><geometry><mesh>\n"
                                             "<uri>meshes/y.stl</uri></mesh></geometry></collision>"))
    link = load_model(both).links[0]
    assert link.visuals == () and link.collisions == ()  # gz-sim's physics skips it with "Failed to load mesh"
    err = _take(errors)
    assert f"{both}:4: model[m]/link[a]/collision[c]/geometry/mesh/uri: mesh 'meshes/y.stl' not found" in err
    assert "the model loads without this collision (nothing collides with it)" in err
    # a description sent over the bus may carry paths of another machine: opt out of file checks
    assert load_model(mesh, check_files=False).links[0].visuals[0].geometry.path == ""
    (tmp_path / "meshes").mkdir()
    (tmp_path / "meshes" / "x.ply").write_text("ply")
    mesh.write_text(mesh.read_text().replace("x.stl", "x.ply"))
    with pytest.raises(DescriptionError, match=r"format '\.ply'.*supported: \.obj, \.stl, \.dae"):
        load_model(mesh)
    # COLLADA is read (converted as URDF meshes are); a broken one is reported at the SDF line naming it
    (tmp_path / "meshes" / "x.dae").write_text("<COLLADA/>")
    mesh.write_text(mesh.read_text().replace("x.ply", "x.dae"))
    with pytest.raises(DescriptionError, match=r"m\.sdf:3: .*mesh 'meshes/x\.dae'.*cannot be read") as e:
        load_model(mesh)
    assert e.value.line == 3
    loop = tmp_path / "loop.sdf"
    loop.write_text('<sdf version="1.8"><model name="m"><include><uri>loop.sdf</uri></include></model></sdf>')
    with pytest.raises(DescriptionError, match="include cycle"):
        load_model(loop)


def test_pose_relative_to_with_no_numbers_is_the_identity_in_that_frame() -> None:
    # Gazebo's own tutorials write <pose relative_to='frame'/>; only a bare <pose/> is refused.
    m = parse_model(
        model(
            "<link name='a'><pose>1 0 0 0 0 0</pose></link>\n<link name='b'><pose relative_to='a'/></link>", static=True
        )
    )
    assert m.link("b").pose_model.xyz == (1, 0, 0)


def test_unsimulated_sensor_types_are_listed_not_fatal() -> None:
    m = parse_model(model("<link name='a'><sensor name='bump' type='contact'/></link>", static=True))
    assert m.ignored == ("sensor 'bump' of type 'contact' on link 'a' is not simulated",)


def test_random_corruption_of_the_robot_file_never_escapes_as_another_exception() -> None:
    """Delete elements, blank texts and attributes at random: the loader loads or says DescriptionError."""
    base = (REPO / "description" / "my_diff_car_control.sdf").read_bytes()
    rng = random.Random(4)
    outcomes = {"ok": 0, "error": 0}
    for _ in range(300):
        root = etree.fromstring(base)
        elements = [e for e in root.iter() if isinstance(e.tag, str) and e is not root]
        for _ in range(rng.randint(1, 3)):
            e = rng.choice(elements)
            action = rng.randrange(4)
            if action == 0 and e.getparent() is not None:
                e.getparent().remove(e)
            elif action == 1:
                e.text = rng.choice(["", " ", "-1", "nan", "1e400", "abc", "0 0", "1 2 3 4 5 6 7 8"])
            elif action == 2 and e.attrib:
                e.set(rng.choice(list(e.attrib)), rng.choice(["", "::", "__model__", "nope", "world"]))
            else:
                e.tag = rng.choice(["pose", "frame", "joint", "model", "include", "link"])
        text = etree.tostring(root, encoding="unicode")
        try:
            parse_model(text, base_dir=REPO / "description")
            outcomes["ok"] += 1
        except DescriptionError as e:
            assert str(e).startswith("<string>"), str(e)
            outcomes["error"] += 1
    assert outcomes["error"] > 50 and outcomes["ok"] > 10, outcomes


def test_cli_style_child_process_survives_an_empty_pose(tmp_path: Path) -> None:
    """PyBullet's own loadSDF aborts the process on <pose/>; ours returns an error the caller can print."""
    bad = tmp_path / "bad.sdf"
    bad.write_text(model("<link name='a'><pose/></link>", static=True))
    code = (
        "import sys\nfrom diffctl.description.sdf_loader import load_model\nfrom diffctl.errors import DiffctlError\n"
        f"try:\n    load_model({str(bad)!r})\nexcept DiffctlError as e:\n    print(e)\n    sys.exit(e.exit_code)\n"
    )
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert r.returncode == 2, r.stderr
    assert f"{bad}:2: model[m]/link[a]/pose: empty <pose/>" in r.stdout
