"""`ExecuteLocal`: run a process on this machine, report what it does, and stop it with escalation."""

from __future__ import annotations

import asyncio
import os
import signal
import traceback
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from .. import logging as launch_logging
from .._private.handler_index import addressed_to
from .._private.process_output import HeldBack, LineLog
from .._private.spawning import spawner_for
from ..action import Action
from ..conditions.evaluate_condition_expression_impl import evaluate_condition_expression
from ..event_handler import EventHandler, _takes_only
from ..event_handlers.on_process_exit import OnProcessExit
from ..event_handlers.on_process_io import OnProcessIO
from ..event_handlers.on_process_start import OnProcessStart
from ..event_handlers.on_shutdown import OnShutdown
from ..events.matchers import matches_action
from ..events.process.process_exited import ProcessExited
from ..events.process.process_started import ProcessStarted
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

OnExit = Callable[[ProcessExited, 'LaunchContext'], 'SomeEntitiesType | None']


class _Unsaid(str):
    """The text of a default, told apart from the same text given."""


# `output` when none is given: the LaunchService's `output_default` (ROS's 'log' unless it says otherwise)
_OUTPUT_UNSAID = _Unsaid('log')


def _shown(cmd: list[str]) -> str:
    """A command line for messages: its words, blank ones left out."""
    return ' '.join(word for word in cmd if word.strip())


class _Run:
    """What one execution of the action has going: futures, loggers, the child, the escalation timers."""

    def __init__(self, loop: asyncio.AbstractEventLoop, name: str) -> None:
        self.done = loop.create_future()  # the process is over for good (no respawn to come)
        self.stopping = loop.create_future()  # a shutdown of the process has begun
        self.log = launch_logging.get_logger(name)
        self.out: logging.Logger | None = None
        self.err: logging.Logger | None = None
        self.child: Any | None = None
        self.timers: list[TimerAction] = []
        self.escalation: list[asyncio.TimerHandle] = []
        self.respawns = 0


class ExecuteLocal(Action):
    """Runs the process an `Executable` describes, on this machine.

    Once executed it emits ProcessStarted, ProcessStdout / ProcessStderr and ProcessExited, and acts on
    ShutdownProcess, SignalProcess and the launch's Shutdown: SIGINT first, SIGTERM `sigterm_timeout`
    seconds later, SIGKILL after `sigkill_timeout` more. On a shutdown caused by a SIGINT with a terminal
    it sends no SIGINT of its own, the terminal did (diffctl's launcher passes that SIGINT on to every
    process group, as a terminal does to its own).

    - `output`: 'log', 'screen', 'both', 'own_log', 'full' or a dict (see
      `launch.logging.get_output_loggers`), overridden by `OVERRIDE_LAUNCH_PROCESS_OUTPUT`; not given, the
      LaunchService's `output_default` ('log', as in ROS, unless it was given another); `output_format`
      makes each line (`{line}`, `{this}` the action).
    - `emulate_tty`: a pseudo-terminal for the process (the `emulate_tty` launch configuration wins).
    - `cached_output`: keep all output for `get_stdout()` / `get_stderr()`.
    - `log_cmd`: log the final command line before starting.
    - `on_exit`: entities, or a callable `(ProcessExited, context)`, for when the process exits.
    - `respawn` (a boolean, possibly a substitution), `respawn_delay` (seconds), `respawn_max_retries`
      (negative: no limit): start again after an exit while the launch is not shutting down.
    """

    def __init__(
        self,
        *,
        process_description: Executable,
        shell: bool = False,
        sigterm_timeout: SomeSubstitutionsType = LaunchConfiguration('sigterm_timeout', default=5),
        sigkill_timeout: SomeSubstitutionsType = LaunchConfiguration('sigkill_timeout', default=5),
        emulate_tty: bool = False,
        output: SomeSubstitutionsType = _OUTPUT_UNSAID,
        output_format: str = '[{this.process_description.final_name}] {line}',
        cached_output: bool = False,
        log_cmd: bool = False,
        on_exit: SomeEntitiesType | OnExit | None = None,
        respawn: bool | SomeSubstitutionsType = False,
        respawn_delay: float | None = None,
        respawn_max_retries: int = -1,
        **kwargs: Any,
    ) -> None:
        super().__init__(**kwargs)
        self._description = process_description
        self._shell = shell
        self._emulate_tty = emulate_tty
        self._term_after = normalize_to_list_of_substitutions(sigterm_timeout)
        self._kill_after = normalize_to_list_of_substitutions(sigkill_timeout)
        chosen = os.environ.get('OVERRIDE_LAUNCH_PROCESS_OUTPUT', output)
        self._output_said = chosen is not _OUTPUT_UNSAID
        self._output = chosen if isinstance(chosen, dict) else normalize_to_list_of_substitutions(chosen)
        self._line_format = output_format
        self._log_cmd = log_cmd
        self._keep_output = cached_output
        self._on_exit = on_exit
        self._respawn = normalize_typed_substitution(respawn, bool)
        self._respawn_delay = respawn_delay
        self._respawn_limit = respawn_max_retries
        self._details: dict[str, Any] | None = None
        self._streams = {'stdout': LineLog(cached_output), 'stderr': LineLog(cached_output)}
        self._run: _Run | None = None
        self._executed = False

    @property
    def process_description(self) -> Executable:
        return self._description

    @property
    def shell(self) -> bool:
        return self._shell

    @property
    def emulate_tty(self) -> bool:
        return self._emulate_tty

    @property
    def sigterm_timeout(self):
        return self._term_after

    @property
    def sigkill_timeout(self):
        return self._kill_after

    @property
    def output(self):
        return self._output

    @property
    def process_details(self) -> dict[str, Any] | None:
        """action, name, cmd, cwd, env of the process once prepared, and its pid once started; else None."""
        return self._details

    @property
    def return_code(self) -> int | None:
        """The exit code; None before the process started and while it runs."""
        child = None if self._run is None else self._run.child
        return None if child is None else child.get_returncode()

    def get_sub_entities(self) -> list[LaunchDescriptionEntity]:
        return self._on_exit if isinstance(self._on_exit, list) else []

    def get_asyncio_future(self) -> asyncio.Future | None:
        return None if self._run is None else self._run.done

    def get_stdout(self) -> str:
        """The process's standard output so far (with `cached_output=True` only)."""
        return self._kept('stdout')

    def get_stderr(self) -> str:
        """The process's standard error so far (with `cached_output=True` only)."""
        return self._kept('stderr')

    def _kept(self, stream: str) -> str:
        if not self._keep_output:
            raise RuntimeError(
                f"cached output must be true to be able to get {stream}, proc '{self._description.name}'")
        return self._streams[stream].text

    # ---- starting ----------------------------------------------------------------------------------------------

    def prepare(self, context: LaunchContext) -> None:
        """Perform the description's substitutions; `process_details` is filled in, but for the pid."""
        self._description.prepare(context, self)
        made = self._description
        self._details = {
            'action': self, 'name': made.final_name, 'cmd': made.final_cmd, 'cwd': made.final_cwd,
            'env': made.final_env,
        }
        self._respawn = perform_typed_substitution(context, self._respawn, bool)

    def _handlers(self) -> list:
        """The handlers the action needs while its process may run (registered in this order)."""
        # A ShutdownProcess or SignalProcess is taken by the handler of the process it targets only: with every
        # process's handler asked about every such event, stopping N processes cost N² handler visits. Those
        # handlers take no other events, and those for `matches_action(self)` concern this action alone.
        to_me = addressed_to(self)
        on_shutdown = _takes_only(EventHandler(
            matcher=lambda event: is_a_subclass(event, ShutdownProcess) and event.process_matcher(self),
            entities=OpaqueFunction(function=self._on_shutdown_process),
        ), ShutdownProcess)
        on_signal = _takes_only(EventHandler(
            matcher=lambda event: is_a_subclass(event, SignalProcess) and event.process_matcher(self),
            entities=OpaqueFunction(function=self._on_signal_process),
        ), SignalProcess)
        if to_me is not None:
            on_shutdown._only_about = on_signal._only_about = to_me
        return [
            on_shutdown,
            on_signal,
            OnProcessIO(
                target_action=self, on_stdin=self._on_stdin, on_stdout=self._on_stdout, on_stderr=self._on_stderr),
            OnShutdown(on_shutdown=self._on_launch_shutdown),
            OnProcessExit(target_action=self, on_exit=self._on_exit),
            OnProcessExit(target_action=self, on_exit=self._flush_output),
        ]

    def execute(self, context: LaunchContext) -> list[LaunchDescriptionEntity] | None:
        """Prepare, register the process's handlers, and start it in a task on the launch's loop."""
        self.prepare(context)
        name = self._description.final_name
        if self._executed:
            raise RuntimeError(f"ExecuteLocal action '{name}': executed more than once: {self.describe()}")
        self._executed = True
        if context.is_shutdown:
            return None  # the launch is ending: nothing new starts
        handlers = self._handlers()
        for handler in handlers:
            context.register_event_handler(handler)
        try:
            run = self._run = _Run(context.asyncio_loop, name)
            output = self._output if isinstance(self._output, dict) else perform_substitutions(context, self._output)
            if not self._output_said:
                output = getattr(context, '_output_default', output)
            run.out, run.err = launch_logging.get_output_loggers(name, output)
            context.asyncio_loop.create_task(self._live(context))
        except Exception:
            for handler in handlers:
                context.unregister_event_handler(handler)
            raise
        return None

    def _use_tty(self, context: LaunchContext) -> bool:
        configured = context.launch_configurations.get('emulate_tty')
        if configured is None:
            return self._emulate_tty
        return evaluate_condition_expression(context, normalize_to_list_of_substitutions(configured))

    async def _live(self, context: LaunchContext) -> None:
        """One life of the process: start, report, wait for its end, then respawn or finish."""
        from diffctl.supervision import SpawnRequest

        details, run = self._details, self._run
        if details is None:
            raise RuntimeError('process_event_args unexpectedly None')
        name, cmd, cwd, env = details['name'], details['cmd'], details['cwd'], details['env']
        if self._log_cmd:
            run.log.info(f"process details: cmd='{_shown(cmd)}', cwd='{cwd}', custom_env?={env is not None}")
        request = SpawnRequest(
            cmd=list(cmd), cwd=cwd, env=env, shell=self._shell, emulate_tty=self._use_tty(context), name=name)
        output = HeldBack(context, details)
        try:
            child = await spawner_for(context).spawn(request, output)
        except Exception:
            run.log.error(f'exception occurred while executing process:\n{traceback.format_exc()}')
            self._finish()
            return
        # asyncio's own subprocess transport reports a start a few loop turns after the fork (it connects the
        # pipes first); code that registers an OnProcessStart just after the launch visited this action
        # (launch_pytest's tools.wait_for_start) counts on that
        for _ in range(3):
            await asyncio.sleep(0)
        pid = details['pid'] = child.get_pid()
        run.log.info(f'process started with pid [{pid}]')
        run.child = child
        await context.emit_event(ProcessStarted(**details))
        output.release()

        code = await child.complete
        if code == 0:
            run.log.info(f'process has finished cleanly [pid {pid}]')
        else:
            run.log.error(
                f"process has died [pid {pid}, exit code {code}, cmd '{_shown(cmd)}'].")
        await context.emit_event(ProcessExited(returncode=code, **details))

        if self._respawn_due(context):
            run.respawns += 1
            if self._respawn_delay is not None and self._respawn_delay > 0.0:
                # a shutdown of the process ends the wait early
                await asyncio.wait((run.stopping,), timeout=self._respawn_delay)
            if not run.stopping.done():
                child.close()
                context.asyncio_loop.create_task(self._live(context))
                return
        self._finish()

    def _respawn_due(self, context: LaunchContext) -> bool:
        run = self._run
        if context.is_shutdown or run.stopping.done() or not self._respawn:
            return False
        return self._respawn_limit < 0 or run.respawns < self._respawn_limit

    def _finish(self) -> None:
        run = self._run
        for timer in run.timers:
            timer.cancel()
        for step in run.escalation:
            step.cancel()
        if run.child is not None:
            run.child.close()
        run.done.set_result(None)

    # ---- stopping ----------------------------------------------------------------------------------------------

    def _shutdown_process(self, context: LaunchContext, *, send_sigint: bool) -> list[Action] | None:
        """Begin stopping the process: SIGINT (when `send_sigint`), escalated by timers while it lingers.

        Returns the actions doing it. Called again, or before the process started (then it waits for the
        start), or after its end, it does what is left to do.
        """
        run = self._run
        if run is None or run.stopping.done():
            return None
        if run.done.done():
            run.stopping.set_result(None)
            return None
        if self._details is None or run.child is None:
            context.register_event_handler(OnProcessStart(
                on_start=lambda event, context: self._shutdown_process(context, send_sigint=send_sigint)))
            return None
        run.stopping.set_result(None)
        context.extend_locals({'process_name': self._details['name']})
        run.timers = self._escalation(context)
        steps: list[Action] = list(run.timers)
        if send_sigint:
            steps.append(EmitEvent(event=SignalProcess(
                signal_number=signal.SIGINT, process_matcher=matches_action(self))))
        return steps

    def _escalation(self, context: LaunchContext) -> list[TimerAction]:
        """SIGTERM after `sigterm_timeout`, SIGKILL after both timeouts, each step logged.

        Timeouts that are numbers (what launch files give) are timers of the loop: stopping 50 processes made
        100 TimerActions, each a task, and their actions otherwise. Others are TimerActions whose own
        evaluation of the timeouts fails as upstream's does."""
        term_text = perform_substitutions(context, self._term_after)
        try:
            term_s = float(term_text)
            kill_s = term_s + float(perform_substitutions(context, self._kill_after))
        except ValueError:
            both = [PythonExpression(('float(', *self._term_after, ') + float(', *self._kill_after, ')'))]
            return [
                TimerAction(
                    period=delay,
                    actions=[
                        OpaqueFunction(function=self._complain, args=(delay, before, sent_name)),
                        EmitEvent(event=SignalProcess(signal_number=sent, process_matcher=matches_action(self))),
                    ],
                    cancel_on_shutdown=False,
                )
                for delay, before, sent, sent_name in (
                    (self._term_after, 'SIGINT', signal.SIGTERM, 'SIGTERM'), (both, 'SIGTERM', 'SIGKILL', 'SIGKILL'))
            ]
        loop = context.asyncio_loop
        self._run.escalation = [
            loop.call_later(term_s, self._escalate, context, term_text, 'SIGINT', signal.SIGTERM, 'SIGTERM'),
            loop.call_later(kill_s, self._escalate, context, str(kill_s), 'SIGTERM', 'SIGKILL', 'SIGKILL'),
        ]
        return []

    def _escalate(self, context: LaunchContext, shown: str, before: str, sent: Any, sent_name: str) -> None:
        self._run.log.error(
            f"process[{self._details['name']}] failed to terminate '{shown}' "
            f"seconds after receiving '{before}', escalating to '{sent_name}'")
        context.emit_event_sync(SignalProcess(signal_number=sent, process_matcher=matches_action(self)))

    def _complain(self, context: LaunchContext, delay: str | list, before: str, after: str) -> None:
        shown = delay if isinstance(delay, str) else perform_substitutions(context, delay)
        self._run.log.error(
            f"process[{context.locals.process_name}] failed to terminate '{shown}' "
            f"seconds after receiving '{before}', escalating to '{after}'")

    def _on_shutdown_process(self, context: LaunchContext) -> list[Action] | None:
        return self._shutdown_process(context, send_sigint=True)

    def _on_launch_shutdown(self, event: Event, context: LaunchContext) -> list[Action] | None:
        # with a terminal, a shutdown due to SIGINT means the processes had their SIGINT already
        return self._shutdown_process(context, send_sigint=not event.due_to_sigint or context.noninteractive)

    def _on_signal_process(self, context: LaunchContext) -> None:
        event = context.locals.event
        if self._details is None:
            raise RuntimeError('Signal event received before execution.')
        child = self._run.child
        if child is None:
            raise RuntimeError('Signal event received before subprocess transport available.')
        name, what = self._details['name'], event.signal_name
        if child.complete.done():
            self._run.log.debug(f"signal '{what}' not set to '{name}' because it is already closing")
            return
        self._run.log.info(f"sending signal '{what}' to process[{name}]")
        try:
            if what == 'SIGKILL':
                child.kill()
            else:
                child.send_signal(event.signal)
        except ProcessLookupError:
            self._run.log.debug(f"signal '{what}' not sent to '{name}' because it has closed already")

    # ---- output ------------------------------------------------------------------------------------------------

    def _writer(self, logger: logging.Logger) -> Callable[[str], None]:
        return lambda line: logger.info(self._line_format.format(line=line, this=self))

    def _on_stdin(self, event: ProcessIO) -> None:
        self._run.log.warning(f"in ExecuteProcess('{id(self)}').__on_process_stdin_event()")

    def _on_stdout(self, event: ProcessIO) -> None:
        self._streams['stdout'].add(event.text.decode(errors='replace'), self._writer(self._run.out))

    def _on_stderr(self, event: ProcessIO) -> None:
        self._streams['stderr'].add(event.text.decode(errors='replace'), self._writer(self._run.err))

    def _flush_output(self, event: Event, context: LaunchContext) -> None:
        run = self._run
        final = run.stopping.done()
        self._streams['stdout'].flush(self._writer(run.out), final=final)
        self._streams['stderr'].flush(self._writer(run.err), final=final)
