"""Markup frontends: the `Parser` they share, the `Entity` interface, the `expose_*` registry."""

from .._private.lazy import lazy_exports

__getattr__, __dir__, __all__ = lazy_exports(__name__, globals(), {
    '.': ('type_utils/',),
    '.parser': ('Parser', 'InvalidFrontendLaunchFileError'),
    '.entity': ('Entity',),
    '.expose': ('expose_action', 'expose_substitution'),
})
