"""diffctl's own launch-file extensions, registered as any third-party extension is: by the
'launch.frontend.launch_extension' entry point, whose loading (when a frontend parses its first action) imports
this package, whose modules expose their tags with launch.frontend's expose_action / expose_substitution.

- `on_exit` / `on_start` / `on_shutdown` tags (event_handler_tags.py);
- `wait_for` readiness, also `WaitFor` in Python launch files (readiness.py);
- `let` with `file` / `replace`, `$(file-content PATH NAME=value)`, `$(optenv)`, `arg`'s `choices:` alias
  (tag_additions.py).
"""

from diffctl.launch_extensions import event_handler_tags, tag_additions
from diffctl.launch_extensions.readiness import Condition, WaitFor, provide_probes

tag_additions.install()

__all__ = ["Condition", "WaitFor", "event_handler_tags", "provide_probes"]
