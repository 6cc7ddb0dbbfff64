"""diffctl's implementation of ros2/launch (Jazzy): the `launch` package, module for module.

Names are imported on first use, so that `import launch` costs little; `launch.actions`,
`launch.substitutions` and the others are reachable as attributes as in ros2/launch.
"""

from ._private.lazy import lazy_exports

__getattr__, __dir__, __all__ = lazy_exports(__name__, globals(), {
    '.': ('actions/', 'conditions/', 'descriptions/', 'events/', 'frontend/', 'logging/', 'substitutions/'),
    '.launch_service': ('LaunchService',),
    '.launch_context': ('LaunchContext',),
    '.launch_description': ('LaunchDescription',),
    '.launch_description_entity': ('LaunchDescriptionEntity',),
    '.launch_description_source': ('LaunchDescriptionSource',),
    '.launch_introspector': ('LaunchIntrospector',),
    '.invalid_launch_file_error': ('InvalidLaunchFileError',),
    '.action': ('Action',),
    '.condition': ('Condition',),
    '.substitution': ('Substitution',),
    '.event': ('Event',),
    '.event_handler': ('EventHandler',),
    '.some_entities_type': ('SomeEntitiesType', 'SomeEntitiesType_types_tuple'),
    '.some_substitutions_type': ('SomeSubstitutionsType', 'SomeSubstitutionsType_types_tuple'),
})
