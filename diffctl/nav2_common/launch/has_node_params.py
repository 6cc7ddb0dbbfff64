"""`HasNodeParams`: 'True' when a parameter file has a top-level entry for a node, else 'False'."""

from __future__ import annotations

from diffctl.launch import LaunchContext, SomeSubstitutionsType, Substitution
from diffctl.launch.utilities import normalize_to_list_of_substitutions, perform_substitutions

from ._files import read_yaml


class HasNodeParams(Substitution):
    def __init__(self, source_file: SomeSubstitutionsType, node_name: str) -> None:
        super().__init__()
        self._source = normalize_to_list_of_substitutions(source_file)
        self._node = node_name

    @property
    def name(self) -> list[Substitution]:
        return self._source

    def describe(self) -> str:
        return ""

    def perform(self, context: LaunchContext) -> str:
        data = read_yaml(perform_substitutions(context, self._source), "HasNodeParams")
        return str(isinstance(data, dict) and self._node in data)
