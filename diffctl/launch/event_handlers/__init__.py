"""Event handlers for launch's own events: process start, output and exit, completion, shutdown."""

from .._private.lazy import lazy_exports

__getattr__, __dir__, __all__ = lazy_exports(__name__, globals(), {
    '.on_process_start': ('OnProcessStart',),
    '.on_process_io': ('OnProcessIO',),
    '.on_process_exit': ('OnProcessExit',),
    '.on_execution_complete': ('OnExecutionComplete',),
    '.on_include_launch_description': ('OnIncludeLaunchDescription',),
    '.on_shutdown': ('OnShutdown',),
    '.event_named': ('event_named',),
})
