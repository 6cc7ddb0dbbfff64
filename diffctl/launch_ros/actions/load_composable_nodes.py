"""LoadComposableNodes (`load_composable_node`): load composable nodes into a running container through its
`<container>/_container/load_node` service (composition_interfaces/srv/LoadNode), one after the other.

The requests are made when the action executes (so the scope's namespace, SetParameter and SetRemap apply);
the calls wait on worker threads for the service, and give up when the launch shuts down.
"""

from __future__ import annotations

import threading
from pathlib import Path
from typing import Any

import diffctl.launch.logging
from diffctl.launch.action import Action
from diffctl.launch.frontend import Entity, Parser, expose_action
from diffctl.launch.launch_context import LaunchContext
from diffctl.launch.some_substitutions_type import SomeSubstitutionsType, SomeSubstitutionsType_types_tuple
from diffctl.launch.utilities import (
    ensure_argument_type,
    is_a_subclass,
    normalize_to_list_of_substitutions,
    perform_substitutions,
)

from ..descriptions import ComposableNode
from ..parameter_descriptions import ParameterFile
from ..ros_adapters import get_ros_node
from ..utilities import (
    add_node_name,
    evaluate_parameters,
    get_node_name_count,
    make_namespace_absolute,
    prefix_namespace,
    to_parameters_list,
)
from ..utilities.normalize_parameters import normalize_parameter_dict
from .composable_node_container import ComposableNodeContainer

LOGGER_NAME = "launch_ros.actions.load_composable_nodes"


@expose_action("load_composable_node")
class LoadComposableNodes(Action):
    """Load `composable_node_descriptions` into `target_container` (a ComposableNodeContainer action, or the
    container's node name)."""

    def __init__(
        self,
        *,
        composable_node_descriptions: list[ComposableNode],
        target_container: SomeSubstitutionsType | ComposableNodeContainer,
        **kwargs: Any,
    ) -> None:
        ensure_argument_type(
            target_container,
            [*SomeSubstitutionsType_types_tuple, ComposableNodeContainer],
            "target_container",
            "LoadComposableNodes",
        )
        super().__init__(**kwargs)
        self.__composable_node_descriptions = composable_node_descriptions
        self.__target_container = target_container
        self.__final_target_container_name: str | None = None
        self.__rclpy_load_node_client: Any = None
        self.__logger = diffctl.launch.logging.get_logger(LOGGER_NAME)

    @classmethod
    def parse(cls, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
        """`target` (the container's name) and `composable_node` children."""
        _, kwargs = super().parse(entity, parser)
        kwargs["target_container"] = parser.parse_substitution(entity.get_attr("target", data_type=str))
        kwargs["composable_node_descriptions"] = []
        for child in entity.get_attr("composable_node", data_type=list[Entity]):
            description_cls, description_kwargs = ComposableNode.parse(parser, child)
            kwargs["composable_node_descriptions"].append(description_cls(**description_kwargs))
        return cls, kwargs

    def _load_node(self, request: Any, context: LaunchContext) -> None:
        """One LoadNode call, on a worker thread: wait for the service, call, log the outcome."""
        client = self.__rclpy_load_node_client
        while not client.wait_for_service(timeout_sec=1.0):
            if context.is_shutdown:
                self.__logger.warning(f"Abandoning wait for the '{client.srv_name}' service, due to shutdown.")
                return
        answered = threading.Event()
        self.__logger.debug(f"Calling the '{client.srv_name}' service with request '{request}'")
        future = client.call_async(request)
        future.add_done_callback(lambda _f: answered.set())
        while not answered.wait(1.0):
            if context.is_shutdown:
                self.__logger.warning(
                    f"Abandoning wait for the '{client.srv_name}' service response, due to shutdown."
                )
                future.cancel()
                return
        if future.exception() is not None:
            raise future.exception()
        response = future.result()
        self.__logger.debug(f"Received response '{response}'")
        node_name = response.full_node_name or request.node_name
        container = self.__final_target_container_name
        if not response.success:
            self.__logger.error(
                f"Failed to load node '{node_name}' of type '{request.plugin_name}' in container '{container}': "
                f"{response.error_message}"
            )
            return
        if node_name:
            add_node_name(context, node_name)
            count = get_node_name_count(context, node_name)
            if count > 1:
                diffctl.launch.logging.get_logger(container).warning(
                    f"there are now at least {count} nodes with the name {node_name} created within this launch context"
                )
        self.__logger.info(f"Loaded node '{response.full_node_name}' in container '{container}'")

    def _load_in_sequence(self, requests: list[Any], context: LaunchContext) -> None:
        """Load the first request, then queue the rest (each a completion future of the launch)."""
        first, rest = requests[0], requests[1:]
        self._load_node(first, context)
        if rest:
            context.add_completion_future(
                context.asyncio_loop.run_in_executor(None, self._load_in_sequence, rest, context)
            )

    def execute(self, context: LaunchContext) -> list[Action] | None:
        from composition_interfaces.srv import LoadNode

        target = self.__target_container
        if is_a_subclass(target, ComposableNodeContainer):
            self.__final_target_container_name = target.node_name
        elif isinstance(target, SomeSubstitutionsType_types_tuple):
            self.__final_target_container_name = perform_substitutions(
                context, normalize_to_list_of_substitutions(target)
            )
        else:
            self.__logger.error("target container is neither a ComposableNodeContainer nor a SubstitutionType")
            return None
        self.__rclpy_load_node_client = get_ros_node(context).create_client(
            LoadNode, f"{self.__final_target_container_name}/_container/load_node"
        )
        # now, not on the worker thread: the scope (namespace, SetParameter, SetRemap) may end before it runs
        requests = [
            r
            for r in (get_composable_node_load_request(d, context) for d in self.__composable_node_descriptions)
            if r is not None
        ]
        if requests:
            context.add_completion_future(
                context.asyncio_loop.run_in_executor(None, self._load_in_sequence, requests, context)
            )
        return None


def get_composable_node_load_request(composable_node_description: ComposableNode, context: LaunchContext) -> Any:
    """The LoadNode request for a description in this context (None when its condition does not hold):
    the scope's namespace, remappings and parameters first, then the description's own."""
    from composition_interfaces.srv import LoadNode

    description = composable_node_description
    condition = description.condition()
    if condition is not None and not condition.evaluate(context):
        return None
    request = LoadNode.Request()
    request.package_name = perform_substitutions(context, description.package)
    request.plugin_name = perform_substitutions(context, description.node_plugin)
    if description.node_name is not None:
        request.node_name = perform_substitutions(context, description.node_name)
    ns = None if description.node_namespace is None else perform_substitutions(context, description.node_namespace)
    combined_ns = make_namespace_absolute(prefix_namespace(context.launch_configurations.get("ros_namespace"), ns))
    if combined_ns is not None:
        request.node_namespace = combined_ns

    remaps = [f"{src}:={dst}" for src, dst in context.launch_configurations.get("ros_remaps") or ()]
    remaps += [
        f"{perform_substitutions(context, list(src))}:={perform_substitutions(context, list(dst))}"
        for src, dst in description.remappings or ()
    ]
    if remaps:
        request.remap_rules = remaps

    parameters: list[Any] = []
    for entry in context.launch_configurations.get("global_params") or ():
        if isinstance(entry, tuple):
            parameters.append(normalize_parameter_dict({entry[0]: entry[1]}))
        else:
            path = Path(entry).resolve()
            assert path.is_file(), path
            parameters.append(ParameterFile(path))
    parameters += list(description.parameters or ())
    if parameters:
        request.parameters = [
            p.to_parameter_msg()
            for p in to_parameters_list(
                context, request.node_name, combined_ns, evaluate_parameters(context, parameters)
            )
        ]
    if description.extra_arguments is not None:
        request.extra_arguments = [
            p.to_parameter_msg()
            for p in to_parameters_list(
                context, request.node_name, combined_ns, evaluate_parameters(context, description.extra_arguments)
            )
        ]
    return request
