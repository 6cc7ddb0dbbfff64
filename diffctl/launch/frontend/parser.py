"""`Parser`: turns a markup launch file into a launch description, with the frontends installed.

Frontends (XML, YAML, third-party) are `Parser` subclasses registered in the `launch.frontend.parser`
entry point group; `Parser.load(file)` picks them by file name, then tries the others. Packages that add
actions or substitutions to the markup register a module in `launch.frontend.launch_extension`; it is
imported before the first action is parsed so that its `expose_*` decorators have run.
"""

from __future__ import annotations

import itertools
import os
import traceback
import warnings
from typing import TYPE_CHECKING, Any, TextIO

from ..invalid_launch_file_error import InvalidLaunchFileError
from ..utilities.typing_file_path import FilePath
from .entity import Entity
from .expose import instantiate_action, where
from .parse_substitution import parse_if_substitutions, parse_substitution, replace_escaped_characters

if TYPE_CHECKING:
    from ..action import Action
    from ..launch_description import LaunchDescription
    from ..substitution import Substitution
    from ..utilities.type_utils import NormalizedValueType, StrSomeValueType

# diffctl ships these frontends; they count even where the package's entry points are not installed
_BUILTIN_PARSERS = {'xml': 'diffctl.launch_xml', 'yaml': 'diffctl.launch_yaml'}


class InvalidFrontendLaunchFileError(InvalidLaunchFileError):
    """A markup launch file none of the frontends could load."""


def _entry_points(group: str) -> list:
    from importlib import metadata

    found = metadata.entry_points(group=group)
    if isinstance(found, dict):  # the older API's {group: [entry points]}
        found = found.get(group, [])
    return list(found)


def __getattr__(name: str) -> Any:
    # `importlib_metadata` (what entry points are read with) is imported on first use
    if name == 'importlib_metadata':
        import importlib.metadata

        return importlib.metadata
    raise AttributeError(f'module {__name__!r} has no attribute {name!r}')


def mark_location(exc: BaseException, entity: Any) -> None:
    """Remember on `exc` the innermost markup element it came from (`file:line`), once."""
    location = getattr(entity, 'location', None)
    if location and getattr(exc, 'launch_location', None) is None:
        try:
            exc.launch_location = location  # type: ignore[attr-defined]
            if location not in str(exc):
                exc.add_note(f'while parsing <{entity.type_name}> at {location}')
        except (AttributeError, TypeError):
            pass  # exceptions that take no attributes keep their message as is


class Parser:
    """Base of the frontend parsers, and the entry to them.

    A frontend overrides `load` (file → root entity and parser) and `get_file_extensions`, and may
    override `parse_substitution`. The rest is shared.
    """

    extensions_loaded = False
    frontend_parsers: dict[str, Any] | None = None

    @classmethod
    def load_launch_extensions(cls) -> None:
        """Import every `launch.frontend.launch_extension` entry point once (a failure is a warning)."""
        if cls.extensions_loaded is False:
            for entry_point in _entry_points('launch.frontend.launch_extension'):
                try:
                    entry_point.load()
                except Exception:
                    warnings.warn(
                        f'Failed to load the launch extension: {entry_point.name}\n{traceback.format_exc()}',
                        stacklevel=1)
            cls.extensions_loaded = True

    @classmethod
    def load_parser_implementations(cls) -> None:
        """Find the frontends (`launch.frontend.parser` entry points) once."""
        if cls.frontend_parsers is not None:
            return
        parsers: dict[str, Any] = {}
        for entry_point in _entry_points('launch.frontend.parser'):
            try:
                parsers[entry_point.name] = entry_point.load()
            except Exception:
                warnings.warn(
                    f'Failed to load the parser extension: {entry_point.name}\n{traceback.format_exc()}', stacklevel=1)
        import importlib

        for name, module in _BUILTIN_PARSERS.items():
            if name not in parsers:
                parsers[name] = importlib.import_module(module).Parser
        cls.frontend_parsers = dict(sorted(parsers.items()))

    def parse_action(self, entity: Entity) -> Action:
        """The action an entity describes, through the parse method registered for its tag."""
        self.load_launch_extensions()
        try:
            action = instantiate_action(entity, self)
        except Exception as exc:
            mark_location(exc, entity)
            raise
        location = getattr(entity, 'location', None)
        if location is not None:
            try:
                action._frontend_location = location  # named by what the action raises when launched
            except AttributeError:
                pass
        return action

    def parse_substitution(self, value: str) -> list[Substitution]:
        """The substitutions in an attribute value."""
        return parse_substitution(value)

    def parse_if_substitutions(self, value: StrSomeValueType) -> NormalizedValueType:
        """See :py:func:`launch.frontend.parse_substitution.parse_if_substitutions`."""
        return parse_if_substitutions(value)

    def escape_characters(self, value: str) -> str:
        """`value` with backslash escapes resolved."""
        return replace_escaped_characters(value)

    def parse_description(self, entity: Entity) -> LaunchDescription:
        """The launch description of a root `launch` entity."""
        from ..launch_description import LaunchDescription

        if entity.type_name != 'launch':
            raise RuntimeError(f"{where(entity)}Expected 'launch' as root tag")
        deprecated = entity.get_attr('deprecated', optional=True)
        actions = [self.parse_action(child) for child in entity.children]
        return LaunchDescription(actions, deprecated_reason=deprecated)

    @classmethod
    def get_available_extensions(cls) -> list[str]:
        """Names of the installed frontends."""
        cls.load_parser_implementations()
        return cls.frontend_parsers.keys()

    @classmethod
    def is_extension_valid(cls, extension: str) -> bool:
        """Deprecated: whether a frontend is named `extension`."""
        warnings.warn('Parser.is_extension_valid is deprecated, use Parser.is_filename_valid instead', stacklevel=1)
        cls.load_parser_implementations()
        return extension in cls.frontend_parsers

    @classmethod
    def get_parser_from_extension(cls, extension: str) -> type[Parser] | None:
        """Deprecated: the frontend named `extension`."""
        warnings.warn(
            'Parser.get_parser_from_extension is deprecated, use Parser.get_parsers_from_filename instead',
            stacklevel=1)
        cls.load_parser_implementations()
        try:
            return cls.frontend_parsers[extension]
        except KeyError:
            raise RuntimeError('Not recognized frontend implementation') from None

    @classmethod
    def may_parse(cls, filename: str) -> bool:
        """Whether `filename` ends with one of this parser's extensions."""
        return any(filename.endswith('.' + ext) for ext in cls.get_file_extensions())

    @classmethod
    def is_filename_valid(cls, filename: str) -> bool:
        """Whether some frontend claims `filename`."""
        cls.load_parser_implementations()
        return any(parser.may_parse(filename) for parser in cls.frontend_parsers.values())

    @classmethod
    def get_parsers_from_filename(cls, filename: str) -> list[type[Parser]]:
        """The frontends that claim `filename`."""
        cls.load_parser_implementations()
        return [parser for parser in cls.frontend_parsers.values() if parser.may_parse(filename)]

    @classmethod
    def get_file_extensions_from_parsers(cls) -> set[str]:
        """Every file extension some frontend claims."""
        cls.load_parser_implementations()
        return set(itertools.chain.from_iterable(p.get_file_extensions() for p in cls.frontend_parsers.values()))

    @classmethod
    def load(cls, file: FilePath | TextIO) -> tuple[Entity, Parser]:
        """(root entity, parser) of a markup file, a path or an open text file.

        The frontends claiming the file's name are tried first, then the others; when none can load it,
        InvalidFrontendLaunchFileError carries what each raised.
        """
        cls.load_parser_implementations()
        opened = isinstance(file, (str, bytes, os.PathLike))
        fileobj = open(file) if opened else file  # noqa: SIM115 (closed below)
        try:
            filename = getattr(fileobj, 'name', '')
            if not isinstance(filename, str):
                filename = ''
            candidates = cls.get_parsers_from_filename(filename)
            candidates += [p for p in cls.frontend_parsers.values() if p not in candidates]
            errors: list[Exception] = []
            for implementation in candidates:
                try:
                    return implementation.load(fileobj)
                except Exception as exc:
                    errors.append(exc)
                    fileobj.seek(0)
            extension = os.path.splitext(filename)[1][1:] if cls.is_filename_valid(filename) else ''
            raise InvalidFrontendLaunchFileError(extension, likely_errors=errors)
        finally:
            if opened:
                fileobj.close()

    @classmethod
    def get_file_extensions(cls) -> set[str]:
        """The file extensions this parser claims (none for the base)."""
        return set()
