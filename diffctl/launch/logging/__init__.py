"""Launch's logging: one screen handler, a `launch.log` per run, and loggers for processes' output.

While this module is loaded, loggers created are `LaunchLogger`s, which do not propagate: each gets the
handlers it writes to from `get_logger` or `get_output_loggers`, as in ros2/launch. The run's folder is
below `$ROS_LOG_DIR`, else `$ROS_HOME/log`, else `~/.ros/log`: a new one per run, with a `latest` link to
it, made when first needed.
"""

from __future__ import annotations

import datetime
import locale
import logging
import os
import sys
import warnings
from typing import Any, ClassVar

from . import handlers

__all__ = ['get_logger', 'get_output_loggers', 'handlers', 'launch_config', 'reset']

# format aliases, by what they format; any other text is a `logging.Formatter` format
_ALIASES = {
    'screen': {
        'default': '[{levelname}] [{name}]: {msg}',
        'default_with_timestamp': '{created:.7f} [{levelname}] [{name}]: {msg}',
    },
    'log': {'default': '{created:.7f} [{levelname}] [{name}]: {msg}'},
}
_OVERRIDES = {'screen': 'OVERRIDE_LAUNCH_SCREEN_FORMAT', 'log': 'OVERRIDE_LAUNCH_LOG_FORMAT'}


def _logs_root() -> str:
    chosen = os.environ.get('ROS_LOG_DIR') or os.path.join(os.environ.get('ROS_HOME') or '~/.ros', 'log')
    return os.path.normpath(os.path.expanduser(chosen))


def _new_run_folder(root: str) -> str:
    """A folder of its own for this run: time, host and process id in its name."""
    import socket

    while True:
        stamp = datetime.datetime.now().strftime('%Y-%m-%d-%H-%M-%S-%f')
        folder = os.path.join(root, f'{stamp}-{socket.gethostname()}-{os.getpid()}')
        if not os.path.isdir(folder):
            os.makedirs(folder, exist_ok=True)
            return folder


def _point_latest_at(folder: str) -> bool:
    """Make `latest` beside `folder` a link to it; False where `latest` is something else than a link."""
    latest = os.path.join(os.path.dirname(folder), 'latest')
    if os.path.islink(latest):
        os.unlink(latest)
    elif os.path.lexists(latest):
        return False
    os.symlink(folder, latest, target_is_directory=True)
    return True


def _override(kind: str) -> str | None:
    """The format an OVERRIDE_LAUNCH_* variable imposes (its backslash escapes read), if set."""
    text = os.environ.get(_OVERRIDES[kind])
    return text.encode('latin1').decode('unicode_escape') if text else None


class _Lenient:
    """A text stream that writes what the locale's encoding cannot represent as replacements."""

    def __init__(self, stream: Any) -> None:
        self.stream = stream

    def write(self, text: str) -> None:
        encoding = locale.getpreferredencoding(False)
        self.stream.write(text.encode(encoding, 'replace').decode(encoding, 'replace'))

    def flush(self) -> None:
        self.stream.flush()


class LaunchConfig:
    """The logging setup of the launch: the level, the run's folder, the formats, the shared handlers."""

    def __init__(self) -> None:
        self.reset()

    def reset(self) -> None:
        """The defaults again: INFO, default formats, no handler made yet, a run folder still to choose."""
        self.file_handlers: dict[str, logging.Handler] = {}
        self.screen_handler: logging.Handler | None = None
        self.screen_formatter: logging.Formatter | None = None
        self.file_formatter: logging.Formatter | None = None
        self._folder: str | None = None
        self._file_handler_maker = None
        self.level = logging.INFO
        self.set_screen_format('default')
        self.set_log_format('default')

    # the level lives on the root logger, which launch's loggers inherit it from
    level = property(
        lambda self: logging.root.getEffectiveLevel(),
        lambda self, new_level: logging.root.setLevel(new_level),
        doc='The level of every launch logger.')

    @property
    def log_dir(self) -> str:
        """The run's log folder; it and the `latest` link are made when first asked for."""
        if self._folder is None:
            self._folder = _new_run_folder(_logs_root())
            try:
                linked = _point_latest_at(self._folder)
            except OSError as problem:
                warnings.warn(f'Cannot create a symlink to latest log directory: {problem}\n', stacklevel=1)
            else:
                if not linked:
                    warnings.warn('Cannot create a symlink to latest log directory', stacklevel=1)
        return self._folder

    @log_dir.setter
    def log_dir(self, new_log_dir: str | None) -> None:
        """An existing folder for the log files (None: pick a new one when next needed)."""
        if new_log_dir is not None:
            if self.file_handlers:
                warnings.warn(
                    f'Loggers have been already configured to output to log files below {self._folder}. '
                    'Proceed at your own risk.', stacklevel=1)
            if not os.path.isdir(new_log_dir):
                raise ValueError(f'{new_log_dir} is not a directory')
        self._folder = new_log_dir

    @property
    def log_handler_factory(self):
        """What makes the log files' handlers: `(path, encoding=…) -> handler`; watched files by default."""
        if self._file_handler_maker is None:
            self._file_handler_maker = handlers.FileHandler if os.name == 'nt' else handlers.WatchedFileHandler
        return self._file_handler_maker

    @log_handler_factory.setter
    def log_handler_factory(self, new_log_handler_factory) -> None:
        self._file_handler_maker = new_log_handler_factory

    def _formatter(self, kind: str, fmt: str | None, style: str | None) -> logging.Formatter | None:
        imposed = _override(kind)
        if imposed is not None:
            fmt, style = imposed, '{'
        if fmt is None:
            return None
        known = _ALIASES[kind].get(fmt)
        if known is not None:
            if style is not None:
                raise ValueError(f'Cannot set a custom format style for the "{fmt}" {kind} format.')
            fmt = known
        return logging.Formatter(fmt, style=style or '{')

    def set_screen_format(self, screen_format: str | None, *, screen_style: str | None = None) -> None:
        """The screen's format: 'default', 'default_with_timestamp', or a format of `logging.Formatter`.

        `OVERRIDE_LAUNCH_SCREEN_FORMAT` ('{' style) wins over the argument. An alias takes no style.
        """
        self.screen_formatter = self._formatter('screen', screen_format, screen_style)
        if self.screen_formatter is not None and self.screen_handler is not None:
            self.screen_handler.setFormatter(self.screen_formatter)

    def set_log_format(self, log_format: str | None, *, log_style: str | None = None) -> None:
        """The format of launch.log: 'default' or a format of `logging.Formatter`.

        `OVERRIDE_LAUNCH_LOG_FORMAT` ('{' style) wins over the argument. The alias takes no style.
        """
        self.file_formatter = self._formatter('log', log_format, log_style)
        if self.file_formatter is not None:
            for handler in self.file_handlers.values():
                handler.setFormatter(self.file_formatter)

    def get_screen_handler(self) -> logging.Handler:
        """The handler writing to the screen: the `sys.stdout` of when it was first asked for."""
        if self.screen_handler is None:
            made = handlers.StreamHandler(_Lenient(sys.stdout))
            made.setFormatter(self.screen_formatter)
            self.screen_handler = made
        return self.screen_handler

    def get_log_file_path(self, file_name: str = 'launch.log') -> str:
        """Where a log file of this run goes."""
        return os.path.join(self.log_dir, file_name)

    def get_log_file_handler(self, file_name: str = 'launch.log') -> logging.Handler:
        """The handler of a log file of this run, made once per file."""
        if file_name not in self.file_handlers:
            made = self.log_handler_factory(self.get_log_file_path(file_name), encoding='utf-8')
            made.setFormatter(self.file_formatter)
            self.file_handlers[file_name] = made
        return self.file_handlers[file_name]


launch_config = LaunchConfig()


def log_launch_config(*, logger: logging.Logger = logging.root) -> None:
    """Say where the log files are (once some are written) and which level is in force."""
    if launch_config.file_handlers:
        logger.info(f'All log files can be found below {launch_config.log_dir}')
    logger.info(f'Default logging verbosity is set to {logging.getLevelName(logging.root.getEffectiveLevel())}')


def _attach(logger: logging.Logger, handler: logging.Handler) -> None:
    if handler not in logger.handlers:
        logger.addHandler(handler)


def get_logger(name: str | None = None) -> logging.Logger:
    """The logger `name`, writing to the screen and to the run's launch.log."""
    logger = logging.getLogger(name)
    _attach(logger, launch_config.get_screen_handler())
    _attach(logger, launch_config.get_log_file_handler())
    return logger


# what each output alias sends where: {source: destinations}, 'both' meaning stdout and stderr
_OUTPUT_ALIASES = {
    'screen': {'both': {'screen'}},
    'log': {'both': {'log'}, 'stderr': {'screen'}},
    'both': {'both': {'log', 'screen'}},
    'own_log': {'both': {'own_log'}, 'stdout': {'own_log'}, 'stderr': {'own_log'}},
    'full': {'both': {'screen', 'log', 'own_log'}, 'stdout': {'own_log'}, 'stderr': {'own_log'}},
}


def _destinations(config: Any) -> dict[str, set[str]]:
    """An output configuration, alias or dict, as destinations by source (ValueError when malformed)."""
    routes: dict[str, set[str]] = {'both': set(), 'stdout': set(), 'stderr': set()}
    if isinstance(config, str):
        if config not in _OUTPUT_ALIASES:
            raise ValueError(f'{config} is not a valid standard output config i.e. "screen", "log" or "both"')
        config = _OUTPUT_ALIASES[config]
    elif not isinstance(config, dict):
        raise ValueError(f'{config} is not a valid output configuration')
    for source, wanted in config.items():
        if source not in routes:
            raise ValueError(f'{source} is not a valid output source i.e. "stdout", "stderr" or "both"')
        wanted = {wanted} if isinstance(wanted, str) else set(wanted)
        unknown = [destination for destination in wanted if destination not in ('screen', 'log', 'own_log')]
        if unknown:
            raise ValueError(
                f'{unknown[0]} is not a valid output destination i.e. "screen", "log" or "own_log"')
        routes[source] = wanted
    return routes


def _wire(logger: logging.Logger, process_name: str, source: str, routes: dict[str, set[str]]) -> None:
    if 'screen' in routes['both'] | routes[source]:
        screen = launch_config.get_screen_handler()
        if screen not in logger.handlers:
            screen.setFormatterFor(logger, logging.Formatter('{msg}', style='{'))  # bare lines on screen
            logger.addHandler(screen)
    if 'log' in routes['both'] | routes[source]:
        main = launch_config.get_log_file_handler()
        if main not in logger.handlers:
            main.setFormatterFor(logger, logging.Formatter('{created:.7f} {msg}', style='{'))
            logger.addHandler(main)
    if 'own_log' in routes[source]:
        own = launch_config.get_log_file_handler(f'{process_name}-{source}.log')
        own.setFormatter(logging.Formatter(fmt=None))
        _attach(logger, own)
    if 'own_log' in routes['both']:
        combined = launch_config.get_log_file_handler(f'{process_name}.log')
        combined.setFormatter(logging.Formatter('{msg}', style='{'))
        _attach(logger, combined)


def get_output_loggers(process_name: str, output_config: Any) -> tuple[logging.Logger, logging.Logger]:
    """The (stdout, stderr) loggers of a process, writing where `output_config` says.

    `output_config`: an alias — 'screen' (both streams to the screen), 'log' (both to launch.log, stderr
    also to the screen), 'both' (both to the screen and launch.log), 'own_log' (each to
    `<name>-stdout.log` / `<name>-stderr.log`, both to `<name>.log`), 'full' (all of that) — or a dict
    from 'stdout', 'stderr' or 'both' to one or several of 'screen', 'log', 'own_log'.
    """
    routes = _destinations(output_config)
    pair = []
    for source in ('stdout', 'stderr'):
        logger = logging.getLogger(f'{process_name}-{source}')
        _wire(logger, process_name, source, routes)
        pair.append(logger)
    return pair[0], pair[1]


class LaunchLogger(logging.getLoggerClass()):  # type: ignore[misc]
    """The logger class while launch is loaded: no propagation, and remembered for `reset()`."""

    all_loggers: ClassVar[list[logging.Logger]] = []

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self.propagate = False
        LaunchLogger.all_loggers.append(self)


def reset() -> None:
    """Undo launch's logging setup: the levels and handlers of its loggers, and `launch_config`."""
    for logger in LaunchLogger.all_loggers:
        logger.handlers.clear()
        logger.setLevel(logging.NOTSET)
    launch_config.reset()
    logging.setLoggerClass(LaunchLogger)


reset()
