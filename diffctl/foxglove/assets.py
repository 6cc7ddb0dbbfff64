"""The assets capability of `foxglove-bridge`: `package://` URIs (the meshes and textures a robot model names)
fetched by the Foxglove app, resolved through diffctl's package index.

As foxglove_bridge: a URI must match one of the `asset_uri_allowlist` regular expressions (by default
`package://` paths of mesh, image and robot-description files) and may not contain `..`; anything else, an
unknown package or a missing file is an error the client sees with the URI.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence
from pathlib import Path

from diffctl.errors import ConfigError, DiffctlError

# foxglove_bridge's default asset_uri_allowlist.
DEFAULT_ALLOWLIST = (
    r"^package://(?:[-\w%]+/)*[-\w%.]+\.(?:dae|fbx|glb|gltf|jpeg|jpg|mtl|obj|png|stl|tif|tiff|urdf|webp|xacro)$",
)


def compile_allowlist(patterns: Sequence[str]) -> list[re.Pattern[str]]:
    out = []
    for p in patterns:
        try:
            out.append(re.compile(p))
        except re.error as e:
            raise ConfigError(f"asset_uri_allowlist entry {p!r} is not a regular expression: {e}",
                              field="asset_uri_allowlist") from None
    return out


class AssetResolver:
    """`fetch(uri)` → the file's bytes; raises with the reason the client is told."""

    def __init__(self, allowlist: Sequence[str] = DEFAULT_ALLOWLIST,
                 share_dir: Callable[[str], Path] | None = None) -> None:
        self.allowlist = compile_allowlist(allowlist)
        if share_dir is None:
            from diffctl.workspace import share_dir as share_dir_of

            share_dir = share_dir_of
        self.share_dir = share_dir

    def allowed(self, uri: str) -> bool:
        # `..` is refused whatever the allowlist says: `package://pkg/../../secret` must not leave the package.
        return ".." not in uri and any(p.search(uri) for p in self.allowlist)

    def path(self, uri: str) -> Path:
        if not self.allowed(uri):
            raise PermissionError(f"Asset URI not allowed: {uri}")
        if uri.startswith("package://"):
            package, _, rest = uri[len("package://"):].partition("/")
            try:
                base = self.share_dir(package)
            except DiffctlError as e:
                raise FileNotFoundError(f"{uri}: package {package!r} not found ({e})") from None
            path = base / rest
        elif uri.startswith("file://"):
            path = Path(uri[len("file://"):])
        else:
            raise ValueError(f"{uri}: only package:// and file:// URIs name assets")
        if not path.is_file():
            raise FileNotFoundError(f"{uri}: no file at {path}")
        return path

    def fetch(self, uri: str) -> bytes:
        return self.path(uri).read_bytes()
