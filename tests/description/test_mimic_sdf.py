"""`<axis><mimic>` (SDF 1.11, sdformat's mimic.sdf) is read into Joint.mimic; a bad one is one error naming its line."""

from __future__ import annotations

import pytest

from diffctl.description.robot_files import parse_description
from diffctl.description.sdf_loader import parse_model
from diffctl.errors import DescriptionError

LINKS = "".join(
    f"<link name='{n}'><inertial><mass>0.1</mass></inertial></link>" for n in ("palm", "left", "right", "thumb")
)


def joint(name: str, child: str, mimic: str = "", kind: str = "prismatic") -> str:
    return (
        f"<joint name='{name}' type='{kind}'><parent>palm</parent><child>{child}</child>\n"
        f"<axis><xyz>0 1 0</xyz>{mimic}</axis></joint>"
    )


def model(*joints: str) -> str:
    # Line 1 holds the header and the links; each joint takes two lines, its <axis> on the second (3, 5, …).
    return f'<sdf version="1.11"><model name="g">{LINKS}\n' + "\n".join(joints) + "\n</model></sdf>"


def test_mimic_is_read_with_sdformat_defaults_and_reference_folded_into_offset() -> None:
    m = parse_model(
        model(
            joint("left_joint", "left"),
            joint(
                "right_joint",
                "right",
                "<mimic joint='left_joint'><multiplier>-2</multiplier><offset>0.01</offset>"
                "<reference>0.003</reference></mimic>",
            ),
            joint("thumb_joint", "thumb", "<mimic joint='right_joint'/>", kind="revolute"),
        )
    )
    assert m.joint("left_joint").mimic is None
    leader, multiplier, offset = m.joint("right_joint").mimic
    # follower = multiplier · (leader − reference) + offset = multiplier · leader + (offset − multiplier · reference)
    assert (leader, multiplier) == ("left_joint", -2.0) and offset == pytest.approx(0.01 + 2 * 0.003)
    assert m.joint("thumb_joint").mimic == ("right_joint", 1.0, 0.0)  # defaults: multiplier 1, offset 0


def test_urdf_mimic_reaches_the_model_through_the_converter() -> None:
    inertial = '<inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>'
    urdf = f"""<robot name="g">
      <link name="palm">{inertial}</link><link name="a">{inertial}</link><link name="b">{inertial}</link>
      <joint name="ja" type="prismatic"><parent link="palm"/><child link="a"/>
        <limit lower="0" upper="0.04" effort="10" velocity="1"/></joint>
      <joint name="jb" type="prismatic"><parent link="palm"/><child link="b"/>
        <limit lower="-0.04" upper="0" effort="10" velocity="1"/>
        <mimic joint="ja" multiplier="-1" offset="0.002"/></joint>
    </robot>"""
    m = parse_description(urdf)
    assert m.joint("jb").mimic == ("ja", -1.0, 0.002)
    assert not any("mimic" in note for note in m.ignored)  # simulated, so not reported as ignored


@pytest.mark.parametrize(
    ("joints", "line", "needles"),
    [
        ((joint("a", "left"), joint("b", "right", "<mimic joint='lefty'/>")), 5, ["'lefty'", "names no joint"]),
        ((joint("a", "left"), joint("b", "right", "<mimic joint='palm'/>")), 5, ["'palm'", "names no joint"]),
        ((joint("a", "left", "<mimic/>"),), 3, ["needs a 'joint' attribute"]),
        ((joint("a", "left", "<mimic joint='a'/>"),), 3, ["cannot mimic itself"]),
        (
            (joint("a", "left", "<mimic joint='b'/>"), joint("b", "right", "<mimic joint='a'/>")),
            2,
            ["loop", "a → b → a"],
        ),
        ((joint("a", "left", kind="fixed"), joint("b", "right", "<mimic joint='a'/>")), 5, ["fixed", "no axis"]),
        ((joint("a", "left"), joint("b", "right", "<mimic joint='a' axis='axis2'/>")), 5, ["single axis"]),
        (
            (joint("a", "left"), joint("b", "right", "<mimic joint='a'><multiplier>nan</multiplier></mimic>")),
            5,
            ["<multiplier>", "finite"],
        ),
    ],
)
def test_bad_mimic_is_one_error_on_its_line(joints: tuple[str, ...], line: int, needles: list[str]) -> None:
    with pytest.raises(DescriptionError) as info:
        parse_model(model(*joints), source="gripper.sdf")
    message = str(info.value)
    assert message.startswith(f"gripper.sdf:{line}") and "\n" not in message, message
    for needle in needles:
        assert needle in message, message
