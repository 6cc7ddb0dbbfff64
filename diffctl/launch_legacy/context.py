"""The launch context, as ros2/launch's LaunchContext: one live state that the engine's visits change.

Launch configurations are one dict (Push/PopLaunchConfigurations save and restore a shallow copy, so lists
kept in it, `global_params` and `ros_remaps`, leak out of a scoped group as they do in Jazzy); the environment
is one dict (the launch environment: what children and `$(env)` see) with its own push/pop; locals are a stack
of frames, a frame per event handled, so what an include sets (the current launch file) is seen by the
entities after it in the same visit. The ROS namespace, SetParameter's parameters and SetRemap's remappings are
launch configurations named as launch_ros names them.
"""

from __future__ import annotations

import os
import secrets
from collections import deque
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from diffctl.errors import LaunchError
from diffctl.launch_legacy.environment import with_tool_path

if TYPE_CHECKING:
    from diffctl.launch_legacy.engine import Engine

ROS_NAMESPACE = "ros_namespace"
GLOBAL_PARAMS = "global_params"  # [(name, value) | parameter file path, …], as launch_ros keeps them
ROS_REMAPS = "ros_remaps"  # [(from, to), …]


@dataclass
class AnonNames:
    """`$(anon x)` gives the same unique name for `x` everywhere in one launch."""

    names: dict[str, str] = field(default_factory=dict)

    def get(self, base: str) -> str:
        if base not in self.names:
            self.names[base] = f"{base}_{os.getpid()}_{secrets.token_hex(4)}"
        return self.names[base]


class Locals:
    """`context.locals.x`: read-only view of the current locals, with ROS's error for a missing name."""

    def __init__(self, values: dict[str, Any]) -> None:
        object.__setattr__(self, "_values", values)

    def __getattr__(self, name: str) -> Any:
        values = object.__getattribute__(self, "_values")
        if name in values:
            return values[name]
        raise AttributeError(
            f"context.locals does not contain attribute '{name}', it contains: [{', '.join(sorted(values))}]"
        )

    def __setattr__(self, name: str, value: Any) -> None:
        raise AttributeError("context.locals is read-only: use context.extend_locals()")


class LaunchContext:
    def __init__(
        self,
        arguments: dict[str, str] | None = None,
        launch_file: str | None = None,
        env: dict[str, str] | None = None,
        engine: Engine | None = None,
    ) -> None:
        self.configurations: dict[str, Any] = dict(arguments or {})
        self._config_stack: list[dict[str, Any]] = []
        if env is os.environ:
            # The live launch: the environment IS the launcher's, as in ros2/launch (an OpaqueFunction's
            # os.environ sees what set_env did).
            os.environ.update(with_tool_path(dict(os.environ)))
            self.env: dict[str, str] = os.environ  # type: ignore[assignment]
        else:
            self.env = with_tool_path(dict(os.environ if env is None else env))
        self.initial_env: dict[str, str] = dict(self.env)  # what ResetEnvironment goes back to
        self._env_stack: list[dict[str, str]] = []
        self._globals: dict[str, Any] = {}
        self._frames: list[dict[str, Any]] = [{}]
        self.handlers: deque[Any] = deque()  # newest first, as LaunchContext.register_event_handler
        self.is_shutdown = False
        self.anon = AnonNames()
        self.engine = engine
        self.argv: list[str] = [f"{k}:={v}" for k, v in (arguments or {}).items()]
        if launch_file:
            self.extend_locals({"current_launch_file_path": launch_file, "include_chain": (launch_file,)})

    @classmethod
    def initial(
        cls, arguments: dict[str, str], launch_file: str | None, env: dict[str, str] | None = None
    ) -> LaunchContext:
        return cls(arguments, launch_file, env)

    # ---- launch configurations ---------------------------------------------------------------------------------

    @property
    def launch_configurations(self) -> dict[str, Any]:
        return self.configurations

    def push_configurations(self) -> None:
        self._config_stack.append(dict(self.configurations))

    def pop_configurations(self) -> None:
        if not self._config_stack:
            raise LaunchError("PopLaunchConfigurations without a matching PushLaunchConfigurations")
        self.configurations.clear()
        self.configurations.update(self._config_stack.pop())

    # ---- environment -------------------------------------------------------------------------------------------

    @property
    def environment(self) -> dict[str, str]:
        return self.env

    def push_environment(self) -> None:
        self._env_stack.append(dict(self.env))

    def pop_environment(self) -> None:
        if not self._env_stack:
            raise LaunchError("PopEnvironment without a matching PushEnvironment")
        self.env.clear()
        self.env.update(self._env_stack.pop())

    def reset_environment(self) -> None:
        self.env.clear()
        self.env.update(self.initial_env)

    def set_env(self, name: str, value: str | None) -> None:
        if value is None:
            self.env.pop(name, None)
        else:
            self.env[name] = value

    @property
    def env_changes(self) -> dict[str, str | None]:
        """How the launch environment differs from the one the launch started in (None: unset)."""
        out: dict[str, str | None] = {k: v for k, v in self.env.items() if self.initial_env.get(k) != v}
        out.update({k: None for k in self.initial_env if k not in self.env})
        return out

    # ---- locals ------------------------------------------------------------------------------------------------

    def extend_locals(self, values: dict[str, Any]) -> None:
        self._frames[-1].update(values)

    def extend_globals(self, values: dict[str, Any]) -> None:
        self._globals.update(values)

    def get_locals_as_dict(self) -> dict[str, Any]:
        return {**self._globals, **self._frames[-1]}

    @property
    def locals(self) -> Locals:
        return Locals(self.get_locals_as_dict())

    @contextmanager
    def frame(self, values: dict[str, Any]) -> Iterator[None]:
        """A fresh locals frame (globals + `values`) for one handler call, popped afterwards."""
        self._frames.append(dict(values))
        try:
            yield
        finally:
            self._frames.pop()

    @property
    def launch_file(self) -> str | None:
        return self.get_locals_as_dict().get("current_launch_file_path")

    @property
    def includes(self) -> tuple[str, ...]:
        return self.get_locals_as_dict().get("include_chain", ())

    # ---- event handlers ----------------------------------------------------------------------------------------

    def register_event_handler(self, handler: Any, append: bool = False) -> None:
        if self.engine is not None:
            self.engine.register(handler, append=append)
        elif append:
            self.handlers.append(handler)
        else:
            self.handlers.appendleft(handler)

    def unregister_event_handler(self, handler: Any) -> None:
        self.handlers.remove(handler)  # ValueError for an unknown one, as in ROS

    def emit_event_sync(self, event: Any) -> None:
        if self.engine is None:
            raise LaunchError("no launch is running to emit events to")
        self.engine.emit(event)

    emit_event = emit_event_sync

    # ---- ROS (launch_ros keeps these in launch configurations) --------------------------------------------------

    @property
    def namespace(self) -> str:
        return self.configurations.get(ROS_NAMESPACE) or "/"

    def push_namespace(self, ns: str) -> None:
        self.configurations[ROS_NAMESPACE] = join_namespace(self.namespace, ns)

    @property
    def global_params(self) -> list[Any]:
        return self.configurations.setdefault(GLOBAL_PARAMS, [])

    @property
    def remaps(self) -> list[tuple[str, str]]:
        return self.configurations.setdefault(ROS_REMAPS, [])

    # ---- substitutions -----------------------------------------------------------------------------------------

    def perform_substitution(self, substitution: Any) -> str:
        from diffctl.launch_legacy.substitutions import perform

        return perform(substitution, self)

    def anon_name(self, base: str) -> str:
        return self.anon.get(base)

    def snapshot(self) -> LaunchContext:
        """A copy to preview what an event handler or timer would do (`--print`), without touching this one."""
        import copy

        other = copy.copy(self)
        other.configurations = copy.deepcopy(self.configurations)
        other._config_stack = []
        other.env = dict(self.env)
        other._env_stack = []
        other._frames = [dict(self.get_locals_as_dict())]
        other.handlers = deque(self.handlers)
        return other


Scope = LaunchContext  # the name the engine's actions and substitutions type their context with


def join_namespace(base: str, ns: str) -> str:
    """ROS namespace rules: absolute replaces, relative appends; result starts with '/' and has no trailing '/'."""
    ns = ns.strip()
    if not ns:
        return base or "/"
    full = ns if ns.startswith("/") else (base.rstrip("/") + "/" + ns)
    full = "/" + "/".join(p for p in full.split("/") if p)
    return full
