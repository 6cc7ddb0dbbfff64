"""`LaunchDescriptionSource`: a launch description, and where it comes from."""

from __future__ import annotations

import traceback
from typing import TYPE_CHECKING

from . import logging as launch_logging
from ._private.ros_names import default_text
from .utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from .utilities.perform_substitutions_impl import perform_substitutions

if TYPE_CHECKING:
    from .launch_context import LaunchContext
    from .launch_description import LaunchDescription
    from .some_substitutions_type import SomeSubstitutionsType


class LaunchDescriptionSource:
    """A launch description given as it is, or loaded from `location` when first needed.

    Loading is the subclasses' part: they implement `_get_launch_description(location)`, the extension
    point ROS 2's own sources use too. `location` may hold substitutions, performed when it is loaded;
    `method` says how the description is obtained ('interpreted python launch file', …).
    """

    def __repr__(self) -> str:
        return default_text(self)  # under ROS's module names, as ros2 launch --print shows it

    def __init__(
        self,
        launch_description: LaunchDescription | None = None,
        location: SomeSubstitutionsType = '<string>',
        method: str = 'unspecified mechanism from a script',
    ) -> None:
        self._description = launch_description
        self._where = normalize_to_list_of_substitutions(location)
        self._where_performed: str | None = None
        self._how = method

    @property
    def location(self) -> str:
        """Where from, once performed; before that, the substitutions' texts joined by ' + '."""
        if self._where_performed is not None:
            return self._where_performed
        return ' + '.join(str(piece) for piece in self._where)

    @property
    def method(self) -> str:
        return self._how

    def _get_launch_description(self, location: str) -> LaunchDescription:
        """Load the description from `location` (subclasses); this base only has the one it was given."""
        if self._description is None:
            raise RuntimeError(
                'LaunchDescriptionSource.get_launch_description(): called without launch description being set')
        return self._description

    def get_launch_description(self, context: LaunchContext) -> LaunchDescription:
        """The description, loaded once, from the location as performed in `context`."""
        if self._where_performed is None:
            self._where_performed = perform_substitutions(context, self._where)
        if self._description is None:
            self._description = self._get_launch_description(self._where_performed)
        return self._description

    def try_get_launch_description_without_context(self) -> LaunchDescription | None:
        """The description, loaded with a context of its own if need be; None when that fails."""
        if self._description is not None:
            return self._description
        from .launch_context import LaunchContext

        try:
            return self._get_launch_description(perform_substitutions(LaunchContext(), self._where))
        except Exception as problem:
            logger = launch_logging.get_logger('launch.launch_description_source')
            logger.debug(traceback.format_exc())
            logger.debug(f'Failed to load the launch file without a context: {problem}')
        return None
