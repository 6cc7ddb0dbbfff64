"""Fuel includes: URI forms, Gazebo's cache layout, the shipped ground plane and sun, downloads, the error."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from diffctl.description.sdf_loader import load_world
from diffctl.errors import DescriptionError
from diffctl.fuel import resolve
from diffctl.fuel.cache import cached_model
from diffctl.fuel.uri import parse_fuel_uri
from tests.gazebo.fuel_server import FuelModels, fuel_server

FUEL = "https://fuel.gazebosim.org/1.0/OpenRobotics/models"

WORLD = """<?xml version="1.0"?>
<sdf version="1.9">
  <world name="fuel_world">
    <include><uri>{ground}</uri></include>
    <include><uri>{sun}</uri></include>
    {extra}
  </world>
</sdf>
"""

BOX_CONFIG = '<?xml version="1.0"?><model><name>Box</name><sdf version="1.6">model.sdf</sdf></model>'
BOX_SDF = """<?xml version="1.0"?>
<sdf version="1.6">
  <model name="box">
    <static>true</static>
    <link name="body">
      <visual name="v"><geometry><mesh><uri>model://Box/meshes/tri.obj</uri></mesh></geometry></visual>
    </link>
  </model>
</sdf>
"""
TRI_OBJ = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"


@pytest.fixture
def cache(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    root = tmp_path / "fuel-cache"
    root.mkdir()
    monkeypatch.setenv("GZ_FUEL_CACHE_PATH", str(root))
    monkeypatch.delenv("DIFFCTL_FUEL_SERVER", raising=False)
    monkeypatch.delenv("DIFFCTL_FUEL_SKIP_MISSING", raising=False)
    monkeypatch.setattr(resolve, "_failed", {})
    return root


def write_world(tmp_path: Path, ground: str, sun: str, extra: str = "") -> Path:
    path = tmp_path / "world.sdf"
    path.write_text(WORLD.format(ground=ground, sun=sun, extra=extra))
    return path


def test_uri_forms_parse_as_gz_fuel_tools_does() -> None:
    ref = parse_fuel_uri(f"{FUEL}/Ground Plane")
    assert (ref.host, ref.owner, ref.name, ref.version, ref.file) == (
        "fuel.gazebosim.org",
        "openrobotics",
        "ground plane",
        None,
        None,
    )
    assert parse_fuel_uri(f"{FUEL}/Ground%20Plane/3/").name == "ground%20plane"  # %20 is never decoded
    assert parse_fuel_uri(f"{FUEL}/Ground Plane/3").version == 3
    assert parse_fuel_uri(f"{FUEL}/Sun/tip").version is None
    no_api = parse_fuel_uri("https://fuel.gazebosim.org//OpenRobotics//models/Sun")
    assert (no_api.owner, no_api.name, no_api.api) == ("openrobotics", "sun", "1.0")
    f = parse_fuel_uri(f"{FUEL}/Box/2/files/meshes/tri.obj")
    assert (f.name, f.version, f.file) == ("box", 2, "meshes/tri.obj")
    assert parse_fuel_uri("model://ground_plane") is None
    assert parse_fuel_uri("https://example.org/robot.sdf") is None


def test_ground_plane_and_sun_need_no_cache_and_no_network(cache: Path, tmp_path: Path, monkeypatch) -> None:
    monkeypatch.setenv("DIFFCTL_FUEL_OFFLINE", "1")
    for ground, sun in (
        (f"{FUEL}/Ground Plane", f"{FUEL}/Sun"),
        ("https://fuel.gazebosim.org/1.0/openrobotics/models/ground plane/1", f"{FUEL}/Sun/2"),
        ("https://fuel.ignitionrobotics.org/1.0/OpenRobotics/models/Ground%20Plane", f"{FUEL}/sun/tip"),
    ):
        world = load_world(write_world(tmp_path, ground, sun))
        (plane,) = world.models
        assert (plane.name, plane.static, [link.name for link in plane.links]) == ("ground_plane", True, ["link"])
        assert plane.links[0].collisions[0].geometry.size_m == (100.0, 100.0)
        (light,) = world.lights
        assert (light.name, light.type, light.direction) == ("sun", "directional", (-0.5, 0.1, -0.9))
        assert light.pose_world.xyz == (0.0, 0.0, 10.0)
    assert not list(cache.iterdir())  # nothing was written


def _cache_model(cache: Path, owner_dir: str, name_dir: str, version: int, sdf: str) -> Path:
    folder = cache / "fuel.gazebosim.org" / owner_dir / "models" / name_dir / str(version)
    folder.mkdir(parents=True)
    (folder / "model.config").write_text(BOX_CONFIG)
    (folder / "model.sdf").write_text(sdf)
    return folder


def test_gazebos_cache_comes_first_tip_is_the_highest_version(cache: Path, tmp_path: Path) -> None:
    plane = '<sdf version="1.6"><model name="{n}"><static>1</static><link name="l"/></model></sdf>'
    _cache_model(cache, "openrobotics", "ground plane", 1, plane.format(n="cached_v1"))
    _cache_model(cache, "openrobotics", "ground plane", 3, plane.format(n="cached_v3"))
    half = cache / "fuel.gazebosim.org/openrobotics/models/ground plane/7"  # no model.config: not a version
    half.mkdir()
    (half / "model.sdf").write_text(plane.format(n="broken"))
    world = load_world(write_world(tmp_path, f"{FUEL}/Ground Plane", f"{FUEL}/Sun"))
    assert [m.name for m in world.models] == ["cached_v3"]
    world = load_world(write_world(tmp_path, f"{FUEL}/Ground Plane/1", f"{FUEL}/Sun"))
    assert [m.name for m in world.models] == ["cached_v1"]
    # `%20` is another cache key than a space: that spelling falls back to diffctl's copy
    world = load_world(write_world(tmp_path, f"{FUEL}/Ground%20Plane", f"{FUEL}/Sun"))
    assert [m.name for m in world.models] == ["ground_plane"]


def test_missing_model_is_reported_once_and_the_world_loads_or_strict_is_one_error(
    cache: Path, tmp_path: Path, monkeypatch, capsys
):
    """ARCHITECTURE.md ("Gazebo resources"): a model that cannot be had is reported once, with where it was looked
    for, and the rest of the world loads, as Gazebo does; DIFFCTL_FUEL_SKIP_MISSING=0 makes it an error."""
    from diffctl.description import sdf_documents

    monkeypatch.setenv("DIFFCTL_FUEL_OFFLINE", "1")
    monkeypatch.setattr(sdf_documents, "_skipped", set())
    uri = f"{FUEL}/Construction Cone"
    twice = f"<include>\n<uri>{uri}</uri></include><include><name>b</name><uri>{uri}</uri></include>"
    path = write_world(tmp_path, f"{FUEL}/Ground Plane", f"{FUEL}/Sun", twice)
    world = load_world(path)
    assert [m.name for m in world.models] == ["ground_plane"]
    (said,) = capsys.readouterr().err.strip().splitlines()  # once, for both includes
    assert said.startswith(f"warning: {path}:7: Fuel model '{uri}' is not available"), said
    assert str(cache / "fuel.gazebosim.org/openrobotics/models/construction cone") in said
    assert f"diffctl fuel download '{uri}'" in said and "the world loads without it" in said
    assert "DIFFCTL_FUEL_SKIP_MISSING=0 makes this an error" in said

    monkeypatch.setenv("DIFFCTL_FUEL_SKIP_MISSING", "0")
    with pytest.raises(DescriptionError) as e:
        load_world(path)
    text = str(e.value)
    assert f"{path}:7" in text and "Construction Cone" in text
    assert str(cache / "fuel.gazebosim.org/openrobotics/models/construction cone") in text
    assert f"diffctl fuel download '{uri}'" in text
    assert "GZ_SIM_RESOURCE_PATH" not in text and "SKIP_MISSING" not in text


def test_gz_sim_says_a_missing_model_before_anything_else_and_runs_the_world(
    cache: Path, tmp_path: Path, router: str
) -> None:
    """On a terminal (where PyBullet's build-time banner is not held back in a pipe's buffer) the missing model
    is the first thing `gz sim` says; then the world runs without it."""
    import os
    import pty

    uri = f"{FUEL}/Construction Cone"
    path = write_world(tmp_path, f"{FUEL}/Ground Plane", f"{FUEL}/Sun", f"<include>\n<uri>{uri}</uri></include>")
    env = {**os.environ, "DIFFCTL_FUEL_OFFLINE": "1", "GZ_FUEL_CACHE_PATH": str(cache), "NO_COLOR": "1"}
    leader, follower = pty.openpty()
    p = subprocess.Popen([sys.executable, "-m", "diffctl", "sim", "run", "-s", "-r", "-v", "3", "--iterations", "20",
                          str(path)],
                         stdin=subprocess.DEVNULL, stdout=follower, stderr=follower, env=env, start_new_session=True)
    os.close(follower)
    out = b""
    try:
        while True:
            try:
                chunk = os.read(leader, 65536)
            except OSError:  # EIO: the terminal's last writer is gone
                break
            if not chunk:
                break
            out += chunk
        assert p.wait(timeout=60) == 0, out.decode(errors="replace")
    finally:
        os.close(leader)
        if p.poll() is None:
            os.killpg(p.pid, 9)
            p.wait()
    lines = [line for line in out.decode(errors="replace").splitlines() if line.strip()]
    assert lines[0].startswith(f"warning: {path}:7: Fuel model '{uri}' is not available"), lines
    assert "world 'fuel_world'" in out.decode() and "1 model(s)" in out.decode(), lines


def test_download_from_a_fuel_server_into_gazebos_cache_layout(cache: Path, tmp_path: Path, monkeypatch) -> None:
    models = FuelModels()
    models.add("OpenRobotics", "Box", 2, {"model.config": BOX_CONFIG, "model.sdf": BOX_SDF, "meshes/tri.obj": TRI_OBJ})
    models.add("OpenRobotics", "Box", 1, {"model.config": BOX_CONFIG, "model.sdf": BOX_SDF, "meshes/tri.obj": TRI_OBJ})
    with fuel_server(models) as url:
        monkeypatch.setenv("DIFFCTL_FUEL_SERVER", url)
        uri = f"{FUEL}/Box"
        out = subprocess.run(
            [sys.executable, "-m", "diffctl", "fuel", "download", uri], capture_output=True, text=True, timeout=60
        )
        assert out.returncode == 0, out.stderr
        assert f"downloading fuel model {FUEL.lower()}/box/tip" in out.stderr.lower()
        # the route is escaped whole, `/` included, as gz-fuel-tools sends it
        assert models.requests == ["/1.0/openrobotics%2Fmodels%2Fbox%2Ftip%2Fbox.zip?link=true"]
        folder = cache / "fuel.gazebosim.org" / "openrobotics" / "models" / "box" / "2"
        assert sorted(p.name for p in folder.iterdir()) == ["meshes", "model.config", "model.sdf"]
        # FixPaths: the model's model:// mesh now names the Fuel file URL, which the cache resolves
        assert (
            "https://fuel.gazebosim.org/1.0/openrobotics/models/box/2/files/meshes/tri.obj"
            in (folder / "model.sdf").read_text()
        )
        world = load_world(
            write_world(tmp_path, f"{FUEL}/Ground Plane", f"{FUEL}/Sun", f"<include><uri>{uri}</uri></include>")
        )
        box = world.models[1]
        assert box.links[0].visuals[0].geometry.path == str(folder / "meshes" / "tri.obj")
        # a link answer (text/plain) is followed; an include of a version not cached downloads it
        models.link = True
        world = load_world(
            write_world(tmp_path, f"{FUEL}/Ground Plane", f"{FUEL}/Sun", f"<include><uri>{uri}/1</uri></include>")
        )
        assert cached_model(parse_fuel_uri(f"{uri}/1")) == folder.parent / "1"
        assert models.requests[-1].startswith("/zips/openrobotics/box/1")


def test_download_failure_names_the_server_answer(cache: Path, tmp_path: Path, monkeypatch) -> None:
    with fuel_server(FuelModels()) as url:
        monkeypatch.setenv("DIFFCTL_FUEL_SERVER", url)
        out = subprocess.run(
            [sys.executable, "-m", "diffctl", "fuel", "download", f"{FUEL}/Nothing"],
            capture_output=True,
            text=True,
            timeout=60,
        )
    assert out.returncode == 1
    assert "404" in out.stderr
    out = subprocess.run(
        [sys.executable, "-m", "diffctl", "fuel", "download", "model://x"], capture_output=True, text=True, timeout=60
    )
    assert out.returncode == 2 and "not a Fuel model or world URL" in out.stderr


def test_an_error_in_a_linked_world_names_the_users_own_file(cache: Path, tmp_path: Path, monkeypatch) -> None:
    # a workspace package's share tree (diffctl's cache) links each installed file to its source
    monkeypatch.setenv("DIFFCTL_FUEL_OFFLINE", "1")
    monkeypatch.setenv("DIFFCTL_FUEL_SKIP_MISSING", "0")
    source = write_world(tmp_path, f"{FUEL}/Ground Plane", f"{FUEL}/Sun", f"<include><uri>{FUEL}/Nope</uri></include>")
    link = tmp_path / "share" / "worlds" / "world.sdf"
    link.parent.mkdir(parents=True)
    link.symlink_to(source)
    with pytest.raises(DescriptionError) as e:
        load_world(link)
    assert e.value.source == str(source.resolve()) and e.value.line == 6


def test_a_fuel_world_url_is_found_in_the_cache_or_downloaded(cache: Path, tmp_path: Path, monkeypatch) -> None:
    """`gz sim https://fuel.gazebosim.org/1.0/OpenRobotics/worlds/Tiny` (Gazebo's last resort for the world
    argument): `…/worlds/<name>/<N>/<file>.sdf` in the cache, else the world's zip from the server."""
    from diffctl.sim.cli import find_world

    tiny = WORLD.format(ground=f"{FUEL}/Ground Plane", sun=f"{FUEL}/Sun", extra="")
    models = FuelModels()
    models.models[("openrobotics", "tiny")] = {3: {"tiny.sdf": tiny}}
    url = "https://fuel.gazebosim.org/1.0/OpenRobotics/worlds/Tiny"
    with fuel_server(models) as server:
        monkeypatch.setenv("DIFFCTL_FUEL_SERVER", server)
        path = find_world(url)
        assert path == cache / "fuel.gazebosim.org" / "openrobotics" / "worlds" / "tiny" / "3" / "tiny.sdf"
        assert models.requests == ["/1.0/openrobotics%2Fworlds%2Ftiny%2Ftip%2Ftiny.zip?link=true"]
        assert find_world(url) == path and len(models.requests) == 1  # cached now: no second request
    assert load_world(path).name == "fuel_world"
    monkeypatch.setenv("DIFFCTL_FUEL_OFFLINE", "1")
    from diffctl.errors import ConfigError

    with pytest.raises(ConfigError, match=r"Fuel world .*Nope.*fetch it with `diffctl fuel download [^,]*`\)$"):
        find_world("https://fuel.gazebosim.org/1.0/OpenRobotics/worlds/Nope")


def test_the_cache_is_the_environments_else_config_yamls_else_home(tmp_path: Path, monkeypatch) -> None:
    from diffctl.fuel.cache import cache_root

    for var in ("GZ_FUEL_CACHE_PATH", "IGN_FUEL_CACHE_PATH"):
        monkeypatch.delenv(var, raising=False)
    monkeypatch.setenv("HOME", str(tmp_path))
    assert cache_root() == tmp_path / ".gz" / "fuel"
    (tmp_path / ".gz" / "fuel").mkdir(parents=True)
    (tmp_path / ".gz" / "fuel" / "config.yaml").write_text(
        "servers:\n  - url: https://fuel.gazebosim.org\ncache:\n  path: /data/fuel\n"
    )
    assert cache_root() == Path("/data/fuel")
    monkeypatch.setenv("IGN_FUEL_CACHE_PATH", str(tmp_path / "old"))
    assert cache_root() == tmp_path / "old"
    monkeypatch.setenv("GZ_FUEL_CACHE_PATH", str(tmp_path / "new"))
    assert cache_root() == tmp_path / "new"
