"""ament_index_python.constants."""

from diffctl.workspace.resource_index import AMENT_PREFIX_PATH_ENV_VAR, RESOURCE_INDEX_SUBFOLDER  # noqa: F401
