"""`InvalidLaunchFileError`: no loader could make sense of a launch file."""

from __future__ import annotations

from collections.abc import Sequence


class InvalidLaunchFileError(Exception):
    """Raised when a launch file cannot be loaded; carries what each loader that tried it raised."""

    def __init__(self, extension: str = '', *, likely_errors: Sequence[BaseException] | None = None):
        self._extension = extension
        self._likely_errors = likely_errors
        if not extension or not likely_errors:
            self._error_message = 'The launch file may have a syntax error, or its format is unknown'
            return
        plural = 'multiple exceptions' if len(likely_errors) > 1 else 'exception'
        lines = [f'Caught {plural} when trying to load file of format [{extension}]:']
        lines += [f' - {type(e).__name__}: {e}' for e in likely_errors]
        self._error_message = '\n'.join(lines)
        self.__cause__ = likely_errors[0]

    def __str__(self) -> str:
        return self._error_message
