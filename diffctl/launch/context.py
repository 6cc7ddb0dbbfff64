"""The resolve-time scope: launch configurations, environment, ROS namespace and the file being read.

Scopes are copied when a scoped group or an include starts, so what is set inside does not leak out.
"""

from __future__ import annotations

import os
import secrets
from dataclasses import dataclass, field, replace
from typing import Any

from diffctl.launch.environment import with_tool_path
from diffctl.launch.plan import Gate


@dataclass
class AnonNames:
    """`$(anon x)` gives the same unique name for `x` everywhere in one launch."""

    names: dict[str, str] = field(default_factory=dict)

    def get(self, base: str) -> str:
        if base not in self.names:
            self.names[base] = f"{base}_{os.getpid()}_{secrets.token_hex(4)}"
        return self.names[base]


@dataclass
class Scope:
    configurations: dict[str, str]
    env: dict[str, str]
    env_changes: dict[str, str | None] = field(default_factory=dict)  # None = unset, for --print
    namespace: str = "/"
    launch_file: str | None = None
    includes: tuple[str, ...] = ()
    gate: Gate | None = None
    anon: AnonNames = field(default_factory=AnonNames)
    initial_env: dict[str, str] = field(default_factory=dict)  # what ResetEnvironment goes back to
    global_params: dict[str, Any] = field(default_factory=dict)  # SetParameter: for every node after it
    remaps: list[tuple[str, str]] = field(default_factory=list)  # SetRemap: for every node after it
    param_files: list[str] = field(default_factory=list)  # SetParametersFromFile: for every node after it

    @classmethod
    def initial(cls, arguments: dict[str, str], launch_file: str | None, env: dict[str, str] | None = None) -> Scope:
        start = with_tool_path(dict(os.environ if env is None else env))
        return cls(
            configurations=dict(arguments),
            env=start,
            initial_env=dict(start),
            launch_file=launch_file,
            includes=(launch_file,) if launch_file else (),
        )

    def child(self, *, forwarding: bool = True) -> Scope:
        """A scope whose changes stay inside (scoped group, include)."""
        return replace(
            self,
            configurations=dict(self.configurations) if forwarding else {},
            env=dict(self.env),
            env_changes=dict(self.env_changes),
            global_params=dict(self.global_params) if forwarding else {},
            remaps=list(self.remaps) if forwarding else [],
            param_files=list(self.param_files) if forwarding else [],
        )

    # ---- as launch's LaunchContext, for OpaqueFunction and callable handlers ------------------------------------

    @property
    def launch_configurations(self) -> dict[str, str]:
        return self.configurations

    @property
    def environment(self) -> dict[str, str]:
        return self.env

    def perform_substitution(self, substitution: Any) -> str:
        from diffctl.launch.substitutions import perform

        return perform(substitution, self)

    def anon_name(self, base: str) -> str:
        return self.anon.get(base)

    def set_env(self, name: str, value: str | None) -> None:
        if value is None:
            self.env.pop(name, None)
        else:
            self.env[name] = value
        self.env_changes[name] = value

    def push_namespace(self, ns: str) -> None:
        self.namespace = join_namespace(self.namespace, ns)


def join_namespace(base: str, ns: str) -> str:
    """ROS namespace rules: absolute replaces, relative appends; result starts with '/' and has no trailing '/'."""
    ns = ns.strip()
    if not ns:
        return base or "/"
    full = ns if ns.startswith("/") else (base.rstrip("/") + "/" + ns)
    full = "/" + "/".join(p for p in full.split("/") if p)
    return full
