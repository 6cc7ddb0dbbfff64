"""`diffctl launch --show-args`: the declared arguments in the text `ros2 launch --show-args` prints.

Written from ros2launch's print_arguments_of_launch_description and launch's DeclareLaunchArgument
(jazzy): a missing description reads "no description given", choices read "One of: [...]" or are appended
to the description as "Valid choices are: [...]", a default is quoted, a required argument has no default line.
"""

from __future__ import annotations

from diffctl.launch.plan import Argument


def ros_description(argument: Argument) -> str:
    """The description DeclareLaunchArgument builds from the one given and the choices."""
    choices = list(argument.choices) if argument.choices is not None else None
    if not argument.description:
        return "no description given" if choices is None else f"One of: {choices}"
    if choices is None:
        return argument.description
    text = argument.description if argument.description.endswith(".") else argument.description + "."
    return f"{text} Valid choices are: {choices}"


def arguments_text(arguments: list[Argument]) -> str:
    lines = ["Arguments (pass arguments as '<name>:=<value>'):"]
    for argument in arguments:
        lines += ["", f"    '{argument.name}':", f"        {ros_description(argument)}"]
        if argument.default is not None:
            lines.append(f"        (default: '{argument.default}')")
    if not arguments:
        lines += ["", "  No arguments."]
    return "\n".join(lines) + "\n"
