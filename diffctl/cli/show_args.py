"""`diffctl launch --show-args`: the declared arguments in the text `ros2 launch --show-args` prints.

Written from ros2launch's print_arguments_of_launch_description and launch's DeclareLaunchArgument
(jazzy): a missing description reads "no description given", choices read "One of: [...]" or are appended
to the description as "Valid choices are: [...]", a default is quoted, a required argument has no default line.
"""

from __future__ import annotations

from typing import Any

from diffctl.launch_legacy.plan import Argument


def ros_description(argument: Argument) -> str:
    """The description DeclareLaunchArgument builds from the one given and the choices."""
    choices = list(argument.choices) if argument.choices is not None else None
    if not argument.description:
        return "no description given" if choices is None else f"One of: {choices}"
    if choices is None:
        return argument.description
    text = argument.description if argument.description.endswith(".") else argument.description + "."
    return f"{text} Valid choices are: {choices}"


def _describe(sub: Any) -> str | None:
    """A substitution as launch's describe() writes it (None: one launch describes in a way not known here)."""
    from diffctl.launch_legacy.substitutions import (
        EnvironmentVariable,
        LaunchConfiguration,
        TextSubstitution,
        ThisLaunchFileDir,
    )

    def joined(subs: Any) -> str | None:
        parts = [_describe(s) for s in subs]
        return None if any(p is None for p in parts) else " + ".join(parts)  # type: ignore[arg-type]

    if isinstance(sub, TextSubstitution):
        return f"'{sub.text}'"
    if isinstance(sub, LaunchConfiguration):
        inner = joined(sub.variable_name)
        return None if inner is None else f"LaunchConfig({inner})"
    if isinstance(sub, EnvironmentVariable):
        inner = joined(sub.name)
        return None if inner is None else f"EnvVar({inner})"
    if isinstance(sub, ThisLaunchFileDir):
        return "ThisLaunchFileDir()"
    return None


def default_text(argument: Argument) -> str:
    """`(default: …)`'s text: launch describes the default as written, `'pre-' + LaunchConfig('a')`."""
    if argument.default_substitutions:
        parts = [_describe(s) for s in argument.default_substitutions]
        if all(p is not None for p in parts):
            return " + ".join(parts)  # type: ignore[arg-type]
    return f"'{argument.default}'"


def arguments_text(arguments: list[Argument]) -> str:
    lines = ["Arguments (pass arguments as '<name>:=<value>'):"]
    for argument in arguments:
        lines += ["", f"    '{argument.name}':", f"        {ros_description(argument)}"]
        if argument.default is not None:
            lines.append(f"        (default: {default_text(argument)})")
    if not arguments:
        lines += ["", "  No arguments."]
    return "\n".join(lines) + "\n"
