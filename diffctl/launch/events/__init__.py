"""Events of the launch itself; those about processes are in `launch.events.process`."""

from .._private.lazy import lazy_exports

__getattr__, __dir__, __all__ = lazy_exports(__name__, globals(), {
    '.': ('process/',),
    '.shutdown': ('Shutdown',),
    '.timer_event': ('TimerEvent',),
    '.execution_complete': ('ExecutionComplete',),
    '.include_launch_description': ('IncludeLaunchDescription',),
    '.matchers': ('matches_action',),
})
