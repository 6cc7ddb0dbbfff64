"""ament_index_python.cli (the `ament_index` command), from diffctl.workspace.resource_index_cli."""

from diffctl.workspace.resource_index_cli import (  # noqa: F401
    main,
    resource_name_completer,
    resource_type_completer,
)
