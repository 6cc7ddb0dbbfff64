"""`ExecuteProcess` (`<executable>`): run a command as a local process."""

from __future__ import annotations

import shlex
from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

from ..descriptions.executable import Executable
from ..frontend.entity import Entity
from ..frontend.expose import expose_action
from ..substitutions.text_substitution import TextSubstitution
from .execute_local import ExecuteLocal
from .shutdown_action import Shutdown

if TYPE_CHECKING:
    from ..frontend.parser import Parser
    from ..some_substitutions_type import SomeSubstitutionsType
    from ..substitution import Substitution


def _non_negative(entity: Entity, attribute: str) -> float | None:
    value = entity.get_attr(attribute, data_type=float, optional=True)
    if value is not None and value < 0.0:
        raise ValueError(
            f'Attribute {attribute} of Entity node expected to be a non-negative value but got `{value}`')
    return value


@expose_action('executable')
class ExecuteProcess(ExecuteLocal):
    """`ExecuteLocal` of an `Executable` built from `cmd`, `prefix`, `name`, `cwd`, `env`, `additional_env`.

    Every other keyword goes to `ExecuteLocal` (output, shell, emulate_tty, timeouts, on_exit, respawn, …).
    In XML: `<executable cmd="ls -las" name="my_ls" output="screen"><env name="A" value="1"/></executable>`.
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
        executable = Executable(cmd=cmd, prefix=prefix, name=name, cwd=cwd, env=env, additional_env=additional_env)
        super().__init__(process_description=executable, **kwargs)

    @classmethod
    def _parse_cmdline(cls, cmd: str, parser: Parser) -> list[SomeSubstitutionsType]:
        """Split a markup command line into arguments, keeping `$(…)` glued to the text around them.

        Text is split on whitespace; a substitution joins the word it touches (`$(find-exec x)/bin` is
        one argument, `$(a) $(b)` two).
        """
        arguments: list[list[Substitution]] = []
        current: list[Substitution] = []

        def end_argument() -> None:
            nonlocal current
            arguments.append(current)
            current = []

        for sub in parser.parse_substitution(cmd):
            if not isinstance(sub, TextSubstitution):
                current.append(sub)
                continue
            words = shlex.split(sub.text)
            if not words:  # only spaces: they separate what is around them
                end_argument()
                continue
            if sub.text[0].isspace() and current:
                end_argument()
            current.append(TextSubstitution(text=words[0]))
            if len(words) > 1:
                end_argument()
                arguments.extend([TextSubstitution(text=w)] for w in words[1:-1])
                current.append(TextSubstitution(text=words[-1]))
            if sub.text[-1].isspace():
                end_argument()
        if current:
            arguments.append(current)
        return arguments

    @classmethod
    def parse(cls, entity: Entity, parser: Parser, ignore: list[str] | None = None):
        """(cls, kwargs) from an `<executable>` entity; attributes named in `ignore` are left to a subclass."""
        _, kwargs = super().parse(entity, parser)
        ignore = ignore or []

        def wanted(name: str) -> bool:
            return name not in ignore

        if wanted('cmd'):
            kwargs['cmd'] = cls._parse_cmdline(entity.get_attr('cmd'), parser)
        for attribute, key in (('cwd', 'cwd'), ('name', 'name'), ('launch-prefix', 'prefix'),
                               ('output', 'output'), ('respawn', 'respawn')):
            if wanted(key):
                value = entity.get_attr(attribute, optional=True)
                if value is not None:
                    kwargs[key] = parser.parse_substitution(value)
        if wanted('on_exit'):
            on_exit = entity.get_attr('on_exit', optional=True)
            if on_exit is not None:
                if on_exit != 'shutdown':
                    raise ValueError(
                        f'Attribute on_exit of Entity node expected to be shutdown but got `{on_exit}`'
                        'Other on_exit actions not yet supported')
                kwargs['on_exit'] = [Shutdown()]
        if wanted('respawn_max_retries'):
            retries = entity.get_attr('respawn_max_retries', data_type=int, optional=True)
            if retries is not None:
                kwargs['respawn_max_retries'] = retries
        if wanted('respawn_delay'):
            delay = _non_negative(entity, 'respawn_delay')
            if delay is not None:
                kwargs['respawn_delay'] = delay
        for timeout in ('sigkill_timeout', 'sigterm_timeout'):
            if wanted(timeout):
                value = _non_negative(entity, timeout)
                if value is not None:
                    kwargs[timeout] = str(value)
        for flag in ('shell', 'emulate_tty'):
            if wanted(flag):
                value = entity.get_attr(flag, data_type=bool, optional=True)
                if value is not None:
                    kwargs[flag] = value
        if wanted('additional_env'):
            # no conditions in <env>: set_env / unset_env actions do that
            env = entity.get_attr('env', data_type=list[Entity], optional=True)
            if env is not None:
                kwargs['additional_env'] = {
                    tuple(parser.parse_substitution(e.get_attr('name'))): parser.parse_substitution(e.get_attr('value'))
                    for e in env
                }
                for e in env:
                    e.assert_entity_completely_parsed()
        return cls, kwargs

    @property
    def name(self):
        """The final name once started, else the name as given (substitutions)."""
        final = self.process_description.final_name
        return final if final is not None else self.process_description.name

    @property
    def cmd(self):
        """The final command once started, else the command as given (lists of substitutions)."""
        final = self.process_description.final_cmd
        return final if final is not None else self.process_description.cmd

    @property
    def cwd(self):
        final = self.process_description.final_cwd
        return final if final is not None else self.process_description.cwd

    @property
    def env(self):
        final = self.process_description.final_env
        return final if final is not None else self.process_description.env

    @property
    def additional_env(self):
        return self.process_description.additional_env
