"""rclpy.signals (diffctl: diffctl.client.signals)."""

from diffctl.client.exceptions import InvalidHandle  # noqa: F401
from diffctl.client.guard_condition import GuardCondition
from diffctl.client.signals import *  # noqa: F403


class SignalHandlerGuardCondition(GuardCondition):
    """A guard condition that a SIGINT triggers (rclpy's executors wait on one); diffctl's executors wake on
    shutdown by themselves, so this one is triggered only by whoever holds it."""

    def __init__(self, context=None) -> None:
        super().__init__(callback=None, callback_group=None, context=context)
