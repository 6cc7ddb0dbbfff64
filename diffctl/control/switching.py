"""switch_controller request checking: strictness, lifecycle preconditions and interface conflicts (pure).

Semantics of controller_manager (Jazzy tip): STRICT aborts on any unknown name, any activation of a
controller that is not inactive, any deactivation of one that is not active; BEST_EFFORT drops those
entries with a warning and fails only when none of the requested names exist. AUTO and FORCE_AUTO are
not implemented upstream and behave as BEST_EFFORT. The interface check applies whatever the strictness:
command interfaces are exclusive, state interfaces shared.

Chaining (controller_manager's chained controllers): a controller that claims another's reference interfaces
("preceding") needs that "following" controller active, or activated in the same request (it is then
activated first); a following controller can not be deactivated while a preceding one that stays active
claims its references. The same holds for a controller reading another's exported state interfaces.
`chain_order` sorts controllers so preceding ones update before those they feed, and exporters of state
interfaces before their readers.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field

from diffctl.control.lifecycle import State

BEST_EFFORT, STRICT, AUTO, FORCE_AUTO = 1, 2, 3, 4
STRICTNESS_NAMES = {BEST_EFFORT: "BEST_EFFORT", STRICT: "STRICT", AUTO: "AUTO", FORCE_AUTO: "FORCE_AUTO"}


@dataclass(frozen=True)
class ControllerView:
    """What the check needs to know of one loaded controller."""

    state: State
    command_interfaces: Sequence[str] = ()  # resolved "joint/interface" names it would claim
    state_interfaces: Sequence[str] = ()


@dataclass
class SwitchPlan:
    ok: bool
    message: str = ""
    activate: list[str] = field(default_factory=list)
    deactivate: list[str] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)

    @property
    def empty(self) -> bool:
        return not self.activate and not self.deactivate


def plan_switch(
    controllers: Mapping[str, ControllerView],
    activate: Sequence[str],
    deactivate: Sequence[str],
    strictness: int,
    *,
    claimed: Mapping[str, str],
    command_available: Callable[[str], bool],
    state_available: Callable[[str], bool],
    reference_owner: Mapping[str, str] | None = None,
    state_owner: Mapping[str, str] | None = None,
) -> SwitchPlan:
    """Check a switch request; `claimed` maps command interface → controller currently holding it,
    `reference_owner` reference interface → the chainable controller exporting it, `state_owner` a
    controller's exported state interface → that controller."""
    reference_owner = reference_owner or {}
    state_owner = state_owner or {}
    warnings: list[str] = []
    if strictness in (AUTO, FORCE_AUTO):
        warnings.append(f"{STRICTNESS_NAMES[strictness]} strictness is not currently implemented; using BEST_EFFORT")
        strictness = BEST_EFFORT
    if strictness not in (BEST_EFFORT, STRICT):
        return SwitchPlan(False, f"unknown strictness {strictness} (1 BEST_EFFORT, 2 STRICT, 3 AUTO, 4 FORCE_AUTO)")
    strict = strictness == STRICT
    requested = list(dict.fromkeys([*activate, *deactivate]))
    if not requested:
        return SwitchPlan(True, "no controllers need to be activated or deactivated", warnings=warnings)

    act: list[str] = []
    deact: list[str] = []
    problems: list[str] = []
    for name in dict.fromkeys(deactivate):
        c = controllers.get(name)
        if c is None:
            problems.append(f"could not deactivate controller '{name}': it is not loaded")
        elif c.state is not State.ACTIVE:
            problems.append(f"could not deactivate controller '{name}': it is not active (state {c.state.value})")
        else:
            deact.append(name)
    for name in dict.fromkeys(activate):
        c = controllers.get(name)
        if c is None:
            problems.append(f"could not activate controller '{name}': it is not loaded")
        elif c.state is State.ACTIVE and name not in deact:
            problems.append(f"could not activate controller '{name}': it is already active")
        elif c.state is not State.INACTIVE and not (c.state is State.ACTIVE and name in deact):
            problems.append(f"could not activate controller '{name}': it is not configured (state {c.state.value})")
        else:
            act.append(name)
    if problems:
        if strict:
            return SwitchPlan(
                False, "; ".join(problems) + ". Aborting, no controller is switched! (STRICT)", warnings=warnings
            )
        warnings.extend(problems)
        if not any(n in controllers for n in requested):
            return SwitchPlan(False, "; ".join(problems), warnings=warnings)
    if not act and not deact:
        return SwitchPlan(True, "no controllers need to be activated or deactivated", warnings=warnings)

    # Interface check, whatever the strictness.
    leaving = set(deact)
    for name in deact:
        users = sorted(
            {c for i, c in claimed.items() if reference_owner.get(i) == name and c not in leaving and c != name}
        )
        if users:
            return SwitchPlan(
                False,
                f"could not deactivate controller '{name}': controller '{users[0]}' is chained in front of it "
                "(claims its reference interfaces); deactivate that one too",
                warnings=warnings,
            )
        readers = sorted(
            r for r, v in controllers.items()
            if v.state is State.ACTIVE and r not in leaving and r != name
            and any(state_owner.get(i) == name for i in v.state_interfaces)
        )  # fmt: skip
        if readers:
            return SwitchPlan(
                False,
                f"could not deactivate controller '{name}': controller '{readers[0]}' reads its exported state "
                "interfaces; deactivate that one too",
                warnings=warnings,
            )
    taken_by_new: dict[str, str] = {}
    for name in act:
        view = controllers[name]
        for iface in view.command_interfaces:
            following = reference_owner.get(iface)
            if (
                following is not None
                and following not in act
                and (following in leaving or not command_available(iface))
            ):
                return SwitchPlan(
                    False,
                    f"could not activate controller '{name}': it is chained in front of '{following}' "
                    f"(claims '{iface}'), which is not active; activate '{following}' first or in the same request",
                    warnings=warnings,
                )
            if following is None and not command_available(iface):
                return SwitchPlan(
                    False,
                    f"could not activate controller '{name}': command interface '{iface}' is not available",
                    warnings=warnings,
                )
            holder = claimed.get(iface)
            if holder is not None and holder != name and holder not in leaving:
                return SwitchPlan(
                    False,
                    f"could not activate controller '{name}': command interface '{iface}' is "
                    f"currently claimed by another controller '{holder}'",
                    warnings=warnings,
                )
            if iface in taken_by_new:
                return SwitchPlan(
                    False,
                    f"could not activate controller '{name}': command interface '{iface}' "
                    f"will be used by another controller that is being activated "
                    f"('{taken_by_new[iface]}')",
                    warnings=warnings,
                )
            taken_by_new[iface] = name
        for iface in view.state_interfaces:
            provider = state_owner.get(iface)
            if provider is not None and provider in act and provider != name:
                continue  # activated first, in this same request
            if not state_available(iface) or provider in leaving:
                return SwitchPlan(
                    False,
                    f"could not activate controller '{name}': state interface '{iface}' is not available",
                    warnings=warnings,
                )
    order = chain_order(act, controllers, reference_owner, state_owner=state_owner, following_first=True)
    return SwitchPlan(True, "", order, deact, warnings)


def chain_order(
    names: Sequence[str],
    controllers: Mapping[str, ControllerView],
    reference_owner: Mapping[str, str],
    *,
    state_owner: Mapping[str, str] | None = None,
    following_first: bool = False,
) -> list[str]:
    """`names` in update order (stable otherwise): a controller before the ones it is chained in front of, and
    after the ones whose exported state interfaces it reads. With `following_first`, activation order: the
    controllers a controller claims references of, or reads states of, before it."""
    state_owner = state_owner or {}
    before: dict[str, set[str]] = {n: set() for n in names}
    for n in names:
        view = controllers[n]
        for i in view.command_interfaces:
            owner = reference_owner.get(i)
            if owner in before and owner != n:
                (before[n] if following_first else before[owner]).add(owner if following_first else n)
        for i in view.state_interfaces:
            owner = state_owner.get(i)
            if owner in before and owner != n:
                before[n].add(owner)
    out: list[str] = []
    placed: set[str] = set()

    def place(n: str, path: tuple[str, ...]) -> None:
        if n in placed or n in path:
            return
        for m in names:
            if m in before[n]:
                place(m, (*path, n))
        placed.add(n)
        out.append(n)

    for n in names:
        place(n, ())
    return out
