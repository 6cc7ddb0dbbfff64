"""`Action`: a launch description entity that does something when visited."""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING

from .condition import Condition
from .launch_description_entity import LaunchDescriptionEntity

if TYPE_CHECKING:
    from .frontend.entity import Entity
    from .frontend.parser import Parser
    from .launch_context import LaunchContext


class Action(LaunchDescriptionEntity):
    """An intention to do something; visiting it runs `execute` unless its `condition` is false.

    After `execute`, an `ExecutionComplete` event is emitted when some handler wants it: at once, or when
    the action's asyncio future is done.
    """

    def __init__(self, *, condition: Condition | None = None) -> None:
        self.__condition = condition

    @staticmethod
    def parse(entity: Entity, parser: Parser):
        """(Action, kwargs) from the attributes every tag accepts: `if` and `unless`.

        Subclasses' `parse` start from it; it is not exposed as a tag itself.
        """
        from .conditions.if_condition import IfCondition
        from .conditions.unless_condition import UnlessCondition

        if_text = entity.get_attr('if', optional=True)
        unless_text = entity.get_attr('unless', optional=True)
        kwargs: dict[str, Condition] = {}
        if if_text is not None and unless_text is not None:
            raise RuntimeError("if and unless conditions can't be used simultaneously")
        if if_text is not None:
            kwargs['condition'] = IfCondition(predicate_expression=parser.parse_substitution(if_text))
        if unless_text is not None:
            kwargs['condition'] = UnlessCondition(predicate_expression=parser.parse_substitution(unless_text))
        return Action, kwargs

    @property
    def condition(self) -> Condition | None:
        """The condition guarding this action, if any."""
        return self.__condition

    def describe(self) -> str:
        return self.__repr__()

    def get_sub_entities(self) -> list[LaunchDescriptionEntity]:
        """Entities this action yields (none by default)."""
        return []

    def describe_sub_entities(self) -> list[LaunchDescriptionEntity]:
        return self.get_sub_entities() if self.condition is None else []

    def describe_conditional_sub_entities(self) -> list[tuple[str, Iterable[LaunchDescriptionEntity]]]:
        if self.condition is None:
            return []
        return [(f'Conditionally included by {self.describe()}', self.get_sub_entities())]

    def visit(self, context: LaunchContext) -> list[LaunchDescriptionEntity] | None:
        """Execute the action when its condition allows, then report its completion."""
        try:
            if self.__condition is not None and not self.__condition.evaluate(context):
                return None
        except Exception as exc:
            self.__locate(exc)
            raise
        try:
            return self.execute(context)
        except Exception as exc:
            self.__locate(exc)
            raise
        finally:
            self.__report_completion(context)

    def __locate(self, exc: Exception) -> None:
        # an action read from a markup file names its file and line in what it raises (see frontend.Parser)
        location = getattr(self, '_frontend_location', None)
        if location is not None and getattr(exc, 'launch_location', None) is None:
            try:
                exc.launch_location = location
                if location not in str(exc):
                    exc.add_note(f'raised by the action at {location}')
            except (AttributeError, TypeError):
                pass

    def __report_completion(self, context: LaunchContext) -> None:
        from .events.execution_complete import ExecutionComplete

        event = ExecutionComplete(action=self)
        if not context.would_handle_event(event):
            return
        future = self.get_asyncio_future()
        if future is None:
            context.emit_event_sync(event)
        else:
            future.add_done_callback(lambda _: context.emit_event_sync(event))

    def execute(self, context: LaunchContext) -> list[LaunchDescriptionEntity] | None:
        """What the action does; returns entities to visit next. Does nothing by default."""
        return None
