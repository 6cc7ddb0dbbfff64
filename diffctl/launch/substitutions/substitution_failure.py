"""`SubstitutionFailure`, the error of a substitution that has no value."""


class SubstitutionFailure(RuntimeError):
    """A substitution could not be performed: an unset configuration, a failing command, a missing file."""

    def __init__(self, msg) -> None:
        super().__init__(msg)
