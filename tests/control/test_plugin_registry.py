"""Plugins found through entry points: scanned once, rescanned when a name is missing (installed later) and on
reload_controller_libraries."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from diffctl.control import plugin_registry
from diffctl.errors import ConfigError

PLUGIN = "late_pkg/LateController"


def _install(site: Path) -> None:
    """A distribution, installed into `site`, whose entry point names a ControllerInterface subclass."""
    (site / "late_pkg").mkdir(parents=True)
    (site / "late_pkg" / "__init__.py").write_text(
        "from diffctl.control.controller_interface import ControllerInterface\n\n\n"
        "class LateController(ControllerInterface):\n    pass\n"
    )
    dist = site / "late_pkg-0.1.dist-info"
    dist.mkdir()
    (dist / "METADATA").write_text("Metadata-Version: 2.1\nName: late-pkg\nVersion: 0.1\n")
    (dist / "entry_points.txt").write_text(f"[diffctl.controllers]\n{PLUGIN} = late_pkg:LateController\n")


def test_a_plugin_installed_after_the_first_scan_is_found(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(plugin_registry, "_scanned", {})
    known = plugin_registry.controller_types()
    assert "diff_drive_controller/DiffDriveController" in known and PLUGIN not in known
    _install(tmp_path)
    monkeypatch.syspath_prepend(str(tmp_path))
    try:
        assert PLUGIN not in plugin_registry.controller_types()  # the scan is kept …
        assert plugin_registry.controller_class(PLUGIN).__name__ == "LateController"  # … until a name is missing
        assert PLUGIN in plugin_registry.controller_types()
    finally:
        sys.modules.pop("late_pkg", None)


def test_an_unknown_plugin_is_still_a_located_error_with_a_suggestion(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(plugin_registry, "_scanned", {})
    with pytest.raises(ConfigError, match="diff_drive_controller/DiffDriveController"):
        plugin_registry.controller_class("diff_drive_controller/DiffDriveControler")
    plugin_registry.rescan()
    assert plugin_registry._scanned == {}
