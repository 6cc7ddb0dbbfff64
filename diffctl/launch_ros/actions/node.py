"""Node: a ROS node's process, its name, namespace, parameters and remappings made into `--ros-args`.

The command is `<executable> <arguments> [--ros-args <ros_arguments>] --ros-args -r __node:=… -r __ns:=…
[-p …/--params-file …] [-r from:=to …]`, in launch_ros's order: what SetParameter/SetParametersFromFile gave
the scope first, then the node's own parameters (a dictionary becomes a parameters file written for the
node), then SetRemap's rules before the node's own. The node name and namespace are LocalSubstitutions of
`ros_specific_arguments`, which extensions (entry point group `launch_ros.node_action`) may change.

A `package` is resolved through diffctl's package index when the node starts: a program of the user's
workspace or an install tree (`<prefix>/lib/<pkg>/<exe>`), or one of diffctl's own components
(`python -m diffctl …`).
"""

from __future__ import annotations

import os
import pathlib
from collections.abc import Iterable
from typing import Any

import diffctl.launch.logging
from diffctl.client.names import validate_namespace, validate_node_name
from diffctl.launch.action import Action
from diffctl.launch.actions import ExecuteProcess
from diffctl.launch.frontend import Entity, Parser, expose_action
from diffctl.launch.frontend.type_utils import get_data_type_from_identifier
from diffctl.launch.launch_context import LaunchContext
from diffctl.launch.some_substitutions_type import SomeSubstitutionsType
from diffctl.launch.substitution import Substitution
from diffctl.launch.substitutions import LocalSubstitution, TextSubstitution
from diffctl.launch.utilities import ensure_argument_type, normalize_to_list_of_substitutions, perform_substitutions

from ..descriptions import Parameter, ParameterFile, ParameterValue
from ..parameters_type import SomeParameters
from ..remap_rule_type import SomeRemapRules
from ..substitutions import ExecutableInPackage
from ..utilities import (
    add_node_name,
    evaluate_parameters,
    get_node_name_count,
    make_namespace_absolute,
    normalize_parameters,
    normalize_remap_rules,
    plugin_support,
    prefix_namespace,
)

LOGGER_NAME = "launch_ros.actions.node"
EXTENSION_GROUP = "launch_ros.node_action"


class NodeActionExtension:
    """Base of the extensions of the `launch_ros.node_action` entry point group.

    `NAME` is set to the entry point's name; `prepare_for_execute` may add command line words and change
    `ros_specific_arguments` (`name`, `ns`) before the node's process starts.
    """

    NAME: str | None = None
    EXTENSION_POINT_VERSION = "0.1"

    def __init__(self) -> None:
        super().__init__()
        plugin_support.satisfies_version(self.EXTENSION_POINT_VERSION, "^0.1")

    def prepare_for_execute(
        self, context: LaunchContext, ros_specific_arguments: dict[str, Any], node_action: Node
    ) -> tuple[list[Any], dict[str, Any]]:
        """(command line additions as TextSubstitutions, the possibly changed ros_specific_arguments)."""
        return [], ros_specific_arguments


class _Basename(Substitution):
    """The last path component of what `value` gives: a node's process is named after its executable,
    whatever command line starts it."""

    def __init__(self, value: SomeSubstitutionsType) -> None:
        super().__init__()
        self.value = normalize_to_list_of_substitutions(value)

    def describe(self) -> str:
        return f"basename({' + '.join(s.describe() for s in self.value)})"

    def perform(self, context: LaunchContext) -> str:
        return os.path.basename(perform_substitutions(context, self.value))


def _yaml_dump(value: Any, stream: Any = None, *, emitter: str = "python", **kwargs: Any) -> Any:
    """yaml.dump with lists for tuples: what any YAML reader (rcl's, the client's safe loader) takes. YAML is
    imported when a node first needs it (a launch of plain nodes never does). `emitter="libyaml"` (parameter
    files) takes libyaml's where PyYAML has it: the pure-Python one scans a long string (a robot description)
    character by character, ~10 ms per file before its node starts. `-p` rules keep the Python emitter's text
    (a scalar ends in "...", as launch_ros writes it)."""
    import yaml

    base = getattr(yaml, "CSafeDumper", yaml.SafeDumper) if emitter == "libyaml" else yaml.SafeDumper

    class Dumper(base):  # type: ignore[misc, valid-type]
        pass

    Dumper.add_representer(tuple, lambda dumper, v: dumper.represent_list(list(v)))
    return yaml.dump(value, stream, Dumper=Dumper, **kwargs)


def _cmdline_value(value: Any) -> str:
    """A SetParameter value as `-p name:=value` text: a list in YAML's flow style, anything else as str()."""
    if isinstance(value, (tuple, list)):
        return _yaml_dump(list(value), default_flow_style=True).strip()
    return str(value)


@expose_action("node")
class Node(ExecuteProcess):
    """Start a ROS node (see the module docstring for its command line)."""

    UNSPECIFIED_NODE_NAME = "<node_name_unspecified>"
    UNSPECIFIED_NODE_NAMESPACE = "<node_namespace_unspecified>"

    def __init__(
        self,
        *,
        executable: SomeSubstitutionsType,
        package: SomeSubstitutionsType | None = None,
        name: SomeSubstitutionsType | None = None,
        namespace: SomeSubstitutionsType | None = None,
        exec_name: SomeSubstitutionsType | None = None,
        parameters: SomeParameters | None = None,
        remappings: SomeRemapRules | None = None,
        ros_arguments: Iterable[SomeSubstitutionsType] | None = None,
        arguments: Iterable[SomeSubstitutionsType] | None = None,
        **kwargs: Any,
    ) -> None:
        """`executable` of `package` (or a path when no package is given), named `name` in `namespace`
        (relative to the scope's pushed namespace); `parameters`: files (paths, substitutions,
        ParameterFile), dictionaries and Parameter descriptions, applied in order; `remappings`:
        `(from, to)` pairs; `ros_arguments` go after a `--ros-args` of their own; `exec_name` names the
        process (default: the executable's name). Other keywords go to ExecuteProcess."""
        program = executable if package is None else ExecutableInPackage(package=package, executable=executable)
        cmd: list[Any] = [program]
        cmd += list(arguments) if arguments is not None else []
        if ros_arguments is not None:
            cmd += ["--ros-args", *ros_arguments]
        cmd.append("--ros-args")  # the ROS arguments launch computes follow
        if name is not None:
            cmd += ["-r", LocalSubstitution("ros_specific_arguments['name']", description="node name")]
        normalized: Any = ()
        if parameters is not None:
            ensure_argument_type(parameters, list, "parameters", "Node")
            normalized = normalize_parameters(parameters)
        kwargs["name"] = exec_name if exec_name is not None else _Basename(executable)
        super().__init__(cmd=cmd, **kwargs)
        self.__package = package
        self.__node_executable = executable
        self.__node_name = name
        self.__node_namespace = namespace
        self.__parameters = normalized
        self.__remappings = [] if remappings is None else list(normalize_remap_rules(remappings))
        self.__ros_arguments = ros_arguments
        self.__arguments = arguments
        self.__expanded_node_name = self.UNSPECIFIED_NODE_NAME
        self.__expanded_node_namespace = self.UNSPECIFIED_NODE_NAMESPACE
        self.__expanded_parameter_arguments: list[tuple[str, bool]] | None = None
        self.__final_node_name: str | None = None
        self.__expanded_remappings: list[tuple[str, str]] | None = None
        self.__substitutions_performed = False
        self.__logger = diffctl.launch.logging.get_logger(LOGGER_NAME)
        self.__extensions = get_extensions(self.__logger)

    # ---------------------------------------------------------------- frontend
    @staticmethod
    def parse_nested_parameters(params: list[Entity], parser: Parser) -> list[Any]:
        """`param` entities → the `parameters` list: `from` (a file, `allow_substs` optional), or `name` with a
        `value` (typed by `type`, split by `value-sep`) or nested `param` children (a namespace)."""

        def nested(entities: list[Entity]) -> dict[tuple[Any, ...], Any]:
            out: dict[tuple[Any, ...], Any] = {}
            for param in entities:
                name = tuple(parser.parse_substitution(param.get_attr("name")))
                type_id = param.get_attr("type", data_type=None, optional=True)
                data_type = None if type_id is None else get_data_type_from_identifier(type_id)
                value = param.get_attr("value", data_type=data_type, optional=True)
                children = param.get_attr("param", data_type=list[Entity], optional=True)
                param.assert_entity_completely_parsed()
                if value is not None and children:
                    raise RuntimeError("nested parameters and value attributes are mutually exclusive")
                if data_type is not None and children:
                    raise RuntimeError("nested parameters and type attributes are mutually exclusive")
                if value is not None:
                    out[name] = ParameterValue(parser.parse_if_substitutions(value), value_type=data_type)
                elif children:
                    out[name] = nested(children)
                else:
                    raise RuntimeError("either a value attribute or nested params are needed")
            return out

        result: list[Any] = []
        for param in params:
            from_attr = param.get_attr("from", optional=True)
            allow_substs = param.get_attr("allow_substs", data_type=bool, optional=True)
            name = param.get_attr("name", optional=True)
            if from_attr is not None and name is not None:
                raise RuntimeError("name and from attributes are mutually exclusive")
            if from_attr is not None:
                allow = parser.parse_substitution(allow_substs) if isinstance(allow_substs, str) else bool(allow_substs)
                param.assert_entity_completely_parsed()
                result.append(ParameterFile(parser.parse_substitution(from_attr), allow_substs=allow))
            elif name is not None:
                if allow_substs is not None:
                    raise RuntimeError("'allow_substs' can only be used together with 'from' attribute")
                result.append(nested([param]))
            else:
                raise ValueError("param Entity should have name or from attribute")
        return result

    @classmethod
    def parse(cls, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
        """`node`: pkg, exec, name, namespace, exec_name, args, ros_args, param, remap, and ExecuteProcess's."""
        _, kwargs = super().parse(entity, parser, ignore=["cmd"])
        args = entity.get_attr("args", optional=True)
        if args is not None:
            kwargs["arguments"] = super()._parse_cmdline(args, parser)
        ros_args = entity.get_attr("ros_args", optional=True)
        if ros_args is not None:
            kwargs["ros_arguments"] = super()._parse_cmdline(ros_args, parser)
        for attr, key in (("node-name", "node_name"), ("name", "name"), ("exec_name", "exec_name"),
                          ("pkg", "package")):
            value = entity.get_attr(attr, optional=True)
            if value is not None:
                kwargs[key] = parser.parse_substitution(value)
        kwargs["executable"] = parser.parse_substitution(entity.get_attr("exec"))
        ns = entity.get_attr("namespace", optional=True)
        if ns is not None:
            kwargs["namespace"] = parser.parse_substitution(ns)
        remaps = entity.get_attr("remap", data_type=list[Entity], optional=True)
        if remaps is not None:
            kwargs["remappings"] = [
                (parser.parse_substitution(r.get_attr("from")), parser.parse_substitution(r.get_attr("to")))
                for r in remaps
            ]
            for r in remaps:
                r.assert_entity_completely_parsed()
        params = entity.get_attr("param", data_type=list[Entity], optional=True)
        if params is not None:
            kwargs["parameters"] = cls.parse_nested_parameters(params, parser)
        return cls, kwargs

    # ---------------------------------------------------------------- properties
    @property
    def node_package(self) -> SomeSubstitutionsType | None:
        return self.__package

    @property
    def node_executable(self) -> SomeSubstitutionsType:
        return self.__node_executable

    @property
    def node_name(self) -> str:
        """The fully qualified node name (`/ns/name`, with placeholders for what was not given); known once
        the action's substitutions were performed."""
        if self.__final_node_name is None:
            raise RuntimeError("cannot access 'node_name' before executing action")
        return self.__final_node_name

    def is_node_name_fully_specified(self) -> bool:
        name = self.node_name
        return self.UNSPECIFIED_NODE_NAME not in name and self.UNSPECIFIED_NODE_NAMESPACE not in name

    @property
    def expanded_node_namespace(self) -> str:
        return self.__expanded_node_namespace

    @property
    def expanded_remapping_rules(self) -> list[tuple[str, str]] | None:
        return self.__expanded_remappings

    # ---------------------------------------------------------------- the command line
    def _extend_cmd(self, *words: SomeSubstitutionsType) -> None:
        self.cmd.extend(normalize_to_list_of_substitutions(w) for w in words)

    def _create_params_file_from_dict(self, params: dict[str, Any]) -> str:
        """A parameters file for this node (its full name, or `/**` when not fully known) holding `params`.

        It is kept (a respawned node reads it again), in the run's log directory rather than ROS's temporary
        one: it goes with the logs of the run it belongs to, not into /tmp for good."""
        section = self.node_name if self.is_node_name_fully_specified() else "/**"
        import tempfile

        try:
            folder: str | None = diffctl.launch.logging.launch_config.log_dir
        except OSError:  # no log directory can be made: the temporary folder, as ROS
            folder = None
        with tempfile.NamedTemporaryFile("w", prefix="launch_params_", dir=folder, delete=False) as f:
            _yaml_dump({section: {"ros__parameters": params}}, f, emitter="libyaml", default_flow_style=False)
        return f.name

    def _get_parameter_rule(self, param: Parameter, context: LaunchContext) -> str:
        name, value = param.evaluate(context)
        return f"{name}:={_yaml_dump(value)}"

    def _perform_substitutions(self, context: LaunchContext) -> None:
        """Name, namespace, parameters and remappings, evaluated once, added to the command line."""
        if self.__substitutions_performed:  # a subclass's execute may have done it already
            return
        self.__substitutions_performed = True
        try:
            if self.__node_name is not None:
                self.__expanded_node_name = perform_substitutions(
                    context, normalize_to_list_of_substitutions(self.__node_name)
                )
                validate_node_name(self.__expanded_node_name)
            ns = None
            if self.__node_namespace is not None:
                ns = perform_substitutions(context, normalize_to_list_of_substitutions(self.__node_namespace))
            ns = make_namespace_absolute(prefix_namespace(context.launch_configurations.get("ros_namespace"), ns))
            if ns is not None:
                self.__expanded_node_namespace = ns
                self._extend_cmd("-r", LocalSubstitution("ros_specific_arguments['ns']"))
                validate_namespace(ns)
        except Exception:
            self.__logger.error(
                f"Error while expanding or validating node name or namespace for 'package={self.__package}, "
                f"executable={self.__node_executable}, name={self.__node_name}, namespace={self.__node_namespace}':"
            )
            raise
        self.__final_node_name = prefix_namespace(self.__expanded_node_namespace, self.__expanded_node_name)

        scope_params = context.launch_configurations.get("global_params")
        if scope_params is not None or self.__parameters is not None:
            self.__expanded_parameter_arguments = []
        for entry in scope_params or ():
            if isinstance(entry, tuple):
                self._extend_cmd("-p", f"{entry[0]}:={_cmdline_value(entry[1])}")
            else:
                path = os.path.abspath(entry)
                assert os.path.isfile(path), path
                self.__expanded_parameter_arguments.append((path, True))
                self._extend_cmd("--params-file", path)
        for params in evaluate_parameters(context, self.__parameters):
            if isinstance(params, dict):
                argument, is_file = self._create_params_file_from_dict(params), True
            elif isinstance(params, pathlib.Path):
                argument, is_file = str(params), True
            elif isinstance(params, Parameter):
                argument, is_file = self._get_parameter_rule(params, context), False
            else:
                raise RuntimeError(f"invalid normalized parameters {params!r}")
            if is_file and not os.path.isfile(argument):
                self.__logger.warning(f"Parameter file path is not a file: {argument}")
                continue
            self.__expanded_parameter_arguments.append((argument, is_file))
            self._extend_cmd("--params-file" if is_file else "-p", argument)

        scope_remaps = context.launch_configurations.get("ros_remaps")
        if scope_remaps or self.__remappings:
            self.__expanded_remappings = list(scope_remaps or ())
            self.__expanded_remappings += [
                (perform_substitutions(context, list(src)), perform_substitutions(context, list(dst)))
                for src, dst in self.__remappings
            ]
            for src, dst in self.__expanded_remappings:
                self._extend_cmd("-r", f"{src}:={dst}")

    def _resolve_executable(self, context: LaunchContext) -> None:
        """The package's executable → its command line words, in place of the ExecutableInPackage."""
        first = self.cmd[0] if self.cmd else None
        if first and len(first) == 1 and isinstance(first[0], ExecutableInPackage):
            self.cmd[0:1] = [[TextSubstitution(text=word)] for word in first[0].argv(context)]

    def execute(self, context: LaunchContext) -> list[Action] | None:
        self._perform_substitutions(context)
        ros_specific_arguments: dict[str, Any] = {}
        if self.__node_name is not None:
            ros_specific_arguments["name"] = f"__node:={self.__expanded_node_name}"
        if self.__expanded_node_namespace != "":
            ros_specific_arguments["ns"] = f"__ns:={self.__expanded_node_namespace}"
        for extension in self.__extensions.values():
            words, ros_specific_arguments = extension.prepare_for_execute(context, ros_specific_arguments, self)
            self.cmd.extend(words)
        context.extend_locals({"ros_specific_arguments": ros_specific_arguments})
        self._resolve_executable(context)
        result = super().execute(context)
        if self.is_node_name_fully_specified():
            add_node_name(context, self.node_name)
            count = get_node_name_count(context, self.node_name)
            if count > 1:
                diffctl.launch.logging.get_logger(self.name).warning(
                    f"there are now at least {count} nodes with the name {self.node_name} created within this "
                    "launch context"
                )
        return result


def instantiate_extension(
    group_name: str,
    extension_name: str,
    extension_class: type,
    extensions: dict[str, Any],
    logger: Any,
    *,
    unique_instance: bool = False,
) -> Any:
    """An instance of an extension class (the one already made, unless `unique_instance`); None, with a
    logged reason, when it cannot be made."""
    if not unique_instance and extension_name in extensions:
        return extensions[extension_name]
    try:
        instance = extension_class()
    except plugin_support.PluginException as e:
        logger.warning(f"Failed to instantiate '{group_name}' extension '{extension_name}': {e}")
        return None
    except Exception as e:
        logger.error(f"Failed to instantiate '{group_name}' extension '{extension_name}': {e}")
        return None
    if not unique_instance:
        extensions[extension_name] = instance
    return instance


g_entry_points_impl: Any = None  # the `launch_ros.node_action` entry points, read once a process


def get_extensions(logger: Any) -> dict[str, Any]:
    """Instances of the `launch_ros.node_action` extensions installed, by entry point name."""
    global g_entry_points_impl
    if g_entry_points_impl is None:
        from importlib import metadata

        g_entry_points_impl = {ep.name: ep for ep in metadata.entry_points(group=EXTENSION_GROUP)}
    extensions: dict[str, Any] = {}
    for name, entry_point in g_entry_points_impl.items():
        try:
            cls = entry_point.load()
        except Exception as e:
            logger.warning(f"Failed to load entry point '{name}': {e}")
            continue
        instance = instantiate_extension(EXTENSION_GROUP, name, cls, extensions, logger)
        if instance is not None:
            instance.NAME = name
            extensions[name] = instance
    return extensions
