"""Every controller lifecycle transition, switch strictness and interface conflict, on mock hardware (the
controllers on real client nodes)."""

from __future__ import annotations

import threading
import time

import pytest
from control_fakes import loaded, make_manager, wheel_info

from diffctl.control.controller_interface import ReturnType
from diffctl.control.lifecycle import State, TransitionError
from diffctl.control.switching import AUTO, BEST_EFFORT, STRICT

pytestmark = pytest.mark.usefixtures("client_bus")
L_VEL, R_VEL = "left_wheel/velocity", "right_wheel/velocity"
L_POS = "left_wheel/position"


def test_load_requires_a_known_type_and_a_unique_name() -> None:
    cm, _ = make_manager({"a": {}})
    with pytest.raises(TransitionError, match="'type' param was not defined for 'nope'"):
        cm.load_controller("nope")
    with pytest.raises(TransitionError, match=r"unknown controller plugin 'diff_drive_controler/X'"):
        cm.load_controller("b", "diff_drive_controler/X")
    mc = cm.load_controller("a")
    assert mc.state is State.UNCONFIGURED and mc.instance.calls == ["on_init"]
    with pytest.raises(TransitionError, match="already loaded"):
        cm.load_controller("a")


def test_on_init_failure_leaves_nothing_loaded() -> None:
    cm, _ = make_manager({"a": {"raise_in": ["on_init"]}})
    with pytest.raises(TransitionError, match="on_init exploded"):
        cm.load_controller("a")
    assert "a" not in cm.controllers and cm.nodes["a"]._destroyed


def test_configure_cleanup_unload_transitions() -> None:
    cm, _ = make_manager({"a": {"commands": [L_VEL]}})
    cm.load_controller("a")
    with pytest.raises(TransitionError, match="can not be cleaned up from 'unconfigured'"):
        cm.cleanup_controller("a")
    cm.configure_controller("a")
    mc = cm.controllers["a"]
    assert mc.state is State.INACTIVE and mc.required_command == [L_VEL]
    # configure from inactive = cleanup, then configure
    cm.configure_controller("a")
    assert mc.instance.calls[-3:] == ["on_configure", "on_cleanup", "on_configure"]
    assert cm.switch_controller(["a"], [], STRICT) == (True, "")
    with pytest.raises(TransitionError, match="can not be configured from 'active'"):
        cm.configure_controller("a")
    with pytest.raises(TransitionError, match="can not be cleaned up from 'active'"):
        cm.cleanup_controller("a")
    with pytest.raises(TransitionError, match="still active"):
        cm.unload_controller("a")
    assert cm.switch_controller([], ["a"], STRICT)[0]
    assert mc.state is State.INACTIVE and cm.rm.claimed == {}
    cm.cleanup_controller("a")
    assert mc.state is State.UNCONFIGURED
    cm.configure_controller("a")
    cm.unload_controller("a")  # inactive → cleanup → shutdown
    assert mc.instance.calls[-2:] == ["on_cleanup", "on_shutdown"]
    assert mc.state is State.FINALIZED and "a" not in cm.controllers and cm.nodes["a"]._destroyed
    with pytest.raises(TransitionError, match="not loaded"):
        cm.configure_controller("a")


def test_failing_hooks_keep_the_previous_state() -> None:
    cm, _ = make_manager({"a": {"raise_in": ["on_configure"]}, "b": {"commands": [L_VEL], "raise_in": ["on_activate"]}})
    cm.load_controller("a")
    with pytest.raises(TransitionError, match="on_configure failed: RuntimeError: on_configure exploded"):
        cm.configure_controller("a")
    assert cm.controllers["a"].state is State.UNCONFIGURED
    loaded(cm, "b")
    ok, msg = cm.switch_controller(["b"], [], STRICT)
    assert not ok and "on_activate failed" in msg
    assert cm.controllers["b"].state is State.INACTIVE and cm.rm.claimed == {}


def test_strict_aborts_on_any_bad_entry() -> None:
    cm, _ = make_manager({"a": {"commands": [L_VEL]}, "u": {}})
    loaded(cm, "a")
    cm.load_controller("u")  # unconfigured
    for act, deact, why in (
        (["a", "ghost"], [], "'ghost': it is not loaded"),
        (["a", "u"], [], "'u': it is not configured"),
        (["a"], ["a"], "deactivate controller 'a': it is not active"),
    ):
        ok, msg = cm.switch_controller(act, deact, STRICT)
        assert not ok and why in msg and "Aborting, no controller is switched!" in msg
        assert cm.controllers["a"].state is State.INACTIVE
    assert cm.switch_controller(["a"], [], STRICT)[0]
    ok, msg = cm.switch_controller(["a"], [], STRICT)
    assert not ok and "already active" in msg


def test_best_effort_drops_bad_entries() -> None:
    cm, log = make_manager({"a": {"commands": [L_VEL]}})
    loaded(cm, "a")
    ok, msg = cm.switch_controller(["a", "ghost"], ["ghost2"], BEST_EFFORT)
    assert ok and cm.controllers["a"].state is State.ACTIVE
    assert "'ghost': it is not loaded" in log.text("WARN")
    assert cm.switch_controller(["a"], [], BEST_EFFORT) == (True, "no controllers need to be activated or deactivated")
    ok, msg = cm.switch_controller(["ghost"], [], BEST_EFFORT)
    assert not ok and "not loaded" in msg
    assert cm.switch_controller([], [], STRICT) == (True, "no controllers need to be activated or deactivated")
    # AUTO is not implemented upstream: warned about, then best effort; strictness 0 = the manager default.
    assert cm.switch_controller([], ["a", "ghost"], AUTO)[0] and "not currently implemented" in log.text("WARN")
    assert cm.switch_controller(["a", "ghost"], [], 0)[0]
    cm2, _ = make_manager({"a": {}}, **{"defaults.switch_controller.strictness": "strict"})
    loaded(cm2, "a")
    assert not cm2.switch_controller(["a", "ghost"], [], 0)[0]


def test_command_interfaces_are_exclusive_and_state_interfaces_shared() -> None:
    cm, _ = make_manager(
        {
            "a": {"commands": [L_VEL, R_VEL], "states": [L_POS]},
            "b": {"commands": [L_VEL], "states": [L_POS]},
            "c": {"states": [L_POS, "right_wheel/velocity"]},
            "bad": {"commands": ["left_wheel/effort"]},
        }
    )
    loaded(cm, "a", "b", "c", "bad")
    ok, msg = cm.switch_controller(["a", "b"], [], BEST_EFFORT)
    assert not ok and "will be used by another controller that is being activated ('a')" in msg
    assert cm.switch_controller(["a", "c"], [], STRICT)[0]  # c shares a's state interface
    ok, msg = cm.switch_controller(["b"], [], BEST_EFFORT)
    assert not ok and "currently claimed by another controller 'a'" in msg
    assert cm.rm.claimed == {L_VEL: "a", R_VEL: "a"}
    # deactivating the holder in the same request frees the interface: one cycle swap
    assert cm.switch_controller(["b"], ["a"], STRICT)[0]
    assert cm.rm.claimed == {L_VEL: "b"}
    assert [cm.controllers[n].state for n in "abc"] == [State.INACTIVE, State.ACTIVE, State.ACTIVE]
    assert cm.controllers["a"].instance.calls[-1] == "on_deactivate"
    ok, msg = cm.switch_controller(["bad"], [], STRICT)
    assert not ok and "'left_wheel/effort' is not available" in msg


def test_claim_all_takes_every_command_interface() -> None:
    cm, _ = make_manager({"all": {"commands": "all"}, "b": {"commands": [R_VEL]}})
    loaded(cm, "all", "b")
    assert cm.switch_controller(["all"], [], STRICT)[0]
    assert sorted(cm.rm.claimed) == [L_VEL, R_VEL]
    assert [c.name for c in cm.controllers["all"].instance.command_interfaces] == [L_VEL, R_VEL]
    assert not cm.switch_controller(["b"], [], STRICT)[0]


def test_interfaces_are_loaned_in_configuration_order_and_written_by_update() -> None:
    cm, _ = make_manager({"a": {"commands": [R_VEL, L_VEL], "states": ["right_wheel/velocity"], "command_value": 2.5}})
    loaded(cm, "a")
    cm.switch_controller(["a"], [], STRICT)
    inst = cm.controllers["a"].instance
    assert [c.name for c in inst.command_interfaces] == [R_VEL, L_VEL]
    cm.read(0, 0.01)
    cm.update(10_000_000, 0.01)
    cm.write(10_000_000, 0.01)
    cm.read(20_000_000, 0.01)  # GenericSystem mirrors the velocity command into the state
    assert cm.state_value("right_wheel/velocity") == 2.5
    assert inst.updates == [(10_000_000, 0.01)]


def test_update_error_or_exception_deactivates_with_the_reason() -> None:
    cm, log = make_manager(
        {
            "a": {"commands": [L_VEL]},
            "b": {"commands": [R_VEL], "raise_in": ["update"]},
            "spare": {"commands": [L_VEL]},
        },
        **{"a.fallback_controllers": ["spare"]},
    )
    loaded(cm, "a", "b", "spare")
    assert cm.switch_controller(["a", "b"], [], STRICT)[0]
    cm.controllers["a"].instance.result = ReturnType.ERROR
    cm.update(1, 0.01)
    a, b, spare = (cm.controllers[n] for n in ("a", "b", "spare"))
    assert a.state is State.INACTIVE and a.last_error == "update() returned ERROR"
    assert b.state is State.INACTIVE and "ValueError: update exploded" in b.last_error
    assert "controller 'b' update() raised ValueError: update exploded: deactivating it" in log.text("ERROR")
    # deactivation wrote zero; the fallback took over the freed interface
    assert spare.state is State.ACTIVE and cm.rm.claimed == {L_VEL: "spare"}
    assert cm.rm.command_interfaces[R_VEL].value == 0.0


def test_hardware_read_error_deactivates_its_controllers() -> None:
    cm, log = make_manager(
        {"a": {"commands": [L_VEL]}, "other": {"commands": ["j/velocity"]}},
        hardware=[wheel_info(), wheel_info("arm", joints=("j",))],
    )
    loaded(cm, "a", "other")
    assert cm.switch_controller(["a", "other"], [], STRICT)[0]
    cm.rm.command_interfaces[L_VEL].value = float("inf")  # GenericSystem's read() fails on an infinite command
    cm.read(0, 0.01)
    assert cm.controllers["a"].state is State.INACTIVE
    assert cm.controllers["other"].state is State.ACTIVE
    assert cm.rm.components["robot"].state is State.UNCONFIGURED
    assert "hardware 'robot' read returned ERROR: deactivating controllers [a]" in log.text("ERROR")
    assert not cm.switch_controller(["a"], [], STRICT)[0]  # its interfaces are gone with the hardware


def test_hardware_component_states_gate_interfaces() -> None:
    cm, _ = make_manager({"a": {"commands": [L_VEL], "states": [L_POS]}, "s": {"states": [L_POS]}})
    loaded(cm, "a", "s")
    assert cm.switch_controller(["a", "s"], [], STRICT)[0]
    assert cm.set_hardware_component_state("robot", State.INACTIVE) is State.INACTIVE
    assert cm.controllers["a"].state is State.INACTIVE  # lost its command interface
    assert cm.controllers["s"].state is State.ACTIVE  # state interfaces stay available while inactive
    assert not cm.rm.command_available(L_VEL) and cm.rm.state_available(L_POS)
    assert not cm.switch_controller(["a"], [], STRICT)[0]
    assert cm.set_hardware_component_state("robot", State.UNCONFIGURED) is State.UNCONFIGURED
    assert cm.controllers["s"].state is State.INACTIVE
    assert cm.set_hardware_component_state("robot", State.ACTIVE) is State.ACTIVE
    assert cm.switch_controller(["a", "s"], [], STRICT)[0]
    with pytest.raises(TransitionError, match="no hardware component named 'nope'"):
        cm.set_hardware_component_state("nope", State.ACTIVE)


def test_initial_hardware_states_from_parameters() -> None:
    cm, _ = make_manager(
        hardware=[wheel_info("a", joints=("x",)), wheel_info("b", joints=("y",)), wheel_info()],
        **{
            "hardware_components_initial_state.unconfigured": ["a"],
            "hardware_components_initial_state.inactive": ["b"],
        },
    )
    states = {n: h.state for n, h in cm.rm.components.items()}
    assert states == {"a": State.UNCONFIGURED, "b": State.INACTIVE, "robot": State.ACTIVE}


def test_controller_update_rate_divides_the_manager_rate() -> None:
    cm, log = make_manager({"slow": {"update_rate": 20}, "fast": {"update_rate": 500}})
    loaded(cm, "slow", "fast")
    assert "cannot be higher than the update rate of the controller manager : '100 Hz'" in log.text("WARN")
    cm.switch_controller(["slow", "fast"], [], STRICT)
    for k in range(1, 21):
        cm.update(k * 10_000_000, 0.01)
    slow = cm.controllers["slow"].instance.updates
    assert len(cm.controllers["fast"].instance.updates) == 20
    assert [t for t, _ in slow] == [10_000_000, 60_000_000, 110_000_000, 160_000_000]
    assert [round(p, 6) for _, p in slow] == [0.01, 0.05, 0.05, 0.05]


def test_switch_waits_for_the_realtime_loop_and_times_out_without_it() -> None:
    cm, _ = make_manager({"a": {"commands": [L_VEL]}})
    loaded(cm, "a")
    cm.loop_running = True  # nobody calls update(): the switch can never happen
    t0 = time.monotonic()
    assert cm.switch_controller(["a"], [], STRICT, timeout_s=0.2) == (
        False,
        "Switch controller timed out after 0.2 seconds!",
    )
    assert 0.2 <= time.monotonic() - t0 < 1.0 and cm.controllers["a"].state is State.INACTIVE
    stop = threading.Event()

    def loop() -> None:
        k = 0
        while not stop.is_set():
            k += 1
            cm.update(k * 10_000_000, 0.01)
            time.sleep(0.01)

    th = threading.Thread(target=loop)
    th.start()
    try:
        assert cm.switch_controller(["a"], [], STRICT, activate_asap=True, timeout_s=2.0) == (True, "")
        assert cm.controllers["a"].state is State.ACTIVE
    finally:
        stop.set()
        th.join()


def test_shutdown_deactivates_and_finalizes_everything() -> None:
    cm, _ = make_manager({"a": {"commands": [L_VEL]}})
    loaded(cm, "a")
    cm.switch_controller(["a"], [], STRICT)
    inst = cm.controllers["a"].instance
    cm.shutdown()
    assert inst.calls[-3:] == ["on_deactivate", "on_cleanup", "on_shutdown"]
    assert cm.controllers == {} and cm.rm.components["robot"].state is State.FINALIZED
