"""The substitutions of launch; each module is imported when one of its names is first used."""

from .._private.lazy import lazy_exports

__getattr__, __dir__, __all__ = lazy_exports(__name__, globals(), {
    '.boolean_substitution': (
        'NotSubstitution', 'AndSubstitution', 'OrSubstitution', 'AnySubstitution', 'AllSubstitution'),
    '.equals_substitution': ('EqualsSubstitution',),
    '.not_equals_substitution': ('NotEqualsSubstitution',),
    '.if_else_substitution': ('IfElseSubstitution',),
    '.text_substitution': ('TextSubstitution',),
    '.path_join_substitution': ('PathJoinSubstitution', 'PathSubstitution'),
    '.launch_configuration': ('LaunchConfiguration',),
    '.local_substitution': ('LocalSubstitution',),
    '.environment_variable': ('EnvironmentVariable',),
    '.python_expression': ('PythonExpression',),
    '.command': ('Command',),
    '.file_content': ('FileContent',),
    '.find_executable': ('FindExecutable',),
    '.anon_name': ('AnonName',),
    '.this_launch_file': ('ThisLaunchFile',),
    '.this_launch_file_dir': ('ThisLaunchFileDir',),
    '.launch_log_dir': ('LaunchLogDir',),
    '.substitution_failure': ('SubstitutionFailure',),
})
