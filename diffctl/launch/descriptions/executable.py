"""`Executable`: the description of a process to run (command, prefix, name, cwd, environment)."""

from __future__ import annotations

import itertools
import os
import re
import shlex
from collections.abc import Iterable
from typing import TYPE_CHECKING

from ..substitutions.launch_configuration import LaunchConfiguration
from ..utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from ..utilities.perform_substitutions_impl import perform_substitutions

if TYPE_CHECKING:
    from ..action import Action
    from ..launch_context import LaunchContext
    from ..some_substitutions_type import SomeSubstitutionsType
    from ..substitution import Substitution

# one counter for the whole process: final names are unique across every launch of it
_instance_numbers = itertools.count(1)

_Pairs = list[tuple[list['Substitution'], list['Substitution']]]


def _pairs(mapping: dict | None) -> _Pairs | None:
    if mapping is None:
        return None
    return [(normalize_to_list_of_substitutions(k), normalize_to_list_of_substitutions(v)) for k, v in mapping.items()]


class Executable:
    """A process the launch may run; `prepare` performs its substitutions into the `final_*` values.

    - `cmd`: the executable and its arguments, each a string, a substitution or a list of them;
      `arguments` are appended to it.
    - `prefix`: words put before the command (gdb, valgrind, …); by default the `launch-prefix` launch
      configuration, applied only when the executable's name matches the `launch-prefix-filter` regular
      expression (when that configuration is set).
    - `name`: the label of the process (default: the executable's base name); the final name gets a
      unique `-N` suffix.
    - `env`: the complete environment (None: the launch's environment); `additional_env` is added to it.
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
        self.__cmd = [normalize_to_list_of_substitutions(x) for x in cmd]
        if arguments is not None:
            self.__cmd += [normalize_to_list_of_substitutions(x) for x in arguments]
        if prefix is None:
            self.__prefix = normalize_to_list_of_substitutions(LaunchConfiguration('launch-prefix', default=''))
            self.__prefix_filter = normalize_to_list_of_substitutions(
                LaunchConfiguration('launch-prefix-filter', default=''))
        else:
            self.__prefix = normalize_to_list_of_substitutions(prefix)
            self.__prefix_filter = None
        self.__name = None if name is None else normalize_to_list_of_substitutions(name)
        self.__cwd = None if cwd is None else normalize_to_list_of_substitutions(cwd)
        self.__env = _pairs(env)
        self.__additional_env = _pairs(additional_env)
        self.__arguments = arguments
        self.__final_cmd: list[str] | None = None
        self.__final_cwd: str | None = None
        self.__final_env: dict[str, str] | None = None
        self.__final_name: str | None = None

    @property
    def name(self):
        return self.__name

    @property
    def prefix(self):
        return self.__prefix

    @property
    def cmd(self):
        return self.__cmd

    @property
    def cwd(self):
        return self.__cwd

    @property
    def env(self):
        return self.__env

    @property
    def additional_env(self):
        return self.__additional_env

    @property
    def arguments(self):
        return self.__arguments

    @property
    def final_name(self):
        return self.__final_name

    @property
    def final_cmd(self):
        return self.__final_cmd

    @property
    def final_cwd(self):
        return self.__final_cwd

    @property
    def final_env(self):
        return self.__final_env

    def prepare(self, context: LaunchContext, action: Action) -> None:
        """Perform the substitutions of the description in `context` (`action` is for subclasses)."""
        cmd = [perform_substitutions(context, part) for part in self.__cmd]
        apply_prefix = True
        if self.__prefix_filter is not None:
            pattern = perform_substitutions(context, self.__prefix_filter)
            apply_prefix = re.match(pattern, os.path.basename(cmd[0])) is not None
        if apply_prefix:
            cmd = shlex.split(perform_substitutions(context, self.__prefix)) + cmd
        self.__final_cmd = cmd
        name = os.path.basename(cmd[0]) if self.__name is None else perform_substitutions(context, self.__name)
        self.__final_name = f'{name}-{next(_instance_numbers)}'
        self.__final_cwd = None if self.__cwd is None else perform_substitutions(context, self.__cwd)
        if self.__env is None:
            env = dict(context.environment)
        else:
            env = {perform_substitutions(context, k): perform_substitutions(context, v) for k, v in self.__env}
        for k, v in self.__additional_env or ():
            env[perform_substitutions(context, k)] = perform_substitutions(context, v)
        self.__final_env = env
