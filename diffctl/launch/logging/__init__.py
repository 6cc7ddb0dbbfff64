"""Launch's logging: one screen handler, a `launch.log` file per run, and loggers for process output.

Importing this module makes every logger created afterwards a `LaunchLogger` (it does not propagate to
the root logger: each logger gets the handlers it should write to from `get_logger` or
`get_output_loggers`), as ros2/launch does. The log directory is `$ROS_LOG_DIR`, else `$ROS_HOME/log`,
else `~/.ros/log`, with one unique sub-folder per run (and a `latest` link to it), made on first use.
"""

from __future__ import annotations

import datetime
import locale
import logging
import os
import sys
from typing import Any, ClassVar

from . import handlers

__all__ = [
    'get_logger',
    'get_output_loggers',
    'handlers',
    'launch_config',
    'reset',
]

_SCREEN_FORMATS = {
    'default': '[{levelname}] [{name}]: {msg}',
    'default_with_timestamp': '{created:.7f} [{levelname}] [{name}]: {msg}',
}
_LOG_FORMATS = {'default': '{created:.7f} [{levelname}] [{name}]: {msg}'}


def _get_logging_directory() -> str:
    base = os.environ.get('ROS_LOG_DIR')
    if not base:
        base = os.path.join(os.environ.get('ROS_HOME') or os.path.join('~', '.ros'), 'log')
    return os.path.normpath(os.path.expanduser(base))


def _make_unique_log_dir(*, base_path: str) -> str:
    import socket

    while True:
        stamp = datetime.datetime.now().strftime('%Y-%m-%d-%H-%M-%S-%f')
        candidate = os.path.join(base_path, f'{stamp}-{socket.gethostname()}-{os.getpid()}')
        if not os.path.isdir(candidate):
            os.makedirs(candidate, exist_ok=True)
            return candidate


def _renew_latest_log_dir(*, log_dir: str) -> bool:
    latest = os.path.join(os.path.dirname(log_dir), 'latest')
    if os.path.lexists(latest):
        if not os.path.islink(latest):
            return False
        os.unlink(latest)
    os.symlink(log_dir, latest, target_is_directory=True)
    return True


class _ReplacingStream:
    """Writes to a text stream, replacing what the locale's encoding cannot represent instead of failing."""

    def __init__(self, stream: Any) -> None:
        self.stream = stream

    def write(self, text: str) -> None:
        encoding = locale.getpreferredencoding(False)
        self.stream.write(text.encode(encoding, 'replace').decode(encoding, 'replace'))

    def flush(self) -> None:
        self.stream.flush()


def _override(variable: str) -> str | None:
    value = os.environ.get(variable)
    if not value:
        return None
    return value.encode('latin1').decode('unicode_escape')


class LaunchConfig:
    """The logging configuration of a launch: level, log directory, formats and the shared handlers."""

    def __init__(self) -> None:
        self.reset()

    def reset(self) -> None:
        """Back to defaults: level INFO, default formats, no handlers, a log directory chosen anew."""
        self._log_dir: str | None = None
        self.file_handlers: dict[str, logging.Handler] = {}
        self.screen_handler: logging.Handler | None = None
        self.screen_formatter: logging.Formatter | None = None
        self.file_formatter: logging.Formatter | None = None
        self._log_handler_factory = None
        logging.root.setLevel(logging.INFO)
        self.set_screen_format('default')
        self.set_log_format('default')

    @property
    def level(self) -> int:
        return logging.root.getEffectiveLevel()

    @level.setter
    def level(self, new_level: int) -> None:
        """The level of every launch logger (set on the root logger)."""
        logging.root.setLevel(new_level)

    @property
    def log_dir(self) -> str:
        """The directory of this run's log files, made (with its `latest` link) on first use."""
        if self._log_dir is None:
            self._log_dir = _make_unique_log_dir(base_path=_get_logging_directory())
            import warnings

            try:
                if not _renew_latest_log_dir(log_dir=self._log_dir):
                    warnings.warn('Cannot create a symlink to latest log directory', stacklevel=1)
            except OSError as e:
                warnings.warn(f'Cannot create a symlink to latest log directory: {e}\n', stacklevel=1)
        return self._log_dir

    @log_dir.setter
    def log_dir(self, new_log_dir: str | None) -> None:
        """Use an existing directory for the log files (None: choose one again on next use)."""
        if new_log_dir is not None:
            if self.file_handlers:
                import warnings

                warnings.warn(
                    f'Loggers have been already configured to output to log files below {self._log_dir}. '
                    'Proceed at your own risk.', stacklevel=1)
            if not os.path.isdir(new_log_dir):
                raise ValueError(f'{new_log_dir} is not a directory')
        self._log_dir = new_log_dir

    @property
    def log_handler_factory(self):
        """Callable `(path, encoding=...) -> handler` making log file handlers (default: watched files)."""
        if self._log_handler_factory is None:
            self._log_handler_factory = handlers.WatchedFileHandler if os.name != 'nt' else handlers.FileHandler
        return self._log_handler_factory

    @log_handler_factory.setter
    def log_handler_factory(self, new_log_handler_factory) -> None:
        self._log_handler_factory = new_log_handler_factory

    def set_screen_format(self, screen_format: str | None, *, screen_style: str | None = None) -> None:
        """Format of screen messages: 'default', 'default_with_timestamp', or a `logging.Formatter` format.

        `OVERRIDE_LAUNCH_SCREEN_FORMAT` (with '{' style) wins over the argument. An alias takes no style.
        """
        override = _override('OVERRIDE_LAUNCH_SCREEN_FORMAT')
        if override is not None:
            screen_format, screen_style = override, '{'
        if screen_format is None:
            self.screen_formatter = None
            return
        if screen_format in _SCREEN_FORMATS:
            if screen_style is not None:
                raise ValueError(f'Cannot set a custom format style for the "{screen_format}" screen format.')
            screen_format = _SCREEN_FORMATS[screen_format]
        self.screen_formatter = logging.Formatter(screen_format, style=screen_style or '{')
        if self.screen_handler is not None:
            self.screen_handler.setFormatter(self.screen_formatter)

    def get_screen_handler(self) -> logging.Handler:
        """The one handler writing to the screen (the `sys.stdout` of when it was first asked for)."""
        if self.screen_handler is None:
            self.screen_handler = handlers.StreamHandler(_ReplacingStream(sys.stdout))
            self.screen_handler.setFormatter(self.screen_formatter)
        return self.screen_handler

    def set_log_format(self, log_format: str | None, *, log_style: str | None = None) -> None:
        """Format of the main log file: 'default' or a `logging.Formatter` format.

        `OVERRIDE_LAUNCH_LOG_FORMAT` (with '{' style) wins over the argument. The alias takes no style.
        """
        override = _override('OVERRIDE_LAUNCH_LOG_FORMAT')
        if override is not None:
            log_format, log_style = override, '{'
        if log_format is None:
            self.file_formatter = None
            return
        if log_format in _LOG_FORMATS:
            if log_style is not None:
                raise ValueError(f'Cannot set a custom format style for the "{log_format}" log format.')
            log_format = _LOG_FORMATS[log_format]
        self.file_formatter = logging.Formatter(log_format, style=log_style or '{')
        for handler in self.file_handlers.values():
            handler.setFormatter(self.file_formatter)

    def get_log_file_path(self, file_name: str = 'launch.log') -> str:
        """Absolute path of a log file of this run."""
        return os.path.join(self.log_dir, file_name)

    def get_log_file_handler(self, file_name: str = 'launch.log') -> logging.Handler:
        """The handler writing to a log file of this run, made once per file."""
        handler = self.file_handlers.get(file_name)
        if handler is None:
            handler = self.log_handler_factory(self.get_log_file_path(file_name), encoding='utf-8')
            handler.setFormatter(self.file_formatter)
            self.file_handlers[file_name] = handler
        return handler


launch_config = LaunchConfig()


def log_launch_config(*, logger: logging.Logger = logging.root) -> None:
    """Tell the user where the log files are and which level is in force."""
    if launch_config.file_handlers:
        logger.info(f'All log files can be found below {launch_config.log_dir}')
    level = logging.getLevelName(logging.root.getEffectiveLevel())
    logger.info(f'Default logging verbosity is set to {level}')


def get_logger(name: str | None = None) -> logging.Logger:
    """The logger `name`, writing to the screen and to this run's `launch.log`."""
    logger = logging.getLogger(name)
    for handler in (launch_config.get_screen_handler(), launch_config.get_log_file_handler()):
        if handler not in logger.handlers:
            logger.addHandler(handler)
    return logger


_ALIASES = {
    'screen': {'both': {'screen'}},
    'log': {'both': {'log'}, 'stderr': {'screen'}},
    'both': {'both': {'log', 'screen'}},
    'own_log': {'both': {'own_log'}, 'stdout': {'own_log'}, 'stderr': {'own_log'}},
    'full': {'both': {'screen', 'log', 'own_log'}, 'stdout': {'own_log'}, 'stderr': {'own_log'}},
}


def _normalize_output_configuration(config: Any) -> dict[str, set]:
    normalized: dict[str, set] = {'both': set(), 'stdout': set(), 'stderr': set()}
    if isinstance(config, str):
        if config not in _ALIASES:
            raise ValueError(f'{config} is not a valid standard output config i.e. "screen", "log" or "both"')
        for source, destinations in _ALIASES[config].items():
            normalized[source] = set(destinations)
        return normalized
    if not isinstance(config, dict):
        raise ValueError(f'{config} is not a valid output configuration')
    for source, destinations in config.items():
        if source not in normalized:
            raise ValueError(f'{source} is not a valid output source i.e. "stdout", "stderr" or "both"')
        if isinstance(destinations, str):
            destinations = {destinations}
        for destination in destinations:
            if destination not in ('screen', 'log', 'own_log'):
                raise ValueError(
                    f'{destination} is not a valid output destination i.e. "screen", "log" or "own_log"')
        normalized[source] = set(destinations)
    return normalized


def get_output_loggers(process_name: str, output_config: Any) -> tuple[logging.Logger, logging.Logger]:
    """The (stdout, stderr) loggers of a process, wired as `output_config` says.

    `output_config` is an alias — 'screen' (both to the screen), 'log' (both to launch.log, stderr also to
    the screen), 'both' (both to the screen and launch.log), 'own_log' (each to `<name>-stdout.log` /
    `<name>-stderr.log` and both to `<name>.log`), 'full' (all of these) — or a dict from 'stdout',
    'stderr' or 'both' to one or a set of 'screen', 'log', 'own_log'. ValueError for anything else.
    """
    config = _normalize_output_configuration(output_config)
    for source in ('stdout', 'stderr'):
        logger = logging.getLogger(f'{process_name}-{source}')
        wanted = config['both'] | config[source]
        if 'screen' in wanted:
            screen = launch_config.get_screen_handler()
            if screen not in logger.handlers:
                screen.setFormatterFor(logger, logging.Formatter('{msg}', style='{'))
                logger.addHandler(screen)
        if 'log' in wanted:
            main_log = launch_config.get_log_file_handler()
            if main_log not in logger.handlers:
                main_log.setFormatterFor(logger, logging.Formatter('{created:.7f} {msg}', style='{'))
                logger.addHandler(main_log)
        if 'own_log' in config[source]:
            own = launch_config.get_log_file_handler(f'{process_name}-{source}.log')
            own.setFormatter(logging.Formatter(fmt=None))
            if own not in logger.handlers:
                logger.addHandler(own)
        if 'own_log' in config['both']:
            combined = launch_config.get_log_file_handler(f'{process_name}.log')
            combined.setFormatter(logging.Formatter('{msg}', style='{'))
            if combined not in logger.handlers:
                logger.addHandler(combined)
    return logging.getLogger(f'{process_name}-stdout'), logging.getLogger(f'{process_name}-stderr')


class LaunchLogger(logging.getLoggerClass()):  # type: ignore[misc]
    """The logger class while launch is loaded: does not propagate, and is remembered for `reset()`."""

    all_loggers: ClassVar[list[logging.Logger]] = []

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.propagate = False
        LaunchLogger.all_loggers.append(self)


def reset() -> None:
    """Undo every launch logging setup: levels and handlers of launch's loggers, and `launch_config`."""
    for logger in LaunchLogger.all_loggers:
        logger.setLevel(logging.NOTSET)
        del logger.handlers[:]
    launch_config.reset()
    logging.setLoggerClass(LaunchLogger)


reset()
