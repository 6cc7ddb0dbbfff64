"""Helpers for writing actions and substitutions: type checks, normalizing, performing substitutions."""

from .._private.lazy import lazy_exports

__getattr__, __dir__, __all__ = lazy_exports(__name__, globals(), {
    '.perform_substitutions_impl': ('perform_substitutions',),
    '.normalize_to_list_of_substitutions_impl': ('normalize_to_list_of_substitutions',),
    '.normalize_to_list_of_entities_impl': ('normalize_to_list_of_entities',),
    '.ensure_argument_type_impl': ('ensure_argument_type',),
    '.class_tools_impl': ('is_a', 'is_a_subclass', 'isclassinstance'),
    '.visit_all_entities_and_collect_futures_impl': ('visit_all_entities_and_collect_futures',),
    '.signal_management': ('AsyncSafeSignalManager',),
})
