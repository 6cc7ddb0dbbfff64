"""ament_index_python.search_paths."""

from diffctl.workspace.resource_index import get_search_paths  # noqa: F401
