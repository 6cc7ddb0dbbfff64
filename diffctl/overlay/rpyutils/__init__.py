"""rpyutils (ROS 2's C-extension loading helpers; diffctl: diffctl.workspace.c_extensions)."""

from diffctl.workspace.c_extensions import add_dll_directories_from_env, import_c_library

__all__ = ["add_dll_directories_from_env", "import_c_library"]
