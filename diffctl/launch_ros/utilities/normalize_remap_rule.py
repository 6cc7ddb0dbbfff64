"""Remapping rules `(from, to)` → tuples of substitutions."""

from __future__ import annotations

from collections.abc import Iterator

from diffctl.launch.utilities import ensure_argument_type, normalize_to_list_of_substitutions

from ..remap_rule_type import RemapRule, SomeRemapRule, SomeRemapRules


def normalize_remap_rule(remap_rule: SomeRemapRule) -> RemapRule:
    """One `(from, to)` pair (a tuple of two; TypeError otherwise)."""
    ensure_argument_type(remap_rule, tuple, "remap_rule")
    if len(remap_rule) != 2:
        raise TypeError(f"remap_rule must be a tuple of length 2, got length {len(remap_rule)}")
    src, dst = remap_rule
    return tuple(normalize_to_list_of_substitutions(src)), tuple(normalize_to_list_of_substitutions(dst))


def normalize_remap_rules(remap_rules: SomeRemapRules) -> Iterator[RemapRule]:
    """Each rule normalized, lazily (as launch_ros: a generator)."""
    for rule in remap_rules:
        yield normalize_remap_rule(rule)
