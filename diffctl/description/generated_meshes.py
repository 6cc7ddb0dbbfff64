"""Shapes SDF has and PyBullet lacks, written once as OBJ meshes into the user's cache.

An `<ellipsoid><radii>a b c</radii>` is a unit icosphere (subdivided three times, 642 vertices) scaled by its
radii: convex, so PyBullet's convex-hull collision for moving bodies is exact up to the tessellation.
"""

from __future__ import annotations

import os
from pathlib import Path

from diffctl.description.urdf.meshes import cache_dir


def ellipsoid_obj(radii_m: tuple[float, float, float]) -> Path:
    out = cache_dir() / ("ellipsoid-" + "-".join(f"{r:.9g}" for r in radii_m) + ".obj")
    if out.is_file():
        return out
    import trimesh

    mesh = trimesh.creation.icosphere(subdivisions=3, radius=1.0)
    mesh.apply_scale(radii_m)
    out.parent.mkdir(parents=True, exist_ok=True)
    tmp = out.with_suffix(f".{os.getpid()}.tmp")
    tmp.write_text(trimesh.exchange.obj.export_obj(mesh, include_normals=False))
    tmp.replace(out)  # atomic: a concurrent loader never reads half a file
    return out
