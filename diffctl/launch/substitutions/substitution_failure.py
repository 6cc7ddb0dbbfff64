"""`SubstitutionFailure`: a substitution could not produce its text."""


class SubstitutionFailure(RuntimeError):
    """Raised by `perform` when a substitution cannot be resolved (missing variable, failed command, …)."""

    def __init__(self, msg):
        super().__init__(msg)
