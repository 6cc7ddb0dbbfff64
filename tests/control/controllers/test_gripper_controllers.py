"""The gripper action controllers (gripper_controllers' position/effort GripperActionController and
parallel_gripper_action_controller) on real client nodes spun by an executor, goals sent by a real ActionClient
over the router: interfaces as upstream's tests configure them (joint_1), a goal reached within goal_tolerance,
a stall aborted (or succeeding with allow_stalling), a cancel holding position, a parallel goal's effort and speed
written to the named interfaces."""

from __future__ import annotations

import threading
import time

import pytest
from controller_harness import START_NS, activate, configure, hand_interfaces, make_controller, update

from diffctl.client.action.client import ActionClient
from diffctl.client.executors import SingleThreadedExecutor
from diffctl.client.interfaces import cls
from diffctl.control.controller_interface import CallbackReturn
from diffctl.control.controllers.gripper_action_controller import (
    EffortGripperActionController,
    PositionGripperActionController,
)
from diffctl.control.controllers.parallel_gripper_action_controller import GripperActionController
from diffctl.control.lifecycle import State

pytestmark = pytest.mark.usefixtures("client_bus")


class Rig:
    """The controller active on its interfaces, its node and a client node spun by an executor thread; `step`
    advances sim time by 10 ms with the joint moving as commanded (position hardware) or held (stalled)."""

    def __init__(self, cls_, name, params, values=None) -> None:
        from diffctl.client.node import Node

        self.c = make_controller(cls_, name, params)
        configure(self.c)
        self.cmd, self.state = hand_interfaces(self.c, values or {})
        activate(self.c)
        self.name = name
        self.client_node = Node(f"{name}_client")
        self.executor = SingleThreadedExecutor()
        self.executor.add_node(self.c.get_node())
        self.executor.add_node(self.client_node)
        threading.Thread(target=self.executor.spin, daemon=True).start()
        self.time_ns = START_NS

    def step(self, moving: bool = True) -> None:
        self.time_ns += 10_000_000
        self.c.probe.time_ns = self.time_ns
        update(self.c, self.time_ns, 0.01)
        joint = self.c.values["joint"]
        pos, vel = self.state[f"{joint}/position"], self.state[f"{joint}/velocity"]
        target = self.cmd.get(f"{joint}/position")
        if moving and target is not None:
            step = max(-0.005, min(0.005, target.value - pos.value))  # 0.5 m/s towards the command
            pos.value += step
            vel.value = step / 0.01
        else:
            vel.value = 0.0

    def goal(self, action: str, fill, moving: bool = True, cancel_after: int | None = None):
        types = cls(action)
        client = ActionClient(self.client_node, types, f"/{self.name}/gripper_cmd")
        assert client.wait_for_server(timeout_sec=10.0)
        goal = types.Goal()
        fill(goal)
        sent = client.send_goal_async(goal)
        deadline = time.monotonic() + 10
        while not sent.done():
            assert time.monotonic() < deadline
            time.sleep(0.005)
        handle = sent.result()
        if not handle.accepted:
            return None
        result = handle.get_result_async()
        steps = 0
        while not result.done():
            assert time.monotonic() < deadline, "no result"
            self.step(moving)
            steps += 1
            if cancel_after is not None and steps == cancel_after:
                cancelled = handle.cancel_goal_async()
                while not cancelled.done():
                    time.sleep(0.005)
            time.sleep(0.002)
        return result.result()

    def close(self) -> None:
        self.executor.shutdown(timeout_sec=2.0)
        self.client_node.destroy_node()


GRIPPER = "control_msgs/action/GripperCommand"
PARALLEL = "control_msgs/action/ParallelGripperCommand"


@pytest.mark.parametrize(("cls_", "kind"), [(PositionGripperActionController, "position"),
                                            (EffortGripperActionController, "effort")])
def test_legacy_gripper_interfaces(cls_, kind) -> None:
    # ConfigureParamsSuccess / JointParameterIsEmpty
    c = make_controller(cls_, "test_gripper_action_controller", {"joint": "joint_1"})
    assert "[Deprecated]" in c.probe.log.text("WARN")
    configure(c)
    assert c.command_interface_configuration().names == [f"joint_1/{kind}"]
    assert c.state_interface_configuration().names == ["joint_1/position", "joint_1/velocity"]
    assert make_controller(cls_, "test_gripper_action_controller", {}).on_configure(State.UNCONFIGURED) \
        is CallbackReturn.ERROR


def test_position_gripper_goals() -> None:
    rig = Rig(PositionGripperActionController, "gripper_controller",
              {"joint": "joint_1", "goal_tolerance": 0.01, "stall_timeout": 0.2, "max_effort": 5.0})
    try:
        def to(position):
            def fill(goal):
                goal.command.position, goal.command.max_effort = position, 3.0
            return fill

        out = rig.goal(GRIPPER, to(0.08))
        assert out.status == 4 and out.result.reached_goal and not out.result.stalled  # SUCCEEDED
        assert abs(out.result.position - 0.08) < 0.01 and out.result.effort == 3.0
        # blocked by an object: no motion for stall_timeout → aborted (stalled)
        out = rig.goal(GRIPPER, to(0.0), moving=False)
        assert out.status == 6 and out.result.stalled and not out.result.reached_goal  # ABORTED
        # a cancel holds where the gripper is
        out = rig.goal(GRIPPER, to(0.5), cancel_after=5)
        assert out.status == 5  # CANCELED
        held = rig.cmd["joint_1/position"].value
        assert held == pytest.approx(rig.state["joint_1/position"].value, abs=0.006) and held < 0.2
    finally:
        rig.close()


def test_parallel_gripper_goals() -> None:
    params = {"joint": "joint_1", "max_effort_interface": "joint_1/max_effort",
              "max_velocity_interface": "joint_1/max_velocity", "allow_stalling": True, "stall_timeout": 0.1}
    rig = Rig(GripperActionController, "parallel_gripper_controller", params)
    try:
        assert rig.c.command_interface_configuration().names == ["joint_1/position", "joint_1/max_effort",
                                                                 "joint_1/max_velocity"]
        update(rig.c, START_NS, 0.01)
        assert (rig.cmd["joint_1/max_effort"].value, rig.cmd["joint_1/max_velocity"].value) == (10.0, 0.1)

        def fill(goal):
            goal.command.position, goal.command.effort, goal.command.velocity = [0.04], [2.5], [0.05]

        out = rig.goal(PARALLEL, fill)
        assert out.status == 4 and out.result.reached_goal and list(out.result.state.position) == \
            pytest.approx([0.04], abs=0.01)
        assert (rig.cmd["joint_1/max_effort"].value, rig.cmd["joint_1/max_velocity"].value) == (2.5, 0.05)

        def squeeze(goal):
            goal.command.position = [0.0]

        out = rig.goal(PARALLEL, squeeze, moving=False)  # stalled, allowed: a success that says so
        assert out.status == 4 and out.result.stalled and not out.result.reached_goal

        def two(goal):
            goal.command.position = [0.0, 0.1]

        assert rig.goal(PARALLEL, two) is None
        assert "wrong number of position values, expects 1, got 2" in rig.c.probe.log.text("ERROR")
    finally:
        rig.close()


def test_effort_gripper_pid_output() -> None:
    # gains.<joint>.* declared on activation; a stuck gripper reports the clamped PID effort it was pushing with
    rig = Rig(EffortGripperActionController, "effort_gripper_controller",
              {"joint": "joint_1", "stall_timeout": 0.05, "gains.joint_1.p": 10.0})
    try:
        assert rig.c.get_node().get_parameter("gains.joint_1.p").value == 10.0

        def fill(goal):
            goal.command.position, goal.command.max_effort = 0.1, 3.0

        out = rig.goal(GRIPPER, fill, moving=False)
        assert out.status == 6 and out.result.stalled and out.result.effort == pytest.approx(1.0)  # 10 · 0.1
        assert rig.cmd["joint_1/effort"].value == pytest.approx(1.0)

        def hard(goal):
            goal.command.position, goal.command.max_effort = 1.0, 3.0

        out = rig.goal(GRIPPER, hard, moving=False)
        assert out.result.effort == pytest.approx(3.0)  # clamped to max_effort
    finally:
        rig.close()
