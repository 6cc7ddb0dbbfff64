"""Events a launch file can emit with EmitEvent (as `launch.events`)."""

from __future__ import annotations

from diffctl.launch.substitutions import SomeSubstitutions, normalize


class Shutdown:
    """Ask the launch to shut down, as `launch.events.Shutdown(reason=…)`."""

    def __init__(self, *, reason: SomeSubstitutions = "shutdown event emitted by the launch file") -> None:
        self.reason = normalize(reason)
