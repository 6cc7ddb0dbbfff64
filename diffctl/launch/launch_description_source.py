"""`LaunchDescriptionSource`: a launch description and where it comes from."""

from __future__ import annotations

import traceback
from typing import TYPE_CHECKING

from . import logging as launch_logging
from .utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from .utilities.perform_substitutions_impl import perform_substitutions

if TYPE_CHECKING:
    from .launch_context import LaunchContext
    from .launch_description import LaunchDescription
    from .some_substitutions_type import SomeSubstitutionsType


class LaunchDescriptionSource:
    """A launch description given directly, or loaded on demand from `location` by a subclass.

    `location` may hold substitutions, performed when the description is first needed. `method` says how
    the description was obtained (e.g. 'interpreted python launch file').
    """

    def __init__(
        self,
        launch_description: LaunchDescription | None = None,
        location: SomeSubstitutionsType = '<string>',
        method: str = 'unspecified mechanism from a script',
    ) -> None:
        self.__launch_description = launch_description
        self.__expanded_location: str | None = None
        self.__location = normalize_to_list_of_substitutions(location)
        self.__method = method
        self.__logger = launch_logging.get_logger('launch.launch_description_source')

    def try_get_launch_description_without_context(self) -> LaunchDescription | None:
        """The description, loaded with a fresh context if needed; None when that fails."""
        if self.__launch_description is not None:
            return self.__launch_description
        from .launch_context import LaunchContext

        try:
            location = perform_substitutions(LaunchContext(), self.__location)
            return self._get_launch_description(location)
        except Exception as exc:
            self.__logger.debug(traceback.format_exc())
            self.__logger.debug('Failed to load the launch file without a context: ' + str(exc))
        return None

    def get_launch_description(self, context: LaunchContext) -> LaunchDescription:
        """The description, loaded (once) from the location performed in `context`."""
        if self.__expanded_location is None:
            self.__expanded_location = perform_substitutions(context, self.__location)
        if self.__launch_description is None:
            self.__launch_description = self._get_launch_description(self.__expanded_location)
        return self.__launch_description

    def _get_launch_description(self, location: str) -> LaunchDescription:
        """Load the description from `location`; subclasses implement it."""
        if self.__launch_description is None:
            raise RuntimeError(
                'LaunchDescriptionSource.get_launch_description(): called without launch description being set')
        return self.__launch_description

    @property
    def location(self) -> str:
        """The performed location once loaded; before, its substitutions as text joined by ' + '."""
        if self.__expanded_location is None:
            return ' + '.join(str(sub) for sub in self.__location)
        return self.__expanded_location

    @property
    def method(self) -> str:
        return self.__method
