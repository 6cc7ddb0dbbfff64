"""Where launch descriptions come from: Python launch files, markup launch files, or either kind."""

from .._private.lazy import lazy_exports

__getattr__, __dir__, __all__ = lazy_exports(__name__, globals(), {
    '.any_launch_description_source': ('AnyLaunchDescriptionSource',),
    '.any_launch_file_utilities': ('get_launch_description_from_any_launch_file',),
    '.python_launch_description_source': ('PythonLaunchDescriptionSource',),
    '.python_launch_file_utilities': (
        'get_launch_description_from_python_launch_file', 'load_python_launch_file_as_module',
        'InvalidPythonLaunchFileError'),
    '.frontend_launch_description_source': ('FrontendLaunchDescriptionSource',),
    '.frontend_launch_file_utilities': (
        'get_launch_description_from_frontend_launch_file', 'InvalidFrontendLaunchFileError'),
    '..invalid_launch_file_error': ('InvalidLaunchFileError',),
})
