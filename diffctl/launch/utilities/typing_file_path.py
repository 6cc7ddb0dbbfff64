"""`FilePath`: what launch accepts as a path to a file."""

import os
import typing

FilePath = typing.TypeVar('FilePath', str, bytes, os.PathLike)
