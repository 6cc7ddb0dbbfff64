"""The project's exception types: every user-facing failure is one of these, rendered as one line.

`DiffctlError.exit_code` is what the CLI exits with (2 for bad input, 1 for runtime failures such as a
spawner that could not activate its controller). `where` names the file, line and column or the field.
"""

from __future__ import annotations

import re
from collections.abc import Iterable


def suggest(word: str, candidates: Iterable[str], n: int = 3) -> str:
    """A ' (did you mean X?)' suffix listing close matches of `word`, or '' when nothing is close."""
    import difflib  # imported on a suggestion's first use: every command imports this module

    matches = difflib.get_close_matches(word, list(candidates), n=n, cutoff=0.6)
    if not matches:
        return ""
    return " (did you mean " + " or ".join(repr(m) for m in matches) + "?)"


def yaml_error(e: Exception, source: str, what: str = "malformed YAML") -> ConfigError:
    """A PyYAML error as one located ConfigError: file, line and column of the problem."""
    mark = getattr(e, "problem_mark", None)
    return ConfigError(
        f"{what}: {getattr(e, 'problem', None) or e}",
        source=source,
        line=mark.line + 1 if mark else None,
        column=mark.column + 1 if mark else None,
    )


_LXML_PLACE = re.compile(r"\s*, line \d+, column \d+\s*$")


def xml_error(e: Exception, source: str, what: str = "malformed XML", kind: type[ConfigError] | None = None
              ) -> ConfigError:
    """An lxml XMLSyntaxError as one located error: libxml2's text ends some messages with a newline before lxml
    appends ", line N, column M", so the place moves into the location and the text is its first line."""
    position = getattr(e, "position", None) or (getattr(e, "lineno", None), None)
    text = _LXML_PLACE.sub("", getattr(e, "msg", None) or str(e))
    text = " ".join(text.split()) or "unreadable XML"
    return (kind or DescriptionError)(f"{what}: {text}", source=source, line=position[0] or None,
                                      column=position[1] or None)


class DiffctlError(Exception):
    """Base of every error diffctl reports to a user."""

    exit_code = 2

    def __init__(
        self,
        message: str,
        *,
        source: str | None = None,
        line: int | None = None,
        column: int | None = None,
        field: str | None = None,
        hint: str | None = None,
    ) -> None:
        super().__init__(message)
        self.message = message
        self.source = source
        self.line = line
        self.column = column
        self.field = field
        self.hint = hint

    @property
    def where(self) -> str:
        parts = []
        if self.source:
            from diffctl.source_paths import user_source

            loc = user_source(str(self.source))  # the file under src/, not its link in diffctl's cache
            if self.line is not None:
                loc += f":{self.line}"
                if self.column is not None:
                    loc += f":{self.column}"
            parts.append(loc)
        if self.field:
            parts.append(self.field)
        return ": ".join(parts)

    def __str__(self) -> str:
        text = f"{self.where}: {self.message}" if self.where else self.message
        if self.hint:
            text += f" ({self.hint})" if not self.hint.startswith(" (") else self.hint
        return text


class ConfigError(DiffctlError):
    """Bad user input in a file or argument (YAML, launch file, parameters, CLI values)."""


class LaunchError(ConfigError):
    """A launch description that cannot be loaded or resolved."""


class DescriptionError(ConfigError):
    """An SDF world or model that cannot be loaded."""


class ParameterError(ConfigError):
    """A controller, hardware or node parameter with a missing or invalid value."""


class MessageError(ConfigError):
    """A message value or type that does not fit its definition."""


class BusError(DiffctlError):
    """A failure talking over the bus."""


class NoRouterError(BusError):
    """No Zenoh router answers at the configured endpoint."""


class ServiceTimeout(BusError):
    """A service did not answer in time."""

    exit_code = 1


class RuntimeFailure(DiffctlError):
    """Something that was asked for could not be done (a spawn that failed, a switch that was refused)."""

    exit_code = 1
