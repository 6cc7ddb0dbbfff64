"""`ament_copyright.main` (diffctl/testing/copyright.py): `main(argv=[...])` returns 0 or 1."""

from diffctl.testing.copyright import main

__all__ = ["main"]
