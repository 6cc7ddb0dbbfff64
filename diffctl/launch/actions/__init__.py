"""The actions of launch; each module is imported when one of its names is first used."""

from .._private.lazy import lazy_exports

__getattr__, __dir__, __all__ = lazy_exports(__name__, globals(), {
    # processes
    '.execute_local': ('ExecuteLocal',),
    '.execute_process': ('ExecuteProcess',),
    # structure
    '.group_action': ('GroupAction',),
    '.include_launch_description': ('IncludeLaunchDescription',),
    '.opaque_function': ('OpaqueFunction',),
    '.opaque_coroutine': ('OpaqueCoroutine',),
    '.timer_action': ('TimerAction',),
    # events
    '.emit_event': ('EmitEvent',),
    '.register_event_handler': ('RegisterEventHandler',),
    '.unregister_event_handler': ('UnregisterEventHandler',),
    '.shutdown_action': ('Shutdown',),
    '.log_info': ('LogInfo',),
    # launch configurations
    '.declare_launch_argument': ('DeclareLaunchArgument',),
    '.set_launch_configuration': ('SetLaunchConfiguration',),
    '.unset_launch_configuration': ('UnsetLaunchConfiguration',),
    '.reset_launch_configurations': ('ResetLaunchConfigurations',),
    '.push_launch_configurations': ('PushLaunchConfigurations',),
    '.pop_launch_configurations': ('PopLaunchConfigurations',),
    # environment
    '.set_environment_variable': ('SetEnvironmentVariable',),
    '.append_environment_variable': ('AppendEnvironmentVariable',),
    '.unset_environment_variable': ('UnsetEnvironmentVariable',),
    '.reset_environment': ('ResetEnvironment',),
    '.push_environment': ('PushEnvironment',),
    '.pop_environment': ('PopEnvironment',),
})
