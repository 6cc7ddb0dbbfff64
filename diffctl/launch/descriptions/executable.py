"""`Executable`: what a process action runs — command, prefix, name, folder, environment."""

from __future__ import annotations

import itertools
import os
import re
import shlex
from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

from .._private.fields import field
from ..substitutions.launch_configuration import LaunchConfiguration
from ..utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from ..utilities.perform_substitutions_impl import perform_substitutions

if TYPE_CHECKING:
    from ..action import Action
    from ..launch_context import LaunchContext
    from ..some_substitutions_type import SomeSubstitutionsType

# Numbers the final names: one sequence for the whole Python process, so names stay unique across runs.
_numbers = itertools.count(1)


def _final_name(context: LaunchContext, action: Action, base: str) -> str:
    """`base-N` (N from `_numbers`), or what the LaunchService's `process_label` makes of `base`."""
    label = getattr(context, '_process_label', None)
    return f'{base}-{next(_numbers)}' if label is None else label(action, base)


def _subs(value: Any) -> Any:
    return None if value is None else normalize_to_list_of_substitutions(value)


def _subs_pairs(mapping: dict | None) -> list | None:
    return None if mapping is None else [(_subs(key), _subs(value)) for key, value in mapping.items()]


class Executable:
    """A process to run; `prepare(context, action)` performs its substitutions into the `final_*` values.

    - `cmd` (each item text, a substitution, or a list of them) and then `arguments` make the command.
    - `prefix` goes before it (gdb, valgrind, …). Without one, the `launch-prefix` launch configuration
      does, for executables whose name matches the `launch-prefix-filter` regular expression (all, when
      it is unset).
    - `name` labels the process (the command's first word's base name by default); the final name adds a
      `-N` that makes it unique (or is what the LaunchService's `process_label` makes of it).
    - `env` replaces the launch's environment, `additional_env` adds to it.
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
        arguments: Iterable[SomeSubstitutionsType] | None = None,
    ) -> None:
        words = [*cmd, *(arguments or ())]
        launch_wide = prefix is None  # the launch configurations decide the prefix, filter included
        self._fields: dict[str, Any] = {
            'cmd': [_subs(word) for word in words],
            'prefix': _subs(LaunchConfiguration('launch-prefix', default='') if launch_wide else prefix),
            'name': _subs(name),
            'cwd': _subs(cwd),
            'env': _subs_pairs(env),
            'additional_env': _subs_pairs(additional_env),
            'arguments': arguments,
            'final_name': None, 'final_cmd': None, 'final_cwd': None, 'final_env': None,
        }
        self._prefix_filter = _subs(LaunchConfiguration('launch-prefix-filter', default='')) if launch_wide else None

    name = field('name')
    prefix = field('prefix')
    cmd = field('cmd')
    cwd = field('cwd')
    env = field('env')
    additional_env = field('additional_env')
    arguments = field('arguments')
    final_name = field('final_name')
    final_cmd = field('final_cmd')
    final_cwd = field('final_cwd')
    final_env = field('final_env')

    def _command(self, context: LaunchContext) -> list[str]:
        command = [perform_substitutions(context, word) for word in self._fields['cmd']]
        if self._prefix_filter is not None:
            pattern = perform_substitutions(context, self._prefix_filter)
            if re.match(pattern, os.path.basename(command[0])) is None:
                return command  # an empty filter matches every name
        return shlex.split(perform_substitutions(context, self._fields['prefix'])) + command

    def _environment(self, context: LaunchContext) -> dict[str, str]:
        given = self._fields['env']
        if given is None:
            environment = dict(context.environment)
        else:
            environment = {perform_substitutions(context, k): perform_substitutions(context, v) for k, v in given}
        for key, value in self._fields['additional_env'] or ():
            environment[perform_substitutions(context, key)] = perform_substitutions(context, value)
        return environment

    def prepare(self, context: LaunchContext, action: Action) -> None:
        """Perform every substitution in `context` (`action` is there for subclasses)."""
        command = self._command(context)
        label = self._fields['name']
        # the base name of the first word, prefix included, when no name is given
        base = os.path.basename(command[0]) if label is None else perform_substitutions(context, label)
        folder = self._fields['cwd']
        self._fields.update(
            final_cmd=command,
            final_name=_final_name(context, action, base),
            final_cwd=None if folder is None else perform_substitutions(context, folder),
            final_env=self._environment(context),
        )
