"""launch_ros's composition for Python components: ComposableNode, ComposableNodeContainer, LoadComposableNodes.

A container is one process (`diffctl component-container`, what `rclcpp_components/component_container`
runs as here) hosting the nodes it is given when it starts, each built from its Python class with the node's
name, namespace, parameters and remappings as `cli_args`. A plugin is a Python class: `module:Class`, or a
name an `rclpy_components` entry point gives (`my_pkg::Talker`). C++ components cannot be loaded: that is
one clear error naming the plugin, when the launch reaches it. LoadComposableNodes adds nodes to a container
the same visit starts; loading into a container already running is an error (there is no load service).
"""

from __future__ import annotations

import json
from collections.abc import Iterable, Mapping
from typing import TYPE_CHECKING, Any

from diffctl.errors import LaunchError
from diffctl.launch_legacy.actions import Action
from diffctl.launch_legacy.conditions import IfCondition, UnlessCondition
from diffctl.launch_legacy.parameters import CommandLineParameter, resolve_parameters
from diffctl.launch_legacy.process_actions import Node
from diffctl.launch_legacy.registry import register
from diffctl.launch_legacy.substitutions import SomeSubstitutions, normalize, perform

if TYPE_CHECKING:
    from diffctl.launch_legacy.context import Scope
    from diffctl.launch_legacy.yaml_frontend import Entity

ENTRY_POINT_GROUP = "rclpy_components"
CONTAINER_EXECUTABLES = ("component_container", "component_container_mt", "component_container_isolated")


class ComposableNode:
    """launch_ros.descriptions.ComposableNode: what a container loads."""

    def __init__(
        self,
        *,
        package: SomeSubstitutions,
        plugin: SomeSubstitutions,
        name: SomeSubstitutions | None = None,
        namespace: SomeSubstitutions | None = None,
        parameters: Iterable[Any] | None = None,
        remappings: Iterable[tuple[SomeSubstitutions, SomeSubstitutions]] | None = None,
        extra_arguments: Iterable[Any] | None = None,
        condition: Any = None,
    ) -> None:
        self.package, self.plugin = normalize(package), normalize(plugin)
        self.name = None if name is None else normalize(name)
        self.namespace = None if namespace is None else normalize(namespace)
        self.parameters = list(parameters or [])
        self.remappings = [(normalize(a), normalize(b)) for a, b in (remappings or [])]
        self.extra_arguments = list(extra_arguments or [])
        self.condition = condition

    def request(self, context: Scope, container_ns: str) -> dict[str, Any]:
        """The load request: plugin and the node's `--ros-args`, global params and remaps first (launch_ros)."""
        plugin = perform(self.plugin, context)
        check_plugin(plugin)
        args: list[str] = []
        name = perform(self.name, context) if self.name is not None else None
        if name:
            args += ["-r", f"__node:={name}"]
        ns = perform(self.namespace, context) if self.namespace is not None else None
        from diffctl.launch_legacy.context import join_namespace

        full_ns = join_namespace(context.namespace if context.namespace != "/" else container_ns, ns or "")
        if full_ns != "/":
            args += ["-r", f"__ns:={full_ns}"]
        for entry in context.configurations.get("global_params") or ():
            args += ["-p", f"{entry[0]}:={entry[1]}"] if isinstance(entry, tuple) else ["--params-file", entry]
        for entry in resolve_parameters(self.parameters, context):
            if isinstance(entry, str):
                args += ["--params-file", entry]
            elif isinstance(entry, CommandLineParameter):
                args += ["-p", f"{entry.name}:={entry.text}"]
            else:
                for key, value in _flat(entry).items():
                    args += ["-p", f"{key}:={json.dumps(value) if not isinstance(value, str) else value}"]
        for src, dst in (*(context.configurations.get("ros_remaps") or ()), *self.remappings):
            args += ["-r", f"{perform(src, context)}:={perform(dst, context)}"]
        return {"package": perform(self.package, context), "plugin": plugin, "cli_args": ["--ros-args", *args]}


def _flat(values: Mapping[str, Any], prefix: str = "") -> dict[str, Any]:
    out: dict[str, Any] = {}
    for key, value in values.items():
        if isinstance(value, Mapping):
            out.update(_flat(value, f"{prefix}{key}."))
        else:
            out[f"{prefix}{key}"] = value
    return out


def check_plugin(plugin: str) -> None:
    """A Python component, or one clear error (a C++ one, `pkg::Class` with no rclpy_components entry point)."""
    from importlib.metadata import entry_points

    if any(ep.name == plugin for ep in entry_points(group=ENTRY_POINT_GROUP)):
        return
    if ":" in plugin and "::" not in plugin:
        return  # module:Class, imported by the container
    raise LaunchError(
        f"component {plugin!r} is not a Python component: diffctl's containers load Python classes only "
        "(C++ components of rclcpp_components cannot be loaded)",
        hint=f"name a Python class as 'module:Class', or register it as an {ENTRY_POINT_GROUP!r} entry point",
    )


@register
class ComposableNodeContainer(Node):
    """A container process and the composable nodes it starts with (`node_container`)."""

    frontend_tags = ("node_container",)
    frontend_attrs = (*Node.frontend_attrs, "composable_node")

    def __init__(
        self,
        *,
        name: SomeSubstitutions,
        namespace: SomeSubstitutions,
        package: SomeSubstitutions = "rclcpp_components",
        executable: SomeSubstitutions = "component_container",
        composable_node_descriptions: Iterable[ComposableNode] | None = None,
        **kw: Any,
    ) -> None:
        super().__init__(package=package, executable=executable, name=name, namespace=namespace, **kw)
        self.descriptions = list(composable_node_descriptions or [])
        self.requests: list[dict[str, Any]] = []

    @classmethod
    def from_entity(cls, e: Entity) -> Action:
        """As launch_ros's parse: a node's attributes, and `composable_node` children (pkg, plugin, name,
        namespace, if/unless, param, remap, extra_arg)."""
        container = super().from_entity(e)
        assert isinstance(container, ComposableNodeContainer)
        container.descriptions = [_composable_from_entity(c) for c in e.items("composable_node", COMPOSABLE_ATTRS)]
        return container

    def command(self, scope: Scope) -> list[str]:
        argv = super().command(scope)
        ns = self.ros_node(scope)[0]
        container_ns = ns.namespace if ns is not None else "/"
        self.requests = [
            d.request(scope, container_ns)
            for d in self.descriptions
            if d.condition is None or d.condition.evaluate(scope)
        ]
        return [*argv, "--nodes", json.dumps(self.requests)]


COMPOSABLE_ATTRS = ("pkg", "plugin", "name", "namespace", "if", "unless", "param", "remap", "extra_arg")


def _composable_from_entity(e: Entity) -> ComposableNode:
    from diffctl.launch_legacy.process_actions import _entity_params

    if e.has("if") and e.has("unless"):
        raise e.error("give `if` or `unless`, not both", key="unless")
    condition = (
        IfCondition(e.text("if")) if e.has("if") else UnlessCondition(e.text("unless")) if e.has("unless") else None
    )
    return ComposableNode(
        package=e.text("pkg", required=True),
        plugin=e.text("plugin", required=True),
        name=e.text("name", required=True),
        namespace=e.text("namespace"),
        parameters=_entity_params(e),
        remappings=[
            (r.text("from", required=True), r.text("to", required=True)) for r in e.items("remap", ("from", "to"))
        ],
        extra_arguments=[
            {x.text("name", required=True): x.text("value", required=True)}
            for x in e.items("extra_arg", ("name", "value"))
        ],
        condition=condition,
    )


@register
class LoadComposableNodes(Action):
    """Add composable nodes to a container started in the same visit (`load_composable_node`)."""

    frontend_tags = ("load_composable_node",)
    frontend_attrs = ("target", "composable_node")

    def __init__(
        self, *, composable_node_descriptions: Iterable[ComposableNode], target_container: Any, **kw: Any
    ) -> None:
        super().__init__(**kw)
        self.descriptions = list(composable_node_descriptions)
        self.target = target_container

    def label(self) -> str:
        return "load_composable_node"

    def execute(self, context: Scope) -> list[Action] | None:
        engine = context.engine
        target = (
            self.target if isinstance(self.target, ComposableNodeContainer) else _container_named(context, self.target)
        )
        process = engine.origin_names.get(id(target))
        ns = context.namespace
        requests = [
            d.request(context, ns) for d in self.descriptions if d.condition is None or d.condition.evaluate(context)
        ]
        if process is None or not engine.amend_start(process, lambda argv: _with_nodes(argv, requests)):
            raise LaunchError(
                "LoadComposableNodes: the container is already running (diffctl's containers take their nodes "
                "when they start; there is no load service)",
                hint="give the nodes to the ComposableNodeContainer, or load them in the visit that starts it",
            )
        return None

    @classmethod
    def from_entity(cls, e: Entity) -> Action:
        return cls(
            target_container=e.text("target", required=True),
            composable_node_descriptions=[
                _composable_from_entity(c) for c in e.items("composable_node", COMPOSABLE_ATTRS)
            ],
        )


def _container_named(context: Scope, target: Any) -> ComposableNodeContainer:
    """A container named by text (launch_ros's `target`): one this launch has started, by its node name."""
    if isinstance(target, Action):
        raise LaunchError(f"LoadComposableNodes: target_container {target.label()!r} is not a ComposableNodeContainer")
    name = perform(target, context)
    fqn = name if name.startswith("/") else f"/{name}"
    for action in context.engine.process_actions.values():
        if isinstance(action, ComposableNodeContainer) and action._fqn == fqn:
            return action
    raise LaunchError(
        f"LoadComposableNodes: no container {fqn!r} in this launch",
        hint="diffctl's containers take their nodes when they start: load into a node_container this launch starts",
    )


def _with_nodes(argv: tuple[str, ...], requests: list[dict[str, Any]]) -> tuple[str, ...]:
    i = argv.index("--nodes")
    return (*argv[: i + 1], json.dumps([*json.loads(argv[i + 1]), *requests]), *argv[i + 2 :])
