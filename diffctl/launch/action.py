"""`Action`: a launch description entity that does something when visited."""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING

from ._private.locate import creation_site, user_location
from .condition import Condition
from .launch_description_entity import LaunchDescriptionEntity

if TYPE_CHECKING:
    from .frontend.entity import Entity
    from .frontend.parser import Parser
    from .launch_context import LaunchContext


def _name_the_source(action: Action, problem: Exception) -> None:
    """Give an exception the location of the action it came from (`launch_location`), once: the markup's tag,
    else (for an error raised in no code of the user's, a substitution of launch's failing, say) the line of
    the Python launch file that made the action."""
    where = getattr(action, '_frontend_location', None)  # set by frontend.Parser.parse_action
    if where is None and user_location(problem) is None:
        where = getattr(action, '_made_at', None)
    if where is None or getattr(problem, 'launch_location', None) is not None:
        return
    try:
        problem.launch_location = where
        if where not in str(problem):
            problem.add_note(f'raised by the action at {where}')
    except (AttributeError, TypeError):
        pass  # an exception type that takes no attributes keeps its message


def _announce_completion(action: Action, context: LaunchContext) -> None:
    from .events.execution_complete import ExecutionComplete

    done = ExecutionComplete(action=action)
    if not context.would_handle_event(done):
        return  # nobody listens: no event at all
    future = action.get_asyncio_future()
    if future is None:
        context.emit_event_sync(done)
    else:
        future.add_done_callback(lambda _: context.emit_event_sync(done))


class Action(LaunchDescriptionEntity):
    """Something to do: visiting runs `execute` when the `condition` (if any) holds.

    When a registered handler would take an `ExecutionComplete` of this action, one is emitted after
    `execute`: straight away, or when the future of `get_asyncio_future()` is done.
    """

    def __init__(self, *, condition: Condition | None = None) -> None:
        self._guard = condition
        self._made_at = creation_site(self)

    @property
    def condition(self) -> Condition | None:
        return self._guard

    @staticmethod
    def parse(entity: Entity, parser: Parser):
        """`(Action, kwargs)` with the condition every tag may have (`if` or `unless`, not both).

        The actions' own `parse` methods start from it; it is no tag of its own.
        """
        from .conditions.if_condition import IfCondition
        from .conditions.unless_condition import UnlessCondition

        found = [
            (kind, entity.get_attr(attribute, optional=True))
            for attribute, kind in (('if', IfCondition), ('unless', UnlessCondition))
        ]
        given = [(kind, text) for kind, text in found if text is not None]
        if len(given) > 1:
            raise RuntimeError("if and unless conditions can't be used simultaneously")
        kwargs = {}
        for kind, text in given:
            kwargs['condition'] = kind(predicate_expression=parser.parse_substitution(text))
        return Action, kwargs

    def describe(self) -> str:
        return repr(self)

    def get_sub_entities(self) -> list[LaunchDescriptionEntity]:
        """The entities this action gives when executed, as far as known beforehand (none here)."""
        return []

    def describe_sub_entities(self) -> list[LaunchDescriptionEntity]:
        return [] if self._guard is not None else self.get_sub_entities()

    def describe_conditional_sub_entities(self) -> list[tuple[str, Iterable[LaunchDescriptionEntity]]]:
        if self._guard is None:
            return []
        return [(f'Conditionally included by {self.describe()}', self.get_sub_entities())]

    def execute(self, context: LaunchContext) -> list[LaunchDescriptionEntity] | None:
        """The action's work; the entities returned are visited next (nothing is done here)."""
        return None

    def visit(self, context: LaunchContext) -> list[LaunchDescriptionEntity] | None:
        try:
            if self._guard is not None and not self._guard.evaluate(context):
                return None
        except Exception as problem:
            _name_the_source(self, problem)
            raise
        try:
            return self.execute(context)
        except Exception as problem:
            _name_the_source(self, problem)
            raise
        finally:
            _announce_completion(self, context)
