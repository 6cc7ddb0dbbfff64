"""Descriptions of what an action runs."""

from .executable import Executable

__all__ = [
    'Executable',
]
