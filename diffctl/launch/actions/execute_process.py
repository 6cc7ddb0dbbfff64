"""`ExecuteProcess`, `<executable cmd=… …>`: run a command line as a local process."""

from __future__ import annotations

import shlex
from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

from .._private.markup import name_value_children
from ..descriptions.executable import Executable
from ..frontend.expose import expose_action
from ..substitutions.text_substitution import TextSubstitution
from .execute_local import ExecuteLocal
from .shutdown_action import Shutdown

if TYPE_CHECKING:
    from ..frontend.entity import Entity
    from ..frontend.parser import Parser
    from ..some_substitutions_type import SomeSubstitutionsType
    from ..substitution import Substitution


def _timeout(entity: Entity, attribute: str) -> float | None:
    seconds = entity.get_attr(attribute, data_type=float, optional=True)
    if seconds is not None and seconds < 0.0:
        raise ValueError(
            f'Attribute {attribute} of Entity node expected to be a non-negative value but got `{seconds}`')
    return seconds


def _on_exit(entity: Entity) -> list | None:
    what = entity.get_attr('on_exit', optional=True)
    if what is None:
        return None
    if what != 'shutdown':
        raise ValueError(
            f'Attribute on_exit of Entity node expected to be shutdown but got `{what}`'
            'Other on_exit actions not yet supported')
    return [Shutdown()]


# markup attributes read by ExecuteProcess.parse: (attribute, keyword, reader); a keyword a subclass names
# in `ignore` is left for it to read
_READERS = (
    ('cwd', 'cwd', 'substitution'),
    ('name', 'name', 'substitution'),
    ('launch-prefix', 'prefix', 'substitution'),
    ('output', 'output', 'substitution'),
    ('respawn', 'respawn', 'substitution'),
    ('on_exit', 'on_exit', 'on_exit'),
    ('respawn_max_retries', 'respawn_max_retries', 'int'),
    ('respawn_delay', 'respawn_delay', 'timeout'),
    ('sigkill_timeout', 'sigkill_timeout', 'timeout text'),
    ('sigterm_timeout', 'sigterm_timeout', 'timeout text'),
    ('shell', 'shell', 'bool'),
    ('emulate_tty', 'emulate_tty', 'bool'),
)


def _read(entity: Entity, parser: Parser, attribute: str, reader: str) -> Any:
    if reader == 'substitution':
        text = entity.get_attr(attribute, optional=True)
        return None if text is None else parser.parse_substitution(text)
    if reader == 'on_exit':
        return _on_exit(entity)
    if reader in ('int', 'bool'):
        return entity.get_attr(attribute, data_type=int if reader == 'int' else bool, optional=True)
    seconds = _timeout(entity, attribute)
    # the kill timeouts are substitutions: the number goes in as its text
    return str(seconds) if seconds is not None and reader == 'timeout text' else seconds


@expose_action('executable')
class ExecuteProcess(ExecuteLocal):
    """`ExecuteLocal` of the `Executable` made of `cmd`, `prefix`, `name`, `cwd`, `env`, `additional_env`.

    Other keywords are ExecuteLocal's (output, shell, emulate_tty, timeouts, on_exit, respawn, …). In
    XML: `<executable cmd="ls -las" name="my_ls" output="screen"><env name="A" value="1"/></executable>`.
    """

    def __init__(
        self,
        *,
        cmd: Iterable[SomeSubstitutionsType],
        prefix: SomeSubstitutionsType | None = None,
        name: SomeSubstitutionsType | None = None,
        cwd: SomeSubstitutionsType | None = None,
        env: dict[SomeSubstitutionsType, SomeSubstitutionsType] | None = None,
        additional_env: dict[SomeSubstitutionsType, SomeSubstitutionsType] | None = None,
        **kwargs: Any,
    ) -> None:
        described = Executable(cmd=cmd, prefix=prefix, name=name, cwd=cwd, env=env, additional_env=additional_env)
        super().__init__(process_description=described, **kwargs)

    @classmethod
    def _parse_cmdline(cls, cmd: str, parser: Parser) -> list[SomeSubstitutionsType]:
        """The arguments of a markup command line, each a list of substitutions.

        The text between substitutions is split on blanks (with shell quoting); a substitution belongs to
        the word it touches: `$(find-exec x)/bin` is one argument, `$(a) $(b)` two. Launch_ros's Node
        reads its `args` and `ros_args` with it.
        """
        arguments: list[list[Substitution]] = []
        word: list[Substitution] = []

        def cut(*, even_empty: bool = False) -> None:
            nonlocal word
            if word or even_empty:
                arguments.append(word)
                word = []

        for piece in parser.parse_substitution(cmd):
            if not isinstance(piece, TextSubstitution):
                word.append(piece)
                continue
            text = piece.text
            parts = shlex.split(text)
            if not parts:
                cut(even_empty=True)  # blanks alone separate what is around them
                continue
            if text[0].isspace():
                cut()
            for index, part in enumerate(parts):
                if index:
                    cut()
                word.append(TextSubstitution(text=part))
            if text[-1].isspace():
                cut()
        cut()
        return arguments

    @classmethod
    def parse(cls, entity: Entity, parser: Parser, ignore: list[str] | None = None):
        """`(cls, kwargs)` of an `<executable>`; the keywords in `ignore` are left to a subclass's parse."""
        _, kwargs = super().parse(entity, parser)
        skipped = set(ignore or ())
        if 'cmd' not in skipped:
            kwargs['cmd'] = cls._parse_cmdline(entity.get_attr('cmd'), parser)
        for attribute, keyword, reader in _READERS:
            if keyword in skipped:
                continue
            value = _read(entity, parser, attribute, reader)
            if value is not None:
                kwargs[keyword] = value
        if 'additional_env' not in skipped:
            # <env name=… value=…/> children, without conditions (set_env and unset_env have those)
            pairs = name_value_children(entity, parser, 'env')
            if pairs is not None:
                kwargs['additional_env'] = {tuple(name): value for name, value in pairs}
        return cls, kwargs

    def _given_or_final(self, given: str) -> Any:
        final = getattr(self.process_description, f'final_{given}')
        return getattr(self.process_description, given) if final is None else final

    @property
    def name(self):
        """The final name once prepared, else the name as given (substitutions)."""
        return self._given_or_final('name')

    @property
    def cmd(self):
        """The final command once prepared, else as given (lists of substitutions)."""
        return self._given_or_final('cmd')

    @property
    def cwd(self):
        return self._given_or_final('cwd')

    @property
    def env(self):
        return self._given_or_final('env')

    @property
    def additional_env(self):
        return self.process_description.additional_env
