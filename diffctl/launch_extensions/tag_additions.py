"""What diffctl's launch files write in tags launch_yaml / launch_xml already have:

- `arg: {name: gui, choices: ["true", "false"]}`: an alias of `choice: [{value: "true"}, {value: "false"}]`;
- `let: {name: robot_description, file: PATH, replace: {PLACEHOLDER: value}}`: a file's text with placeholders
  replaced (the tutorial's SDF step, done in Python there); XML: `<let name="d" file="…"><replace
  name="PLACEHOLDER" value="…"/></let>`;
- `$(file-content PATH [PLACEHOLDER=value …])`: the same as a substitution;
- `$(optenv NAME [default])`: an environment variable, empty (or the default) when unset.

The first three extend tags launch exposes already: a tag has one parse method, so these wrap it (the
registry's entry), reading their own attributes and handing the rest to launch's.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

from diffctl.errors import LaunchError
from diffctl.launch.action import Action
from diffctl.launch.actions import SetLaunchConfiguration
from diffctl.launch.frontend import Entity, Parser, expose, expose_substitution
from diffctl.launch.launch_context import LaunchContext
from diffctl.launch.some_substitutions_type import SomeSubstitutionsType
from diffctl.launch.substitution import Substitution
from diffctl.launch.substitutions import EnvironmentVariable, SubstitutionFailure, TextSubstitution
from diffctl.launch.utilities import normalize_to_list_of_substitutions, perform_substitutions
from diffctl.launch_extensions import frontend_values


class FileWithReplacements(Substitution):
    """A file's text with each placeholder replaced by a value (FileContent, plus the replacing)."""

    def __init__(self, path: SomeSubstitutionsType, replace: dict[str, SomeSubstitutionsType] | None = None) -> None:
        super().__init__()
        self.path = normalize_to_list_of_substitutions(path)
        self.replace = {k: normalize_to_list_of_substitutions(v) for k, v in (replace or {}).items()}

    def describe(self) -> str:
        pairs = "".join(f", {k}={' + '.join(s.describe() for s in v)}" for k, v in self.replace.items())
        return f"FileContent({' + '.join(s.describe() for s in self.path)}{pairs})"

    def perform(self, context: LaunchContext) -> str:
        path = perform_substitutions(context, self.path)
        try:
            with open(path, encoding="utf-8") as f:
                text = f.read()
        except FileNotFoundError:
            raise SubstitutionFailure(f"File not found: {path}") from None
        except OSError as e:
            raise SubstitutionFailure(f"cannot read {path}: {e.strerror}") from None
        for placeholder, value in self.replace.items():
            text = text.replace(placeholder, perform_substitutions(context, value))
        return text


def _wrap_action(tag: str, extend: Callable[[Entity, Parser, Callable[..., Any]], Any]) -> None:
    original = expose.action_parse_methods[tag]

    def parse(entity: Entity, parser: Parser) -> Any:
        return extend(entity, parser, original)

    parse.__wrapped__ = original  # type: ignore[attr-defined]
    expose.action_parse_methods[tag] = parse


def _arg(entity: Entity, parser: Parser, original: Callable[..., Any]) -> Any:
    choices = entity.get_attr("choices", data_type=None, optional=True)
    if choices is None:
        return original(entity, parser)
    if entity.get_attr("choice", data_type=list[Entity], optional=True) is not None:
        raise LaunchError("give `choice` or `choices`, not both", field="arg.choices")
    if not isinstance(choices, list) or not choices:
        raise LaunchError(f"`choices` must be a non-empty list, got {choices!r}", field="arg.choices")
    cls, kwargs = original(entity, parser)
    kwargs["choices"] = [parser.escape_characters(str(c)) for c in choices]
    return cls, kwargs


def _let(entity: Entity, parser: Parser, original: Callable[..., Any]) -> Any:
    path = entity.get_attr("file", optional=True)
    if path is None:
        if _replacements(entity, parser):
            raise LaunchError("`replace` needs `file`", field="let.replace")
        return original(entity, parser)
    if entity.get_attr("value", data_type=None, optional=True) is not None:
        raise LaunchError("`let` takes either `value` or `file` (with optional `replace`)", field="let")
    _, kwargs = Action.parse(entity, parser)  # if / unless
    kwargs["name"] = parser.parse_substitution(entity.get_attr("name"))
    kwargs["value"] = [FileWithReplacements(parser.parse_substitution(path), _replacements(entity, parser))]
    entity.assert_entity_completely_parsed()
    return SetLaunchConfiguration, kwargs


def _replacements(entity: Entity, parser: Parser) -> dict[str, Any]:
    if frontend_values.is_yaml(entity):
        raw = frontend_values.mapping(entity, "replace") or {}
        return {k: parser.parse_substitution(str(v)) for k, v in raw.items()}
    items = entity.get_attr("replace", data_type=list[Entity], optional=True) or []
    return {r.get_attr("name"): parser.parse_substitution(r.get_attr("value")) for r in items}


def _split_pair(arg: Sequence[Substitution]) -> tuple[str, list[Substitution]]:
    """`NAME=value…` (value possibly substitutions) → NAME and the value's substitutions."""
    first = arg[0] if arg else None
    if not isinstance(first, TextSubstitution) or "=" not in first.text:
        raise LaunchError("file-content takes PATH then PLACEHOLDER=value pairs")
    name, _, rest = first.text.partition("=")
    return name, [TextSubstitution(text=rest), *arg[1:]]


@expose_substitution("optenv")
def _optenv(data: Sequence[SomeSubstitutionsType]) -> tuple[type, dict[str, Any]]:
    if not data or len(data) > 2:
        raise LaunchError("optenv takes a name and an optional default: $(optenv NAME [default])")
    return EnvironmentVariable, {"name": data[0], "default_value": data[1] if len(data) > 1 else ""}


def _file_content(data: Sequence[SomeSubstitutionsType]) -> tuple[type, dict[str, Any]]:
    if not data:
        raise LaunchError("file-content takes a path: $(file-content PATH [PLACEHOLDER=value …])")
    pairs = dict(_split_pair(normalize_to_list_of_substitutions(a)) for a in data[1:])
    return FileWithReplacements, {"path": data[0], "replace": pairs}


def install() -> None:
    # The modules that expose `arg`, `let` and `file-content` (launch imports its actions on first use).
    import diffctl.launch.actions.declare_launch_argument
    import diffctl.launch.actions.set_launch_configuration
    import diffctl.launch.substitutions.file_content  # noqa: F401

    _wrap_action("arg", _arg)
    _wrap_action("let", _let)
    original = expose.substitution_parse_methods["file-content"]

    def file_content(data: Sequence[SomeSubstitutionsType]) -> tuple[type, dict[str, Any]]:
        return _file_content(data) if len(data) > 1 else original(data)

    expose.substitution_parse_methods["file-content"] = file_content
