"""diffctl's implementation of ros2/launch (Jazzy): the `launch` package, module for module.

Names are imported on first use, so that `import launch` costs little; `launch.actions`,
`launch.substitutions` and the others are reachable as attributes as in ros2/launch.
"""

from ._private.lazy import lazy_exports

__all__ = [
    'Action',
    'Condition',
    'Event',
    'EventHandler',
    'InvalidLaunchFileError',
    'LaunchContext',
    'LaunchDescription',
    'LaunchDescriptionEntity',
    'LaunchDescriptionSource',
    'LaunchIntrospector',
    'LaunchService',
    'SomeEntitiesType',
    'SomeEntitiesType_types_tuple',
    'SomeSubstitutionsType',
    'SomeSubstitutionsType_types_tuple',
    'Substitution',
    'actions',
    'conditions',
    'descriptions',
    'events',
    'frontend',
    'logging',
    'substitutions',
]

__getattr__, __dir__ = lazy_exports(__name__, globals(), {
    'actions': '.actions:',
    'conditions': '.conditions:',
    'descriptions': '.descriptions:',
    'events': '.events:',
    'frontend': '.frontend:',
    'logging': '.logging:',
    'substitutions': '.substitutions:',
    'Action': '.action',
    'Condition': '.condition',
    'Event': '.event',
    'EventHandler': '.event_handler',
    'InvalidLaunchFileError': '.invalid_launch_file_error',
    'LaunchContext': '.launch_context',
    'LaunchDescription': '.launch_description',
    'LaunchDescriptionEntity': '.launch_description_entity',
    'LaunchDescriptionSource': '.launch_description_source',
    'LaunchIntrospector': '.launch_introspector',
    'LaunchService': '.launch_service',
    'SomeEntitiesType': '.some_entities_type',
    'SomeEntitiesType_types_tuple': '.some_entities_type',
    'SomeSubstitutionsType': '.some_substitutions_type',
    'SomeSubstitutionsType_types_tuple': '.some_substitutions_type',
    'Substitution': '.substitution',
})
