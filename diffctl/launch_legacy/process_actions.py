"""Process actions: ExecuteProcess (`executable:`) and Node (`node:`), and their validated options.

A Node is an ExecuteProcess whose command comes from the package index and which carries ROS node data
(name, namespace, parameters, remappings) that become `--ros-args` when it starts.
"""

from __future__ import annotations

import os
import re
import shlex
import shutil
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from diffctl.errors import LaunchError
from diffctl.launch_legacy.actions import Action, Shutdown, describe, seconds
from diffctl.launch_legacy.conditions import truth
from diffctl.launch_legacy.context import ROS_NAMESPACE, join_namespace
from diffctl.launch_legacy.parameters import Parameter, ParameterFile, resolve_parameters
from diffctl.launch_legacy.plan import OUTPUTS, RosNode, StartProcess
from diffctl.launch_legacy.registry import register
from diffctl.launch_legacy.substitutions import SomeSubstitutions, Substitution, TextSubstitution, normalize, perform
from diffctl.workspace import package_index

if TYPE_CHECKING:
    from diffctl.launch_legacy.context import Scope
    from diffctl.launch_legacy.yaml_frontend import Entity

_NODE_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")

PROCESS_ATTRS = (
    "name",
    "cwd",
    "env",
    "output",
    "respawn",
    "respawn_delay",
    "respawn_max_retries",
    "on_exit",
    "required",
    "sigterm_timeout",
    "sigkill_timeout",
    "launch_prefix",
    "interactive",
    "emulate_tty",
)


@dataclass(frozen=True)
class ProcessOptions:
    """How a process is supervised; every value checked here, once, for both frontends."""

    output: str = "screen"
    respawn: bool = False
    respawn_delay_s: float = 0.0
    respawn_max_retries: int = -1
    sigterm_timeout_s: float = 5.0
    sigkill_timeout_s: float = 5.0
    required: bool = False
    interactive: bool = False

    @classmethod
    def build(cls, raw: Mapping[str, Any]) -> ProcessOptions:
        """From attribute values already substituted (str) or given as Python literals; None = default."""
        out: dict[str, Any] = {}
        output = os.environ.get("OVERRIDE_LAUNCH_PROCESS_OUTPUT") or raw.get("output")
        if output is not None:
            output = {"own_log": "log"}.get(str(output), str(output))
            if output not in OUTPUTS:
                raise LaunchError(f"output {output!r} is not valid", hint="valid: " + ", ".join(OUTPUTS))
            out["output"] = output
        for key in ("respawn", "required", "interactive"):
            if raw.get(key) is not None:
                out[key] = _flag(raw[key], key)
        if raw.get("respawn_delay") is not None:
            out["respawn_delay_s"] = seconds(str(raw["respawn_delay"]), "respawn_delay")
        for key in ("sigterm_timeout", "sigkill_timeout"):
            if raw.get(key) is not None:
                out[f"{key}_s"] = seconds(str(raw[key]), key, allow_zero=False)
        if raw.get("respawn_max_retries") is not None:
            text = str(raw["respawn_max_retries"])
            try:
                retries = int(text)
            except ValueError:
                raise LaunchError(f"respawn_max_retries {text!r} is not an integer") from None
            if retries < -1:
                raise LaunchError(f"respawn_max_retries {text!r} must be ≥ 0, or -1 for no limit")
            out["respawn_max_retries"] = retries
        return cls(**out)


def _flag(value: Any, what: str) -> bool:
    return value if isinstance(value, bool) else truth(str(value), what)


class SplitArgs:
    """An `args`/`cmd` text split into arguments as launch splits it.

    The written text is split like a shell would; what a substitution gives is never split (a
    `$(find-pkg-share pkg)` under a folder with spaces stays one argument), but joins the text it touches.
    Quotes that span a substitution (`'$(var a) b'`) cannot be split that way: then the whole text is
    substituted first and split after.
    """

    def __init__(self, text: SomeSubstitutions) -> None:
        self.text = normalize(text)

    def split(self, scope: Scope) -> list[str]:
        try:
            return self._split_parts(scope)
        except ValueError:
            value = perform(self.text, scope)
            try:
                return shlex.split(value)
            except ValueError as e:
                raise LaunchError(f"cannot split {value!r} into arguments: {e}") from None

    def _split_parts(self, scope: Scope) -> list[str]:
        args: list[str] = []
        current: str | None = None  # the argument being built; None between arguments

        def end() -> None:
            nonlocal current
            if current:  # a substitution that gave nothing adds no empty argument
                args.append(current)
            current = None

        for part in self.text:
            if not isinstance(part, TextSubstitution):
                current = (current or "") + part.perform(scope)
                continue
            text = part.text
            tokens = shlex.split(text)  # ValueError: a quote spans a substitution
            if text and (text[0].isspace() or not tokens):
                end()
            if not tokens:
                continue
            current = (current or "") + tokens[0]
            for token in tokens[1:]:
                end()
                current = token
            if text[-1].isspace():
                end()
        end()
        return args


def _arguments(items: Iterable[Any], scope: Scope) -> list[str]:
    out: list[str] = []
    for item in items:
        if isinstance(item, SplitArgs):
            out += item.split(scope)
        else:
            out.append(perform(item, scope))
    return out


def _option(value: Any, scope: Scope) -> Any:
    if value is None or isinstance(value, (bool, int, float)):
        return value
    return perform(value, scope)


@register
class ExecuteProcess(Action):
    frontend_tags = ("executable",)
    frontend_attrs = ("cmd", "args", "shell", *PROCESS_ATTRS)

    def __init__(
        self,
        *,
        cmd: Iterable[SomeSubstitutions] | SplitArgs,
        name: SomeSubstitutions | None = None,
        cwd: SomeSubstitutions | None = None,
        env: Mapping[str, SomeSubstitutions] | None = None,
        additional_env: Mapping[str, SomeSubstitutions] | None = None,
        shell: bool = False,
        output: SomeSubstitutions | None = None,
        respawn: bool | SomeSubstitutions = False,
        respawn_delay: float | SomeSubstitutions | None = None,
        respawn_max_retries: int | SomeSubstitutions = -1,
        sigterm_timeout: float | SomeSubstitutions = 5.0,
        sigkill_timeout: float | SomeSubstitutions = 5.0,
        on_exit: Any = None,
        prefix: SomeSubstitutions | None = None,
        required: bool | SomeSubstitutions = False,
        interactive: bool = False,
        emulate_tty: bool | None = None,  # accepted for compatibility: children are line-buffered anyway
        cached_output: bool = False,
        **kw: Any,
    ) -> None:
        super().__init__(**kw)
        self.cached_output = cached_output
        # get_stdout()/get_stderr()/return_code, as launch's: filled from the process's events by whoever
        # watches them for a test (diffctl/testing registers the handlers), not by the engine itself.
        self.output_cache: dict[str, list[str]] = {"stdout": [], "stderr": []}
        self.return_code: int | None = None
        self.cmd = [cmd] if isinstance(cmd, SplitArgs) else list(cmd)
        self.name_subs = None if name is None else normalize(name)
        self.cwd = None if cwd is None else normalize(cwd)
        self.env = None if env is None else {k: normalize(v) for k, v in env.items()}
        self.additional_env = {k: normalize(v) for k, v in (additional_env or {}).items()}
        self.shell = shell
        self.prefix = None if prefix is None else normalize(prefix)
        self.options = {
            "output": output,
            "respawn": respawn,
            "respawn_delay": respawn_delay,
            "respawn_max_retries": respawn_max_retries,
            "sigterm_timeout": sigterm_timeout,
            "sigkill_timeout": sigkill_timeout,
            "required": required,
            "interactive": interactive,
        }
        if on_exit == "shutdown" or (isinstance(on_exit, Shutdown) and on_exit.reason is None):
            # The `required` idiom: keep it a flag so YAML `on_exit: shutdown` and Python print the same.
            self.options["required"] = True
            on_exit = None
        self.on_exit_callable = on_exit if callable(on_exit) and not isinstance(on_exit, Action) else None
        if self.on_exit_callable is not None:
            on_exit = None
        self.on_exit = [on_exit] if isinstance(on_exit, Action) else list(on_exit or [])

    def get_stdout(self) -> str:
        return self._cached("stdout")

    def get_stderr(self) -> str:
        return self._cached("stderr")

    def _cached(self, stream: str) -> str:
        if not self.cached_output:
            raise RuntimeError(f"cached output must be true to be able to get {stream}, proc '{self.label()}'")
        return "".join(self.output_cache[stream])

    def label(self) -> str:
        words = [describe(c.text if isinstance(c, SplitArgs) else c) for c in self.cmd]
        return f"executable {describe(self.name_subs) or ' '.join(words)}"

    def command(self, scope: Scope) -> list[str]:
        argv = _arguments(self.cmd, scope)
        if not argv or not argv[0]:
            raise LaunchError("the command is empty")
        return argv

    def default_name(self, argv: list[str], scope: Scope) -> str:
        return os.path.basename(argv[0])

    def ros_node(self, scope: Scope) -> tuple[RosNode | None, dict[str, str | None]]:
        return None, {}

    completes_later = True  # ExecutionComplete when the process has exited for good

    @property
    def name(self) -> str | None:
        """The process's name once executed (as launch's ExecuteLocal.name), else its name as written."""
        process = getattr(self, "_process_name", None)
        return process if process is not None else (describe(self.name_subs) or None)

    def execute(self, context: Scope) -> list[Action] | None:
        if context.is_shutdown:
            return None  # as ExecuteProcess: nothing starts once the launch is shutting down
        scope = context
        engine = context.engine
        argv = self.command(scope)
        name = perform(self.name_subs, scope) if self.name_subs is not None else self.default_name(argv, scope)
        if self.prefix is not None:
            argv = shlex.split(perform(self.prefix, scope)) + argv
        elif scope.configurations.get("launch-prefix"):
            # As launch's Executable.prepare: the `launch-prefix` configuration for every process without its
            # own prefix, limited by the `launch-prefix-filter` regex on the executable's name when set.
            pattern = scope.configurations.get("launch-prefix-filter")
            if not pattern or re.match(str(pattern), os.path.basename(argv[0])):
                argv = shlex.split(str(scope.configurations["launch-prefix"])) + argv
        raw = {k: _option(v, scope) for k, v in self.options.items()}
        if raw.get("output") is None:
            raw["output"] = engine.output_default
        options = ProcessOptions.build(raw)
        env: dict[str, str | None] = {} if self.env is not None else dict(scope.env_changes)
        if self.env is not None:
            env.update({k: perform(v, scope) for k, v in self.env.items()})
        env.update({k: perform(v, scope) for k, v in self.additional_env.items()})
        cwd = perform(self.cwd, scope) if self.cwd is not None else None
        if cwd is not None and not Path(cwd).is_dir():
            raise LaunchError(f"working directory {cwd!r} does not exist")
        if self.shell:
            argv = ["/bin/sh", "-c", " ".join(argv)]
        else:
            _check_executable(argv[0], env.get("PATH") or scope.env.get("PATH", ""), cwd)
        node, _ = self.ros_node(scope)
        spec = engine.add_process(
            self,
            name,
            argv=tuple(argv),
            shell=self.shell,
            cwd=cwd,
            env=env,
            env_replace=self.env is not None,
            output=options.output,
            respawn=options.respawn,
            respawn_delay_s=options.respawn_delay_s,
            respawn_max_retries=options.respawn_max_retries,
            required=options.required,
            sigterm_timeout_s=options.sigterm_timeout_s,
            sigkill_timeout_s=options.sigkill_timeout_s,
            interactive=options.interactive,
            node=node,
            **self.index_names(scope),
        )
        if self.on_exit_callable is not None or self.on_exit:
            from diffctl.launch_legacy.event_handlers import OnProcessExit

            handler = OnProcessExit(target_action=self, on_exit=self.on_exit_callable or self.on_exit)
            context.register_event_handler(handler)
        engine.effect(StartProcess(spec=spec))
        return None

    def index_names(self, scope: Scope) -> dict[str, str]:
        return {}

    @classmethod
    def entity_process_options(cls, e: Entity) -> dict[str, Any]:
        on_exit: Any = None
        if e.has("on_exit"):
            raw = e.raw("on_exit")
            if raw == "shutdown":
                on_exit = "shutdown"
            elif isinstance(raw, list):
                on_exit = e.children("on_exit")
            else:
                raise e.error(
                    f"on_exit {raw!r} is not valid", key="on_exit", hint="valid: shutdown, or a list of actions"
                )
        env = {}
        for item in e.items("env", ("name", "value")):
            env[item.plain("name", required=True)] = item.text("value", required=True)
        return {
            "name": e.text("name"),
            "cwd": e.text("cwd"),
            "additional_env": env,
            "output": e.text("output"),
            "respawn": e.text("respawn"),
            "respawn_delay": e.text("respawn_delay"),
            "respawn_max_retries": e.text("respawn_max_retries"),
            "sigterm_timeout": e.text("sigterm_timeout"),
            "sigkill_timeout": e.text("sigkill_timeout"),
            "required": e.text("required"),
            "interactive": e.boolean("interactive", False),
            "prefix": e.text("launch_prefix"),
            "on_exit": on_exit,
        }

    @classmethod
    def from_entity(cls, e: Entity) -> Action:
        if not e.has("cmd"):
            raise e.error("`executable` needs `cmd`")
        cmd = entity_words(e, "cmd") + entity_words(e, "args")
        kw = {k: v for k, v in cls.entity_process_options(e).items() if v is not None}
        return cls(cmd=cmd, shell=e.boolean("shell", False), **kw)


def entity_words(e: Entity, key: str) -> list[Any]:
    """`args: "a b 'c d'"` is split like a shell would; `args: [a, b, c d]` is taken item by item."""
    raw = e.raw(key)
    if raw is None:
        return []
    if isinstance(raw, list):
        if any(isinstance(item, (list, dict)) for item in raw):
            raise e.error(f"`{key}` items must be text", key=key)
        return [e.parse(str(item).lower() if isinstance(item, bool) else str(item), key) for item in raw]
    return [SplitArgs(e.text(key))]


def _check_executable(program: str, path: str, cwd: str | None) -> None:
    if "/" in program:
        full = Path(cwd or ".") / program
        if not (full.is_file() and os.access(full, os.X_OK)):
            raise LaunchError(f"executable {program!r} does not exist or is not executable")
    elif shutil.which(program, path=path) is None:
        raise LaunchError(f"executable {program!r} not found on PATH")


@register
class Node(ExecuteProcess):
    """A ROS node from the package index: `Node(package="controller_manager", executable="spawner", …)`."""

    frontend_tags = ("node",)
    frontend_attrs = (
        "pkg",
        "exec",
        "namespace",
        "ns",
        "args",
        "ros_args",
        "param",
        "remap",
        "exec_name",
        *PROCESS_ATTRS,
    )

    def __init__(
        self,
        *,
        executable: SomeSubstitutions,
        package: SomeSubstitutions | None = None,
        name: SomeSubstitutions | None = None,
        namespace: SomeSubstitutions | None = None,
        exec_name: SomeSubstitutions | None = None,
        parameters: Iterable[Any] | None = None,
        remappings: Iterable[tuple[SomeSubstitutions, SomeSubstitutions]] | None = None,
        ros_arguments: Iterable[Any] | None = None,
        arguments: Iterable[Any] | None = None,
        **kw: Any,
    ) -> None:
        super().__init__(cmd=[], **kw)
        # Without a package the executable is looked up on PATH, as launch_ros does.
        self.package = None if package is None else normalize(package)
        self.executable = normalize(executable)
        self.name_parts = None if name is None else normalize(name)
        self._fqn: str | None = None
        self.name_subs = None if exec_name is None else normalize(exec_name)
        self.namespace = None if namespace is None else normalize(namespace)
        self.parameters = list(parameters or [])
        for p in self.parameters:
            if not isinstance(p, (Mapping, str, Path, Substitution, list, tuple, ParameterFile, Parameter)):
                raise LaunchError(f"parameters entry {p!r} must be a dict or a parameter file path")
        self.remappings = [(normalize(a), normalize(b)) for a, b in (remappings or [])]
        self.ros_arguments = list(ros_arguments or [])
        self.arguments = list(arguments or [])

    def label(self) -> str:
        return f"node {describe(self.package) + '/' if self.package else ''}{describe(self.executable)}"

    @property
    def node_name(self) -> str:
        """The fully qualified node name, once the node has been executed (as launch_ros's Node.node_name)."""
        if self._fqn is None:
            raise LaunchError("Node.node_name is known once the node has been executed (and was given a name)")
        return self._fqn

    def command(self, scope: Scope) -> list[str]:
        if self.package is None:
            argv = [perform(self.executable, scope)]
        else:
            argv = package_index.executable_argv(perform(self.package, scope), perform(self.executable, scope))
        argv += _arguments(self.arguments, scope)
        if self.ros_arguments:
            argv += ["--ros-args", *_arguments(self.ros_arguments, scope)]  # launch_ros adds no `--` after them
        return argv

    def index_names(self, scope: Scope) -> dict[str, str]:
        if self.package is None:
            return {}
        return {"package": perform(self.package, scope), "executable": perform(self.executable, scope)}

    def default_name(self, argv: list[str], scope: Scope) -> str:
        if scope.engine is not None and scope.engine.process_names == "ros":
            return os.path.basename(perform(self.executable, scope))  # launch_ros labels by executable
        return perform(self.name_parts if self.name_parts is not None else self.executable, scope)

    def ros_node(self, scope: Scope) -> tuple[RosNode | None, dict[str, str | None]]:
        namespace = scope.namespace
        if self.namespace is not None:
            namespace = join_namespace(scope.namespace, perform(self.namespace, scope))
        node_name = perform(self.name_parts, scope) if self.name_parts is not None else None
        if node_name is not None and not _NODE_NAME.fullmatch(node_name):
            raise LaunchError(
                f"node name {node_name!r} is not valid",
                hint="letters, digits and underscores, not starting with a digit",
            )
        # SetParameter / SetParametersFromFile / SetRemap of the scope come first, so the node's own win
        # (launch_ros's order); SetParameter's reach the node as `-p name:=value`.
        params = resolve_parameters(self.parameters, scope)
        own = tuple((perform(a, scope), perform(b, scope)) for a, b in self.remappings)
        glob = tuple(scope.configurations.get("global_params") or ())
        remaps = tuple(scope.configurations.get("ros_remaps") or ())
        if node_name is not None:
            self._fqn = namespace.rstrip("/") + "/" + node_name
        given = self.namespace is not None or scope.configurations.get(ROS_NAMESPACE) is not None
        node = RosNode(
            node_name=node_name,
            namespace=namespace,
            params=params,
            remaps=(*remaps, *own),
            global_params=glob,
            namespace_given=given,
        )
        return node, {}

    @classmethod
    def from_entity(cls, e: Entity) -> Action:
        kw = {k: v for k, v in cls.entity_process_options(e).items() if v is not None}
        kw["exec_name"] = e.text("exec_name")
        kw["name"] = e.text("name")
        if e.has("namespace") and e.has("ns"):
            raise e.error("give `namespace` or `ns`, not both", key="ns")
        return cls(
            package=e.text("pkg"),
            executable=e.text("exec", required=True),
            namespace=e.text("namespace") if e.has("namespace") else e.text("ns"),
            arguments=entity_words(e, "args"),
            ros_arguments=entity_words(e, "ros_args"),
            parameters=_entity_params(e),
            remappings=[
                (r.text("from", required=True), r.text("to", required=True)) for r in e.items("remap", ("from", "to"))
            ],
            **kw,
        )


def _entity_params(e: Entity, key: str = "param") -> list[Any]:
    """`param:` items: {name, value}, {from: FILE}, or {name, param: [...]} for a nested namespace."""
    out: list[Any] = []
    for item in e.items(key, ("name", "value", "from", "param")):
        if item.has("from"):
            if item.has("name") or item.has("value"):
                raise item.error("a `from:` parameter entry takes no name or value")
            out.append(item.text("from"))
            continue
        name = item.plain("name", required=True)
        if item.has("param"):
            nested: dict[str, Any] = {}
            for sub in _entity_params(item, "param"):
                if not isinstance(sub, Mapping):
                    raise item.error("nested parameters cannot load files", key="param")
                nested.update(sub)
            out.append({name: nested})
        elif item.has("value"):
            out.append({name: item.value("value")})
        else:
            raise item.error(f"parameter {name!r} needs a value", key="value")
    return out
