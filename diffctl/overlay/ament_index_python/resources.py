"""ament_index_python.resources: the resource index on AMENT_PREFIX_PATH (diffctl.workspace.resource_index)."""

from diffctl.workspace.resource_index import (  # noqa: F401
    InvalidResourceNameError,
    InvalidResourceTypeNameError,
    get_resource,
    get_resource_types,
    get_resources,
    has_resource,
)
