"""The assets capability's URI rules on their own: foxglove_bridge's default allowlist, `..`, file:// when a
user's allowlist lets it through, and a bad allowlist entry."""

from __future__ import annotations

from pathlib import Path

import pytest

from diffctl.errors import ConfigError
from diffctl.foxglove.assets import AssetResolver


def test_default_allowlist_takes_package_meshes_only(tmp_path: Path) -> None:
    share = tmp_path / "share"
    (share / "meshes").mkdir(parents=True)
    (share / "meshes" / "base.dae").write_text("<COLLADA/>")

    def share_dir(package: str) -> Path:  # a package index that knows one package
        if package != "bot":
            raise ConfigError(f"no package {package}")
        return share

    r = AssetResolver(share_dir=share_dir)
    assert r.fetch("package://bot/meshes/base.dae") == b"<COLLADA/>"
    for uri in ("package://bot/meshes/../meshes/base.dae", "file:///etc/passwd", "package://bot/secret.txt",
                "package://bot/.hidden/x.stl", "http://example.com/a.stl"):
        with pytest.raises(PermissionError, match="not allowed"):
            r.fetch(uri)
    with pytest.raises(FileNotFoundError, match="no file at"):
        r.fetch("package://bot/meshes/missing.stl")
    with pytest.raises(FileNotFoundError, match="package 'nope' not found"):
        r.fetch("package://nope/meshes/a.stl")


def test_a_users_allowlist_may_admit_file_uris_but_never_dot_dot(tmp_path: Path) -> None:
    mesh = tmp_path / "m.stl"
    mesh.write_bytes(b"solid m\nendsolid m\n")
    r = AssetResolver([r"^file:///.*\.stl$"])
    assert r.fetch(f"file://{mesh}") == mesh.read_bytes()
    with pytest.raises(PermissionError):
        r.fetch(f"file://{tmp_path}/../{tmp_path.name}/m.stl")
    with pytest.raises(ConfigError, match="asset_uri_allowlist entry '\\(' is not a regular expression"):
        AssetResolver(["("])
