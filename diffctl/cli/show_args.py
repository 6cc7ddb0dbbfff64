"""`diffctl launch --show-args`: the declared arguments, in the text `ros2 launch --show-args` prints.

As ros2launch's print_arguments_of_launch_description (Jazzy): each argument's name (`*` when only a condition
makes it count), its description (DeclareLaunchArgument's, which says "no description given" and names the
choices), and the default as launch describes it (`'pre-' + LaunchConfig('a')`), never evaluated.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any


def arguments_text(arguments: Iterable[Any]) -> str:
    """`arguments`: a description's `get_launch_arguments()`."""
    lines = ["Arguments (pass arguments as '<name>:=<value>'):"]
    conditional = False
    count = 0
    for argument in arguments:
        count += 1
        star = "*" if getattr(argument, "_conditionally_included", False) else ""
        conditional = conditional or bool(star)
        lines += ["", f"    '{argument.name}':{star}", f"        {argument.description}"]
        if argument.default_value is not None:
            lines.append(f"        (default: {' + '.join(s.describe() for s in argument.default_value)})")
    if count == 0:
        lines += ["", "  No arguments."]
    elif conditional:
        lines += ["", "* argument(s) which are only used if specific conditions occur"]
    return "\n".join(lines) + "\n"
