"""`Parser`: markup launch files to launch descriptions, through the installed frontends.

A frontend (XML, YAML, a third party's) is a `Parser` subclass named in the `launch.frontend.parser` entry
point group; `Parser.load(file)` asks those claiming the file's name first, then the others. Packages adding
tags or substitutions name a module in `launch.frontend.launch_extension`; it is imported before the first
action is parsed, so that its `expose_*` decorators have run.
"""

from __future__ import annotations

import functools
import os
import traceback
import warnings
from typing import TYPE_CHECKING, Any, TextIO

from .._private.attempts import NoneWorked, first_success
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

# the frontends diffctl ships: found even where the package's entry points are not installed
_OWN_FRONTENDS = {'xml': 'diffctl.launch_xml', 'yaml': 'diffctl.launch_yaml'}


class InvalidFrontendLaunchFileError(InvalidLaunchFileError):
    """No frontend could read a markup launch file."""


def __getattr__(name: str) -> Any:
    # `importlib_metadata`, what the entry points are read with, is imported when first asked for
    if name == 'importlib_metadata':
        import importlib.metadata

        return importlib.metadata
    raise AttributeError(f'module {__name__!r} has no attribute {name!r}')


def _loaded_entry_points(group: str, what: str) -> dict[str, Any]:
    """Each entry point of `group` loaded, by name; one that fails to load is a warning, not an error."""
    from importlib import metadata

    found = metadata.entry_points(group=group)
    if isinstance(found, dict):  # the older API: {group: [entry points]}
        found = found.get(group, [])
    loaded = {}
    for entry_point in found:
        try:
            loaded[entry_point.name] = entry_point.load()
        except Exception:
            warnings.warn(f'Failed to load the {what}: {entry_point.name}\n{traceback.format_exc()}', stacklevel=1)
    return loaded


def mark_location(exc: BaseException, entity: Any) -> None:
    """Note on `exc` the markup element it came from (`file:line`), unless an inner one was noted."""
    location = getattr(entity, 'location', None)
    if not location or getattr(exc, 'launch_location', None) is not None:
        return
    try:
        exc.launch_location = location  # type: ignore[attr-defined]
        if location not in str(exc):
            exc.add_note(f'while parsing <{entity.type_name}> at {location}')
    except (AttributeError, TypeError):
        pass  # an exception type that takes no attributes keeps its message


class Parser:
    """The frontends' base class, and the way to them.

    A frontend implements `load` (a file → its root entity and a parser instance) and
    `get_file_extensions`; it may replace `parse_substitution`. Everything else is shared.
    """

    extensions_loaded = False
    frontend_parsers: dict[str, Any] | None = None

    # ---- what is installed -----------------------------------------------------------------------------------

    @classmethod
    def load_launch_extensions(cls) -> None:
        """Import the `launch.frontend.launch_extension` entry points (once)."""
        if not cls.extensions_loaded:
            _loaded_entry_points('launch.frontend.launch_extension', 'launch extension')
            cls.extensions_loaded = True

    @classmethod
    def load_parser_implementations(cls) -> None:
        """Find the frontends of the `launch.frontend.parser` entry points (once)."""
        if cls.frontend_parsers is not None:
            return
        import importlib

        found = _loaded_entry_points('launch.frontend.parser', 'parser extension')
        for name, module in _OWN_FRONTENDS.items():
            if name not in found:
                found[name] = importlib.import_module(module).Parser
        cls.frontend_parsers = {name: found[name] for name in sorted(found)}

    @classmethod
    def _frontends(cls) -> dict[str, Any]:
        cls.load_parser_implementations()
        return cls.frontend_parsers

    @classmethod
    def get_available_extensions(cls) -> list[str]:
        """The frontends' names."""
        return cls._frontends().keys()

    @classmethod
    def get_file_extensions(cls) -> set[str]:
        """The file extensions this frontend reads (the base class reads none)."""
        return set()

    @classmethod
    def get_file_extensions_from_parsers(cls) -> set[str]:
        """Every file extension one of the frontends reads."""
        extensions: set[str] = set()
        for frontend in cls._frontends().values():
            extensions |= set(frontend.get_file_extensions())
        return extensions

    @classmethod
    def may_parse(cls, filename: str) -> bool:
        """Whether `filename` ends with one of this frontend's extensions."""
        return any(filename.endswith(f'.{extension}') for extension in cls.get_file_extensions())

    @classmethod
    def get_parsers_from_filename(cls, filename: str) -> list[type[Parser]]:
        """The frontends whose extensions `filename` ends with."""
        return [frontend for frontend in cls._frontends().values() if frontend.may_parse(filename)]

    @classmethod
    def is_filename_valid(cls, filename: str) -> bool:
        """Whether some frontend reads files named like `filename`."""
        return bool(cls.get_parsers_from_filename(filename))

    @classmethod
    def is_extension_valid(cls, extension: str) -> bool:
        """Deprecated (use `is_filename_valid`): whether a frontend is called `extension`."""
        warnings.warn('Parser.is_extension_valid is deprecated, use Parser.is_filename_valid instead', stacklevel=1)
        return extension in cls._frontends()

    @classmethod
    def get_parser_from_extension(cls, extension: str) -> type[Parser] | None:
        """Deprecated (use `get_parsers_from_filename`): the frontend called `extension`."""
        warnings.warn(
            'Parser.get_parser_from_extension is deprecated, use Parser.get_parsers_from_filename instead',
            stacklevel=1)
        frontends = cls._frontends()
        if extension not in frontends:
            raise RuntimeError('Not recognized frontend implementation')
        return frontends[extension]

    # ---- reading a file ------------------------------------------------------------------------------------

    @classmethod
    def load(cls, file: FilePath | TextIO) -> tuple[Entity, Parser]:
        """The root entity of a markup file (a path, or a text file open for reading) and its parser.

        The frontends claiming the file's name try first, then the rest; if none reads it,
        InvalidFrontendLaunchFileError tells what each of them raised.
        """
        frontends = cls._frontends()
        if isinstance(file, (str, bytes, os.PathLike)):
            with open(file) as stream:
                return cls._load_with_any(stream, frontends)
        return cls._load_with_any(file, frontends)

    @classmethod
    def _load_with_any(cls, stream: TextIO, frontends: dict[str, Any]) -> tuple[Entity, Parser]:
        name = getattr(stream, 'name', '')
        name = name if isinstance(name, str) else ''
        claiming = cls.get_parsers_from_filename(name)
        order = claiming + [frontend for frontend in frontends.values() if frontend not in claiming]
        try:
            return first_success(
                (functools.partial(frontend.load, stream) for frontend in order), after_failure=lambda: stream.seek(0))
        except NoneWorked as tried:
            failures = tried.failures
        extension = os.path.splitext(name)[1][1:] if claiming else ''
        raise InvalidFrontendLaunchFileError(extension, likely_errors=failures)

    # ---- what a frontend's entities become ---------------------------------------------------------------

    def parse_description(self, entity: Entity) -> LaunchDescription:
        """The launch description of a root `<launch>` entity."""
        from ..launch_description import LaunchDescription

        if entity.type_name != 'launch':
            raise RuntimeError(f"{where(entity)}Expected 'launch' as root tag")
        reason = entity.get_attr('deprecated', optional=True)
        return LaunchDescription([self.parse_action(child) for child in entity.children], deprecated_reason=reason)

    def parse_action(self, entity: Entity) -> Action:
        """The action `entity` describes, by the parse method registered for its tag."""
        self.load_launch_extensions()
        try:
            action = instantiate_action(entity, self)
        except Exception as problem:
            mark_location(problem, entity)
            raise
        location = getattr(entity, 'location', None)
        if location is not None:
            try:
                action._frontend_location = location  # what the action raises when launched names it
            except AttributeError:
                pass
        return action

    def parse_substitution(self, value: str) -> list[Substitution]:
        """The substitutions an attribute's text holds."""
        return parse_substitution(value)

    def parse_if_substitutions(self, value: StrSomeValueType) -> NormalizedValueType:
        """A typed value, its strings read as substitutions (see `parse_substitution.parse_if_substitutions`)."""
        return parse_if_substitutions(value)

    def escape_characters(self, value: str) -> str:
        """`value` with its backslash escapes resolved."""
        return replace_escaped_characters(value)
