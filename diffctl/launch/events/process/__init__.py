"""Events about the processes ExecuteLocal / ExecuteProcess run, and the events sent to them."""

from ..._private.lazy import lazy_exports

__getattr__, __dir__, __all__ = lazy_exports(__name__, globals(), {
    # what a running process reports
    '.running_process_event': ('RunningProcessEvent',),
    '.process_started': ('ProcessStarted',),
    '.process_exited': ('ProcessExited',),
    '.process_io': ('ProcessIO',),
    '.process_stdin': ('ProcessStdin',),
    '.process_stdout': ('ProcessStdout',),
    '.process_stderr': ('ProcessStderr',),
    # what is asked of processes
    '.process_targeted_event': ('ProcessTargetedEvent',),
    '.shutdown_process': ('ShutdownProcess',),
    '.signal_process': ('SignalProcess',),
    '.process_matchers': ('matches_pid', 'matches_name', 'matches_executable'),
})
