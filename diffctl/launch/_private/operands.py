"""What the built-in substitutions have in common.

A substitution holds operands (lists of substitutions), reads the positional arguments of its `$(tag …)`
form into constructor keywords, and describes its operands. Each tag keeps the exception type and wording
ROS 2 users know for a wrong argument count, so the table lives with the tag, and the counting here.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from ..launch_context import LaunchContext
    from ..substitution import Substitution


def tag_kwargs(
    data: Sequence[Any],
    names: Sequence[str],
    message: str,
    *,
    required: int | None = None,
    error: type[Exception] = TypeError,
) -> dict[str, Any]:
    """Keyword arguments from `$(tag a b …)`'s arguments: the n-th one is called `names[n]`.

    At least `required` (all of `names` when None) and at most `len(names)` arguments are accepted;
    any other count raises `error(message)`.
    """
    fewest = len(names) if required is None else required
    if len(data) < fewest or len(data) > len(names):
        raise error(message)
    return {name: value for name, value in zip(names, data, strict=False)}


def joined(subs: Iterable[Substitution], separator: str = ' + ') -> str:
    """The descriptions of `subs`, one after the other."""
    return separator.join(sub.describe() for sub in subs)


def truth_of(context: LaunchContext, operand: list[Substitution]) -> bool:
    """`operand` read as a boolean, as typed substitutions read one; unreadable text fails the substitution."""
    from ..substitutions.substitution_failure import SubstitutionFailure
    from ..utilities.type_utils import perform_typed_substitution

    try:
        return perform_typed_substitution(context, operand, bool)
    except (TypeError, ValueError) as problem:
        raise SubstitutionFailure(problem) from problem


def bool_text(value: bool) -> str:
    """The spelling substitutions give booleans."""
    return 'true' if value else 'false'


def launch_file_local(context: LaunchContext, key: str, who: str) -> str:
    """A local an include sets for the file it loads; a script has none, which fails the substitution."""
    from ..substitutions.substitution_failure import SubstitutionFailure

    known = context.get_locals_as_dict()
    if key in known:
        return known[key]
    raise SubstitutionFailure(f'{who} used outside of a launch file (in a script)')
