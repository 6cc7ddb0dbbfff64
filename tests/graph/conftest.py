"""The graph tests reuse the end-to-end stack's per-test router port."""

from __future__ import annotations

from tests.e2e.conftest import stack_env

__all__ = ["stack_env"]
