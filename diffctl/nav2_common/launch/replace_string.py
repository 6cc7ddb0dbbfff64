"""`ReplaceString`: the path of a copy of a file with strings replaced, line by line."""

from __future__ import annotations

from diffctl.launch import Condition, LaunchContext, SomeSubstitutionsType, Substitution
from diffctl.launch.substitutions import SubstitutionFailure
from diffctl.launch.utilities import normalize_to_list_of_substitutions, perform_substitutions

from ._files import read_text, write_copy


class ReplaceString(Substitution):
    """Each key of `replacements` becomes its value in a copy of `source_file`, in the dictionary's order; when
    `condition` is given and false, the source file's own path instead."""

    def __init__(
        self, source_file: SomeSubstitutionsType, replacements: dict, condition: Condition | None = None
    ) -> None:
        super().__init__()
        self._source = normalize_to_list_of_substitutions(source_file)
        self._replacements = {k: normalize_to_list_of_substitutions(v) for k, v in replacements.items()}
        self._condition = condition

    @property
    def name(self) -> list[Substitution]:
        return self._source

    @property
    def condition(self) -> Condition | None:
        return self._condition

    def describe(self) -> str:
        return ""

    def perform(self, context: LaunchContext) -> str:
        path = perform_substitutions(context, self._source)
        if self._condition is not None and not self._condition.evaluate(context):
            return path
        pairs = [(key, perform_substitutions(context, value)) for key, value in self._replacements.items()]
        wrong = [key for key, _ in pairs if not isinstance(key, str)]
        if wrong:
            raise SubstitutionFailure(f"ReplaceString: replacement key {wrong[0]!r} is not a string")
        lines = read_text(path, "ReplaceString").splitlines(keepends=True)
        for old, new in pairs:
            lines = [line.replace(old, new) for line in lines]
        return write_copy("".join(lines))
