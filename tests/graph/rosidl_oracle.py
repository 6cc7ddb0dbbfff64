"""rosidl itself as the oracle for types no Jazzy wheel ships (controller_manager_msgs, control_msgs, tf2_msgs, …).

rosidl's Jazzy Python packages (`ros-rosidl-adapter`, `-parser`, `-generator-type-description` 4.6.6, with
lark-parser and empy) are downloaded once with pip (`--no-deps`, nothing installed) and unpacked into a cache
directory; a child interpreter started without site-packages runs them on the upstream .msg/.srv texts kept
in `upstream_interfaces/` (see its README). Types the texts reference from other packages (std_msgs/Header,
lifecycle_msgs/State, service_msgs/ServiceEventInfo, …) come from the rosidl JSON files inside the Jazzy
wheels of jazzy_oracle, exactly as a colcon build finds them in the installed share/ directories.
"""

from __future__ import annotations

import hashlib
import json
import subprocess
import sys
import tarfile
import tempfile
import zipfile
from pathlib import Path

from tests.graph import jazzy_oracle

UPSTREAM = Path(__file__).parent / "upstream_interfaces"
ROSIDL_VERSION = "4.6.6"  # rosidl's Jazzy release
WHEELS = {f"ros-rosidl-{p}": ROSIDL_VERSION for p in ("adapter", "parser", "generator-type-description")}
WHEELS["lark-parser"] = "0.12.0"
EMPY = ("empy", "4.2.1")  # an sdist only: its single module em.py is taken from it, nothing is built


def _fill(d: Path) -> Path:
    """A directory whose subdirectories hold rosidl's modules, lark and em; built once (under `filling(d)`)."""
    root = d / "site"
    if (root / "done").exists():
        return root
    pip = [sys.executable, "-m", "pip", "download", "--no-deps", "-q", "-d", str(d)]
    subprocess.run([*pip, "--only-binary=:all:", *(f"{p}=={v}" for p, v in WHEELS.items())], check=True,
                   timeout=600)
    subprocess.run([*pip, "--no-binary=:all:", f"{EMPY[0]}=={EMPY[1]}"], check=True, timeout=600)
    root.mkdir(exist_ok=True)
    for wheel in d.glob("*.whl"):
        with zipfile.ZipFile(wheel) as z:
            for name in z.namelist():
                # ROS wheels keep their modules under <dist>.data/data/lib/pythonX.Y/site-packages/
                rel = name.split("/site-packages/", 1)[1] if "/site-packages/" in name else name
                if rel.endswith(("/", ".pyc")) or ".dist-info/" in rel or ".egg-info/" in rel:
                    continue
                if rel.split("/")[0] in ("rosidl_adapter", "rosidl_parser", "rosidl_generator_type_description",
                                         "lark"):
                    (root / rel).parent.mkdir(parents=True, exist_ok=True)
                    (root / rel).write_bytes(z.read(name))
    sdist = next(d.glob(f"{EMPY[0]}-{EMPY[1]}.tar.gz"))
    with tarfile.open(sdist) as t:
        member = t.extractfile(f"{EMPY[0]}-{EMPY[1]}/em.py")
        assert member is not None
        (root / "em.py").write_bytes(member.read())
    (root / "done").touch()
    return root


def _includes(work: Path) -> dict[str, str]:
    """share/<pkg>/ of every Jazzy wheel, unpacked: rosidl's JSON descriptions the texts may reference."""
    out: dict[str, str] = {}
    for wheel in jazzy_oracle.fetch():
        with zipfile.ZipFile(wheel) as z:
            for name in z.namelist():
                parts = name.split("/")
                if len(parts) >= 4 and parts[-4] == "share" and name.endswith(".json"):
                    pkg = parts[-3]
                    target = work / "share" / pkg / parts[-2] / parts[-1]
                    target.parent.mkdir(parents=True, exist_ok=True)
                    target.write_bytes(z.read(name))
                    out[pkg] = str(work / "share" / pkg)
    return out


def packages() -> list[str]:
    return sorted(d.name for d in UPSTREAM.iterdir() if d.is_dir())


def upstream_hashes() -> dict[str, str]:
    """type name → RIHS01 hash, as rosidl computes it from every upstream text (the types and their parts:
    a service's _Request, _Response and _Event). rosidl takes ~15 s for them: its answer is kept in the cache,
    under the digest of everything it read (the texts, the script, rosidl's and the wheels' releases), so it is
    asked again whenever any of that changes, and once per machine otherwise (not once per pytest-xdist worker)."""
    d = jazzy_oracle.cache_dir().parent / "rosidl-oracle"
    script = Path(__file__).with_name("rosidl_hash_script.py")
    digest = hashlib.sha256(repr((WHEELS, EMPY, jazzy_oracle.JAZZY_WHEELS)).encode())
    for f in [script, *sorted(UPSTREAM.glob("*/*/*"))]:
        digest.update(str(f.relative_to(UPSTREAM.parent)).encode() + b"\0" + f.read_bytes())
    answer = d / f"hashes-{digest.hexdigest()[:32]}.json"
    with jazzy_oracle.filling(d):
        if not answer.exists():
            hashes = _ask_rosidl(_fill(d), script)
            tmp = answer.with_suffix(".tmp")
            tmp.write_text(json.dumps(hashes))
            tmp.replace(answer)
    return json.loads(answer.read_text())


def _ask_rosidl(site: Path, script: Path) -> dict[str, str]:
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        spec = {"packages": {p: str(UPSTREAM / p) for p in packages()}, "includes": _includes(work),
                "out": str(work / "out")}
        (work / "spec.json").write_text(json.dumps(spec))
        # -S -E: only the standard library and the unpacked rosidl modules, nothing of the project's venv
        code = f"import sys; sys.path[:0] = [{str(site)!r}]; sys.argv = ['x', {str(work / 'spec.json')!r}]; " \
               f"exec(compile(open({str(script)!r}).read(), {str(script)!r}, 'exec'))"
        res = subprocess.run([sys.executable, "-S", "-E", "-c", code], capture_output=True, text=True,
                             timeout=300, check=False)
        assert res.returncode == 0, res.stderr[-3000:]
        return json.loads(res.stdout.strip().splitlines()[-1])


def upstream_texts(package: str) -> dict[str, str]:
    """pkg/msg/T or pkg/srv/T → the upstream file's text."""
    return {f"{package}/{f.parent.name}/{f.stem}": f.read_text()
            for f in sorted((UPSTREAM / package).glob("*/*")) if f.suffix in (".msg", ".srv")}
