"""A click group that imports a subcommand's module only when that subcommand runs.

`diffctl topic echo` must not pay for importing pybullet, and `diffctl --help` must stay instant.
"""

from __future__ import annotations

import importlib

import click


class LazyGroup(click.Group):
    """Subcommands given as {"name": ("module.path:attribute", "short help")}, imported on first use."""

    def __init__(self, *args, lazy_commands: dict[str, tuple[str, str]] | None = None, **kwargs) -> None:
        super().__init__(*args, **kwargs)
        self.lazy_commands = {k: v[0] for k, v in (lazy_commands or {}).items()}
        self.lazy_help = {k: v[1] for k, v in (lazy_commands or {}).items()}

    def format_commands(self, ctx: click.Context, formatter: click.HelpFormatter) -> None:
        # Listing must not import every subsystem (pybullet, zenoh): use the declared short help.
        rows = [
            (name, self.lazy_help.get(name, ""))
            for name in self.list_commands(ctx)
            if not self.lazy_help.get(name, "").startswith("(internal)")
        ]
        if rows:
            with formatter.section("Commands"):
                formatter.write_dl(rows)

    def list_commands(self, ctx: click.Context) -> list[str]:
        return sorted(set(super().list_commands(ctx)) | set(self.lazy_commands))

    def get_command(self, ctx: click.Context, cmd_name: str) -> click.Command | None:
        if cmd_name in self.lazy_commands:
            module_name, attr = self.lazy_commands[cmd_name].split(":")
            try:
                return getattr(importlib.import_module(module_name), attr)
            except ImportError as e:  # a broken install must not show up as a traceback
                raise click.ClickException(f"command {cmd_name!r} is unavailable: {e}") from None
        return super().get_command(ctx, cmd_name)

    def resolve_command(self, ctx: click.Context, args: list[str]):
        # Unknown subcommands get a close-match suggestion, as every other name in diffctl does.
        from diffctl.errors import suggest

        name = args[0] if args else ""
        if name and not name.startswith("-") and self.get_command(ctx, name) is None:
            ctx.fail(
                f"no such command {name!r}{suggest(name, self.list_commands(ctx))}; "
                f"valid: {', '.join(self.list_commands(ctx))}"
            )
        return super().resolve_command(ctx, args)
