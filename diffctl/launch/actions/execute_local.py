"""`ExecuteLocal`: run a process on this machine, report its events, shut it down with escalation."""

from __future__ import annotations

import asyncio
import os
import signal
import traceback
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from .. import logging as launch_logging
from .._private.spawning import spawner_for
from ..action import Action
from ..conditions.evaluate_condition_expression_impl import evaluate_condition_expression
from ..event_handler import EventHandler
from ..event_handlers.on_process_exit import OnProcessExit
from ..event_handlers.on_process_io import OnProcessIO
from ..event_handlers.on_process_start import OnProcessStart
from ..event_handlers.on_shutdown import OnShutdown
from ..events.matchers import matches_action
from ..events.process.process_exited import ProcessExited
from ..events.process.process_started import ProcessStarted
from ..events.process.process_stderr import ProcessStderr
from ..events.process.process_stdout import ProcessStdout
from ..events.process.shutdown_process import ShutdownProcess
from ..events.process.signal_process import SignalProcess
from ..substitutions.launch_configuration import LaunchConfiguration
from ..substitutions.python_expression import PythonExpression
from ..utilities.class_tools_impl import is_a_subclass
from ..utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from ..utilities.perform_substitutions_impl import perform_substitutions
from ..utilities.type_utils import normalize_typed_substitution, perform_typed_substitution
from .emit_event import EmitEvent
from .opaque_function import OpaqueFunction
from .timer_action import TimerAction

if TYPE_CHECKING:
    import logging

    from ..descriptions.executable import Executable
    from ..event import Event
    from ..events.process.process_io import ProcessIO
    from ..launch_context import LaunchContext
    from ..launch_description_entity import LaunchDescriptionEntity
    from ..some_entities_type import SomeEntitiesType
    from ..some_substitutions_type import SomeSubstitutionsType

_ESCALATION = "process[{}] failed to terminate '{}' seconds after receiving '{}', escalating to '{}'"


class _Output:
    """One output stream of a process, logged line by line.

    Partial lines wait for the rest. Cached, the whole output is kept for `get_stdout()`; otherwise only
    the unfinished line is. Once closed (the process ended for good), chunks are logged as they come.
    """

    def __init__(self, cached: bool) -> None:
        self.cached = cached
        self.text = ''
        self.logged_up_to = 0  # cached: end of the last logged line
        self.closed = False

    def add(self, chunk: str, log: Callable[[str], None]) -> None:
        if self.closed and not self.cached:
            log(chunk)
            return
        self.text += chunk
        start = self.logged_up_to if self.cached else 0
        end = self.text.rfind(os.linesep, start)
        if end < 0:
            return
        complete = self.text[start:end]
        for line in complete.split(os.linesep):
            log(line)
        end += len(os.linesep)
        if self.cached:
            self.logged_up_to = end
        else:
            self.text = self.text[end:]

    def flush(self, log: Callable[[str], None], *, final: bool) -> None:
        """Log what is left of an unfinished line; `final`: no respawn will write here again."""
        if self.cached:
            rest = self.text[self.logged_up_to:]
            for line in rest.splitlines(keepends=True):
                log(line)
            self.logged_up_to = len(self.text)
            return
        if self.text:
            log(self.text)
        self.text = ''
        self.closed = self.closed or final


class _Sink:
    """Turns a child's output into ProcessStdout / ProcessStderr events, none before ProcessStarted."""

    def __init__(self, context: LaunchContext, event_args: dict[str, Any]) -> None:
        self.context = context
        self.event_args = event_args
        self.early: list[tuple[type, bytes]] | None = []  # output read before the start was reported

    def started(self) -> None:
        early, self.early = self.early, None
        for kind, data in early or ():
            self.context.emit_event_sync(kind(text=data, **self.event_args))

    def __emit(self, kind: type, data: bytes) -> None:
        if self.early is not None:
            self.early.append((kind, data))
        else:
            self.context.emit_event_sync(kind(text=data, **self.event_args))

    def on_stdout(self, data: bytes) -> None:
        self.__emit(ProcessStdout, data)

    def on_stderr(self, data: bytes) -> None:
        self.__emit(ProcessStderr, data)


class ExecuteLocal(Action):
    """Runs the process an `Executable` describes, on this machine.

    Once executed it handles `ShutdownProcess` and `Shutdown` (SIGINT, then SIGTERM after
    `sigterm_timeout` and SIGKILL after `sigkill_timeout` more seconds), `SignalProcess` and `ProcessStdin`
    events for its process, and emits `ProcessStarted`, `ProcessStdout`/`ProcessStderr` and
    `ProcessExited`. On a launch shutdown due to SIGINT with a terminal, it sends no SIGINT itself: the
    terminal already did (diffctl's launcher forwards the SIGINT to its children's process groups).

    - `output`: where output goes ('log', 'screen', 'both', 'own_log', 'full', or a dict; see
      `launch.logging.get_output_loggers`); the `OVERRIDE_LAUNCH_PROCESS_OUTPUT` environment variable
      overrides it. `output_format` formats each line (`{line}`, `{this}`).
    - `emulate_tty`: run with a pseudo-terminal; the `emulate_tty` launch configuration overrides it.
    - `cached_output`: keep the output for `get_stdout()` / `get_stderr()`.
    - `log_cmd`: log the final command before starting it.
    - `on_exit`: entities, or a callable `(ProcessExited, context)`, for when the process exits.
    - `respawn` (bool or substitution), `respawn_delay` (s), `respawn_max_retries` (negative: no limit):
      start the process again when it exits while the launch is not shutting down.
    """

    def __init__(
        self,
        *,
        process_description: Executable,
        shell: bool = False,
        sigterm_timeout: SomeSubstitutionsType = LaunchConfiguration('sigterm_timeout', default=5),
        sigkill_timeout: SomeSubstitutionsType = LaunchConfiguration('sigkill_timeout', default=5),
        emulate_tty: bool = False,
        output: SomeSubstitutionsType = 'log',
        output_format: str = '[{this.process_description.final_name}] {line}',
        cached_output: bool = False,
        log_cmd: bool = False,
        on_exit: SomeEntitiesType | Callable[[ProcessExited, LaunchContext], SomeEntitiesType | None] | None = None,
        respawn: bool | SomeSubstitutionsType = False,
        respawn_delay: float | None = None,
        respawn_max_retries: int = -1,
        **kwargs: Any,
    ) -> None:
        super().__init__(**kwargs)
        self.__process_description = process_description
        self.__shell = shell
        self.__sigterm_timeout = normalize_to_list_of_substitutions(sigterm_timeout)
        self.__sigkill_timeout = normalize_to_list_of_substitutions(sigkill_timeout)
        self.__emulate_tty = emulate_tty
        chosen = os.environ.get('OVERRIDE_LAUNCH_PROCESS_OUTPUT', output)
        self.__output = chosen if isinstance(chosen, dict) else normalize_to_list_of_substitutions(chosen)
        self.__output_format = output_format
        self.__log_cmd = log_cmd
        self.__cached_output = cached_output
        self.__on_exit = on_exit
        self.__respawn = normalize_typed_substitution(respawn, bool)
        self.__respawn_delay = respawn_delay
        self.__respawn_max_retries = respawn_max_retries
        self.__respawn_retries = 0

        self.__process_event_args: dict[str, Any] | None = None
        self._subprocess_protocol: Any | None = None
        self._subprocess_transport: Any | None = None
        self.__completed_future: asyncio.Future | None = None
        self.__shutdown_future: asyncio.Future | None = None
        self.__sigterm_timer: TimerAction | None = None
        self.__sigkill_timer: TimerAction | None = None
        self.__stdout = _Output(cached_output)
        self.__stderr = _Output(cached_output)
        self.__logger = launch_logging.get_logger('launch.actions.execute_local')
        self.__stdout_logger: logging.Logger | None = None
        self.__stderr_logger: logging.Logger | None = None
        self.__executed = False

    @property
    def process_description(self) -> Executable:
        return self.__process_description

    @property
    def shell(self) -> bool:
        return self.__shell

    @property
    def emulate_tty(self) -> bool:
        return self.__emulate_tty

    @property
    def sigkill_timeout(self):
        return self.__sigkill_timeout

    @property
    def sigterm_timeout(self):
        return self.__sigterm_timeout

    @property
    def output(self):
        return self.__output

    @property
    def process_details(self) -> dict[str, Any] | None:
        """name, cmd, cwd, env, pid (and the action) of the process; None before execution."""
        return self.__process_event_args

    def get_sub_entities(self) -> list[LaunchDescriptionEntity]:
        return self.__on_exit if isinstance(self.__on_exit, list) else []

    # ---- shutting the process down -------------------------------------------------------------------------

    def _shutdown_process(self, context: LaunchContext, *, send_sigint: bool) -> list[Action] | None:
        if self.__shutdown_future is None or self.__shutdown_future.done():
            return None  # not executed, or already shutting down
        if self.__completed_future is None or self.__completed_future.done():
            self.__shutdown_future.set_result(None)  # over (or never to start)
            return None
        if self.process_details is None or self._subprocess_transport is None:
            # not started yet: shut it down as soon as it is
            context.register_event_handler(OnProcessStart(
                on_start=lambda event, context: self._shutdown_process(context, send_sigint=send_sigint)))
            return None
        self.__shutdown_future.set_result(None)
        context.extend_locals({'process_name': self.process_details['name']})
        actions = self.__escalation_timers()
        if send_sigint:
            actions.append(EmitEvent(event=SignalProcess(
                signal_number=signal.SIGINT, process_matcher=matches_action(self))))
        return actions

    def __escalation_timers(self) -> list[Action]:
        def report(context: LaunchContext, message: str, timeout: list[Any]) -> None:
            self.__logger.error(message.format(
                context.locals.process_name, perform_substitutions(context, timeout)))

        term_after = self.__sigterm_timeout
        kill_after = [PythonExpression(('float(', *self.__sigterm_timeout, ') + float(', *self.__sigkill_timeout, ')'))]
        self.__sigterm_timer = TimerAction(
            period=term_after,
            actions=[
                OpaqueFunction(function=report, args=(_ESCALATION.format('{}', '{}', 'SIGINT', 'SIGTERM'), term_after)),
                EmitEvent(event=SignalProcess(signal_number=signal.SIGTERM, process_matcher=matches_action(self))),
            ],
            cancel_on_shutdown=False,
        )
        self.__sigkill_timer = TimerAction(
            period=kill_after,
            actions=[
                OpaqueFunction(
                    function=report, args=(_ESCALATION.format('{}', '{}', 'SIGTERM', 'SIGKILL'), kill_after)),
                EmitEvent(event=SignalProcess(signal_number='SIGKILL', process_matcher=matches_action(self))),
            ],
            cancel_on_shutdown=False,
        )
        return [self.__sigterm_timer, self.__sigkill_timer]

    def __on_shutdown_process_event(self, context: LaunchContext) -> list[Action] | None:
        if not context.locals.event.process_matcher(self):
            return None
        return self._shutdown_process(context, send_sigint=True)

    def __on_signal_process_event(self, context: LaunchContext) -> None:
        event = context.locals.event
        if not event.process_matcher(self):
            return None
        if self.process_details is None:
            raise RuntimeError('Signal event received before execution.')
        if self._subprocess_transport is None:
            raise RuntimeError('Signal event received before subprocess transport available.')
        name = self.process_details['name']
        if self._subprocess_protocol.complete.done():
            self.__logger.debug(
                f"signal '{event.signal_name}' not set to '{name}' because it is already closing")
            return None
        self.__logger.info(f"sending signal '{event.signal_name}' to process[{name}]")
        try:
            if event.signal_name == 'SIGKILL':
                self._subprocess_transport.kill()
            else:
                self._subprocess_transport.send_signal(event.signal)
        except ProcessLookupError:
            self.__logger.debug(
                f"signal '{event.signal_name}' not sent to '{name}' because it has closed already")
        return None

    def __on_shutdown(self, event: Event, context: LaunchContext) -> list[Action] | None:
        # with a terminal, a SIGINT shutdown means the processes got the SIGINT already
        return self._shutdown_process(context, send_sigint=not event.due_to_sigint or context.noninteractive)

    # ---- output --------------------------------------------------------------------------------------------

    def __on_process_stdin(self, event: ProcessIO) -> None:
        self.__logger.warning(f"in ExecuteProcess('{id(self)}').__on_process_stdin_event()")
        return None

    def __line_logger(self, logger: logging.Logger) -> Callable[[str], None]:
        return lambda line: logger.info(self.__output_format.format(line=line, this=self))

    def __on_stdout(self, event: ProcessIO) -> None:
        self.__stdout.add(event.text.decode(errors='replace'), self.__line_logger(self.__stdout_logger))

    def __on_stderr(self, event: ProcessIO) -> None:
        self.__stderr.add(event.text.decode(errors='replace'), self.__line_logger(self.__stderr_logger))

    def __flush_output(self, event: Event, context: LaunchContext) -> None:
        final = self.__shutdown_future is None or self.__shutdown_future.done()
        self.__stdout.flush(self.__line_logger(self.__stdout_logger), final=final)
        self.__stderr.flush(self.__line_logger(self.__stderr_logger), final=final)

    # ---- running -------------------------------------------------------------------------------------------

    def __cleanup(self) -> None:
        for timer in (self.__sigterm_timer, self.__sigkill_timer):
            if timer is not None:
                timer.cancel()
        if self._subprocess_transport is not None:
            self._subprocess_transport.close()
        self.__completed_future.set_result(None)

    async def __execute_process(self, context: LaunchContext) -> None:
        from diffctl.supervision import SpawnRequest

        args = self.__process_event_args
        if args is None:
            raise RuntimeError('process_event_args unexpectedly None')
        cmd, cwd, env = args['cmd'], args['cwd'], args['env']
        if self.__log_cmd:
            self.__logger.info("process details: cmd='{}', cwd='{}', custom_env?={}".format(
                ' '.join(part for part in cmd if part.strip()), cwd, 'True' if env is not None else 'False'))
        emulate_tty = self.__emulate_tty
        if 'emulate_tty' in context.launch_configurations:
            emulate_tty = evaluate_condition_expression(
                context, normalize_to_list_of_substitutions(context.launch_configurations['emulate_tty']))
        process_logger = launch_logging.get_logger(args['name'])
        request = SpawnRequest(cmd=list(cmd), cwd=cwd, env=env, shell=self.__shell, emulate_tty=emulate_tty,
                               name=args['name'])
        sink = _Sink(context, args)
        try:
            child = await spawner_for(context).spawn(request, sink)
        except Exception:
            self.__logger.error(f'exception occurred while executing process:\n{traceback.format_exc()}')
            self.__cleanup()
            return
        # asyncio's subprocess transport reports a start a few loop iterations after the fork (its pipes are
        # connected first); code that registers an OnProcessStart right after the launch visited this action
        # (launch_pytest's tools.wait_for_start) relies on that
        for _ in range(3):
            await asyncio.sleep(0)
        pid = child.get_pid()
        process_logger.info(f'process started with pid [{pid}]')
        args['pid'] = pid
        self._subprocess_transport = child
        self._subprocess_protocol = child
        await context.emit_event(ProcessStarted(**args))
        sink.started()

        returncode = await child.complete
        if returncode == 0:
            process_logger.info(f'process has finished cleanly [pid {pid}]')
        else:
            process_logger.error("process has died [pid {}, exit code {}, cmd '{}'].".format(
                pid, returncode, ' '.join(part for part in cmd if part.strip())))
        await context.emit_event(ProcessExited(returncode=returncode, **args))

        if self.__should_respawn(context):
            self.__respawn_retries += 1
            if self.__respawn_delay is not None and self.__respawn_delay > 0.0:
                # wait, but stop waiting when the launch shuts the process down
                await asyncio.wait((self.__shutdown_future,), timeout=self.__respawn_delay)
            if not self.__shutdown_future.done():
                child.close()
                context.asyncio_loop.create_task(self.__execute_process(context))
                return
        self.__cleanup()

    def __should_respawn(self, context: LaunchContext) -> bool:
        return (
            not context.is_shutdown
            and self.__shutdown_future is not None
            and not self.__shutdown_future.done()
            and bool(self.__respawn)
            and (self.__respawn_max_retries < 0 or self.__respawn_retries < self.__respawn_max_retries)
        )

    def prepare(self, context: LaunchContext) -> None:
        """Perform the substitutions of the description; fills `process_details` (without the pid)."""
        self.__process_description.prepare(context, self)
        description = self.__process_description
        self.__process_event_args = {
            'action': self,
            'name': description.final_name,
            'cmd': description.final_cmd,
            'cwd': description.final_cwd,
            'env': description.final_env,
        }
        self.__respawn = perform_typed_substitution(context, self.__respawn, bool)

    def execute(self, context: LaunchContext) -> list[LaunchDescriptionEntity] | None:
        """Prepare, register the process's event handlers, and start it in a task on the launch loop."""
        self.prepare(context)
        name = self.__process_description.final_name
        if self.__executed:
            raise RuntimeError(f"ExecuteLocal action '{name}': executed more than once: {self.describe()}")
        self.__executed = True
        if context.is_shutdown:
            return None  # the launch is ending: do not start anything

        event_handlers = [
            EventHandler(
                matcher=lambda event: is_a_subclass(event, ShutdownProcess),
                entities=OpaqueFunction(function=self.__on_shutdown_process_event),
            ),
            EventHandler(
                matcher=lambda event: is_a_subclass(event, SignalProcess),
                entities=OpaqueFunction(function=self.__on_signal_process_event),
            ),
            OnProcessIO(
                target_action=self,
                on_stdin=self.__on_process_stdin,
                on_stdout=self.__on_stdout,
                on_stderr=self.__on_stderr,
            ),
            OnShutdown(on_shutdown=self.__on_shutdown),
            OnProcessExit(target_action=self, on_exit=self.__on_exit),
            OnProcessExit(target_action=self, on_exit=self.__flush_output),
        ]
        for handler in event_handlers:
            context.register_event_handler(handler)
        try:
            self.__completed_future = context.asyncio_loop.create_future()
            self.__shutdown_future = context.asyncio_loop.create_future()
            self.__logger = launch_logging.get_logger(name)
            output = self.__output if isinstance(self.__output, dict) else perform_substitutions(context, self.__output)
            self.__stdout_logger, self.__stderr_logger = launch_logging.get_output_loggers(name, output)
            context.asyncio_loop.create_task(self.__execute_process(context))
        except Exception:
            for handler in event_handlers:
                context.unregister_event_handler(handler)
            raise
        return None

    def get_asyncio_future(self) -> asyncio.Future | None:
        return self.__completed_future

    def get_stdout(self) -> str:
        """All the process's standard output so far (needs `cached_output=True`)."""
        if not self.__cached_output:
            raise RuntimeError(
                f"cached output must be true to be able to get stdout, proc '{self.__process_description.name}'")
        return self.__stdout.text

    def get_stderr(self) -> str:
        """All the process's standard error so far (needs `cached_output=True`)."""
        if not self.__cached_output:
            raise RuntimeError(
                f"cached output must be true to be able to get stderr, proc '{self.__process_description.name}'")
        return self.__stderr.text

    @property
    def return_code(self) -> int | None:
        """The exit code, None while the process runs (or before it starts)."""
        if self._subprocess_transport is None:
            return None
        return self._subprocess_transport.get_returncode()
