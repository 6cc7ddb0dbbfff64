"""A workspace interface package is importable as rosidl would build it: rosidl's own test_msgs (every field
kind: arrays, bounded and unbounded sequences, defaults, constants, strings, nested, services, actions)
declared in a workspace behaves, serializes and hashes as the real generated test_msgs."""

from __future__ import annotations

import json

import pytest

from tests.interfaces.programs import assert_same, run_oracle, run_ours
from tests.interfaces.test_wire_agreement import same_wire
from tests.oracle import jazzy_venv

MSGS = ["Arrays", "BasicTypes", "BoundedPlainSequences", "BoundedSequences", "Builtins", "Constants", "Defaults",
        "Empty", "MultiNested", "Nested", "Strings", "UnboundedSequences", "WStrings"]

PROGRAM = r'''
import importlib
import test_msgs.msg as M
import test_msgs.srv as S
import test_msgs.action as A
TYPES = [getattr(M, n) for n in %r]
TYPES += [S.Arrays.Request, S.Arrays.Response, S.BasicTypes.Request, S.Empty.Response, S.Arrays.Event]
F = A.Fibonacci
TYPES += [F.Goal, F.Result, F.Feedback, F.Impl.SendGoalService.Request, F.Impl.SendGoalService.Response,
          F.Impl.GetResultService.Request, F.Impl.GetResultService.Response, F.Impl.FeedbackMessage,
          F.Impl.SendGoalService.Event, A.NestedMessage.Goal, A.NestedMessage.Impl.FeedbackMessage]
for T in TYPES:
    n = T.__module__ + '.' + T.__name__
    obs(n + ' repr', lambda T=T: T())
    obs(n + ' fields', lambda T=T: T.get_fields_and_field_types())
    obs(n + ' slot types', lambda T=T: [slot(t) for t in T.SLOT_TYPES])
    obs(n + ' kinds', lambda T=T: [kind(getattr(T(), f)) for f in T.get_fields_and_field_types()])
    obs(n + ' public', lambda T=T: sorted(a for a in dir(T) if not a.startswith('_')))
    obs(n + ' eq', lambda T=T: T() == T())
    obs(n + ' defaults', lambda T=T: {a: repr(getattr(T, a)) for a in dir(T) if a.endswith('__DEFAULT')})
obs('action', lambda: (F.Goal, F.Impl.SendGoalService, F.Impl.CancelGoalService, F.Impl.GoalStatusMessage,
                       type(F).__name__))
obs('action instantiate', lambda: F())
obs('action exports', lambda: sorted(n for n in dir(A) if not n.startswith('_')))
obs('srv exports', lambda: sorted(n for n in dir(S) if not n.startswith('_')))
obs('bounded', lambda: M.BoundedSequences(int32_values=[1, 2, 3, 4]))
obs('bounded string', lambda: M.Strings(bounded_string_value='x' * 30))
obs('bounded strings seq', lambda: M.BoundedSequences(string_values=['a'] * 4))
obs('defaults values', lambda: M.Defaults())
obs('arrays defaults', lambda: (M.Arrays().float32_values_default, M.Arrays().string_values_default))
obs('constants', lambda: (M.Constants.BYTE_CONST, M.Constants.CHAR_CONST, M.Constants.FLOAT32_CONST,
                          M.Strings.STRING_VALUE_CONST if hasattr(M.Strings, 'STRING_VALUE_CONST') else None))
obs('wstrings', lambda: M.WStrings(wstring_value='ä'))
obs('nested', lambda: M.MultiNested(bounded_sequence_of_arrays=[M.Arrays()]).bounded_sequence_of_arrays[0]
    .int8_values)
obs('builtins', lambda: M.Builtins().time_value)
'''


@pytest.mark.parametrize("check", ["", "1"], ids=["checks-off", "checks-on"])
def test_workspace_package_behaves_as_the_real_build(test_msgs_workspace, check: str) -> None:
    program = PROGRAM % MSGS
    env = {"ROS_PYTHON_CHECK_FIELDS": check} if check else {}
    ours = run_ours(program, {**env, "DIFFCTL_WORKSPACE": str(test_msgs_workspace)})
    assert_same(ours, run_oracle(program, env or None))


WIRE = r'''
import math
import test_msgs.msg as M
from test_msgs.action import Fibonacci
msgs = {n: getattr(M, n)() for n in %r}
msgs['basic'] = M.BasicTypes(bool_value=True, byte_value=b'\x05', char_value=66, float32_value=1.5,
                             float64_value=-2.25, int8_value=-3, uint8_value=250, int16_value=-1000,
                             uint16_value=60000, int32_value=-7, uint32_value=7, int64_value=-2**40,
                             uint64_value=2**63)
msgs['arrays'] = M.Arrays(bool_values=[True, False, True], byte_values=[b'\x01', b'\x02', b'\x03'],
                          string_values=['a', 'bb', ''], int64_values=[1, -2, 3])
msgs['unbounded'] = M.UnboundedSequences(bool_values=[True], byte_values=[b'\x09'], float64_values=[1.0, 2.0],
                                         string_values=['x'], basic_types_values=[M.BasicTypes(int8_value=1)],
                                         uint16_values=[1, 2, 3], alignment_check=9)
msgs['bounded'] = M.BoundedSequences(int8_values=[1], float64_values=[3.0], string_values=['q'],
                                     alignment_check=3)
msgs['strings'] = M.Strings(string_value='ünïcode', bounded_string_value='b')
msgs['wstrings'] = M.WStrings(wstring_value='abä\U0001F600', array_of_wstrings=['x', '', 'ハ'],
                              unbounded_sequence_of_wstrings=['', 'q'])
msgs['multi'] = M.MultiNested(unbounded_sequence_of_bounded_sequences=[M.BoundedSequences(int32_values=[5])])
msgs['goal_req'] = Fibonacci.Impl.SendGoalService.Request(goal=Fibonacci.Goal(order=5))
msgs['feedback'] = Fibonacci.Impl.FeedbackMessage(feedback=Fibonacci.Feedback(sequence=[0, 1, 1, 2]))
msgs['result_resp'] = Fibonacci.Impl.GetResultService.Response(status=4,
                                                               result=Fibonacci.Result(sequence=[1, 2]))
'''


def test_workspace_package_on_the_wire(test_msgs_workspace) -> None:
    program = WIRE % MSGS
    oracle = run_oracle(program + r'''
from rclpy.serialization import serialize_message
for k, m in msgs.items():
    obs(k, lambda m=m: serialize_message(m).hex())
    obs(k + ' repr', lambda m=m: m)
''')
    assert all(v[0] == "ok" for v in oracle.values()), oracle
    hexes = {k: v[1] for k, v in oracle.items() if not k.endswith(" repr")}
    ours = run_ours(program + f"HEX = {json.dumps(hexes)}\n" + r'''
from diffctl.interfaces import serialize, deserialize
for k, m in msgs.items():
    obs(k, lambda m=m: serialize(m).hex())
    obs(k + ' repr', lambda k=k, m=m: deserialize(bytes.fromhex(HEX[k]), type(m)))
''', {"DIFFCTL_WORKSPACE": str(test_msgs_workspace)})
    bad = {k: (ours[k], oracle[k]) for k in hexes if ours[k][0] != "ok" or not same_wire(ours[k][1], oracle[k][1])}
    bad.update({k: (ours[k], oracle[k]) for k in oracle if k.endswith(" repr") and ours[k] != oracle[k]})
    assert not bad, "\n".join(f"{k}: diffctl {a} != rosidl {b}" for k, (a, b) in bad.items())


def test_workspace_package_hashes_as_rosidl(test_msgs_workspace) -> None:
    real = {}
    for path in sorted(jazzy_venv.share("test_msgs").glob("*/*.json")):
        for entry in json.loads(path.read_text())["type_hashes"]:
            real[entry["type_name"]] = entry["hash_string"]
    ours = run_ours(f"NAMES = {sorted(real)!r}\n" + r'''
from diffctl.interfaces import registry
from diffctl.interfaces import types
for n in NAMES:
    registry.package(n.split('/')[0])
    obs(n, lambda n=n: types.type_hash(n))
''', {"DIFFCTL_WORKSPACE": str(test_msgs_workspace)})
    assert {k: v[1] for k, v in ours.items()} == real


SETTERS = r'''
import array
import numpy
import test_msgs.msg as M
BAD = {"str": "x", "int": 1, "neg": -1, "big": 2**70, "float": 1.5, "inf": float("inf"), "huge": 1e300,
       "bytes": b"ab", "byte": b"a", "none": None, "list": [1, 2], "flist": [1.0, 2.0, 3.0],
       "longlist": list(range(40)), "strs": ["a", "b", "c"], "longstrs": ["x" * 30] * 2, "nan": float("nan"),
       "ndarray": numpy.zeros(3, dtype=numpy.int32), "ndarray3f": numpy.zeros(3, dtype=numpy.float32),
       "arr_d": array.array("d", [1.0]), "arr_i": array.array("i", [1] * 4), "bools": [True, False, True],
       "tuple": (1, 2, 3), "set": {1, 2, 3}, "longstr": "y" * 30}
for T in (M.BasicTypes, M.Arrays, M.BoundedSequences, M.UnboundedSequences, M.BoundedPlainSequences,
          M.Strings, M.WStrings, M.Nested, M.MultiNested, M.Builtins):
    for field in T.get_fields_and_field_types():
        for label, value in BAD.items():
            def set_it(T=T, field=field, value=value):
                m = T()
                setattr(m, field, value)
                return getattr(m, field)
            obs(f"{T.__name__}.{field}={label}", set_it)
'''


@pytest.mark.parametrize("check", ["", "1"], ids=["checks-off", "checks-on"])
def test_field_setters_check_as_rosidl(test_msgs_workspace, check: str) -> None:
    """Every field kind of test_msgs given wrong values, with and without ROS_PYTHON_CHECK_FIELDS=1: the same
    values are accepted (and converted the same way), the same are refused with rosidl's assertion message."""
    env = {"ROS_PYTHON_CHECK_FIELDS": check}
    ours = run_ours(SETTERS, {**env, "DIFFCTL_WORKSPACE": str(test_msgs_workspace)})
    oracle = run_oracle(SETTERS, env)
    assert len(oracle) > 1000
    assert_same(ours, oracle)


def test_workspace_package_filled_in_agrees_on_the_wire(test_msgs_workspace) -> None:
    """test_msgs' every message and service part, each field filled in from its SLOT_TYPES (the sweep of
    test_wire_agreement): the same bytes as the real build, and the real bytes decode to the same message."""
    from tests.interfaces.test_wire_agreement import SWEEP

    program = SWEEP % ["test_msgs"]
    oracle = run_oracle(program + r'''
from rclpy.serialization import serialize_message
for k, m in msgs.items():
    obs(k, lambda m=m: serialize_message(m).hex())
    obs(k + ' repr', lambda m=m: m)
''')
    assert len(oracle) > 2 * 20 and all(v[0] == "ok" for v in oracle.values()), oracle
    hexes = {k: v[1] for k, v in oracle.items() if not k.endswith(" repr")}
    ours = run_ours(program + f"HEX = {json.dumps(hexes)}\n" + r'''
from diffctl.interfaces import serialize, deserialize
for k, m in msgs.items():
    obs(k, lambda m=m: serialize(m).hex())
    obs(k + ' repr', lambda k=k, m=m: deserialize(bytes.fromhex(HEX[k]), type(m)))
''', {"DIFFCTL_WORKSPACE": str(test_msgs_workspace)})
    bad = [k for k in hexes if ours[k][0] != "ok" or not same_wire(ours[k][1], oracle[k][1])]
    bad += [k for k in oracle if k.endswith(" repr") and ours[k] != oracle[k]]
    assert not bad, "\n".join(f"{k}: diffctl {ours[k]} != rosidl {oracle[k]}" for k in bad[:5])
