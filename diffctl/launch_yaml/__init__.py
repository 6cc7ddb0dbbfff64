"""diffctl's implementation of ros2/launch's `launch_yaml`: YAML launch files.

Its names are imported on first use (PEP 562): the launcher makes this package `launch_yaml` for every launch
file, and only a YAML file needs its parser.
"""

from diffctl.launch._private.lazy import lazy_exports

__getattr__, __dir__, __all__ = lazy_exports(__name__, globals(), {
    '.entity': ('Entity',),
    '.parser': ('Parser',),
    '.launch_description_sources': ('launch_description_sources/',),
})
