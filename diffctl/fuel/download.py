"""Download a Fuel model into Gazebo's cache through Fuel's REST API, as FuelClient::DownloadModel does.

`GET <server>/<api>/<escaped owner/models/name/version/name.zip>?link=true`: the whole path escaped, `/`
included; a `text/plain` answer is a link to follow, a zip is the model. The version comes from the
`X-Ign-Resource-Version` header (1 when missing). The zip is unpacked into `<cache>/…/<name>/<N>/` and the
model's `model://<name>/…` file URIs are rewritten to Fuel file URLs (gz-fuel-tools' FixPaths), which the
cache then resolves. `$DIFFCTL_FUEL_SERVER` sends requests to another server (a local mirror, tests) while
the cache keeps the URI's host.
"""

from __future__ import annotations

import io
import os
import shutil
import sys
import tempfile
import urllib.error
import urllib.parse
import urllib.request
import zipfile
from collections.abc import Callable
from pathlib import Path

from lxml import etree

from diffctl import __version__
from diffctl.description.resources import model_file_in
from diffctl.fuel.cache import cache_root, is_complete, model_root
from diffctl.fuel.uri import FuelRef

SERVER_ENV = "DIFFCTL_FUEL_SERVER"
TIMEOUT_S = 20.0
ZIP_TYPES = ("application/zip", "binary/octet-stream", "application/octet-stream", "")
# Elements whose model:// URIs FixPaths rewrites: meshes, material scripts and PBR maps, actor skins/animations.
FIXED_TAGS = ("uri", "albedo_map", "normal_map", "metalness_map", "roughness_map", "emissive_map", "filename")


class DownloadError(Exception):
    """A download that did not produce a model; the message says why in one line."""


def server_url(ref: FuelRef) -> str:
    return (os.environ.get(SERVER_ENV, "").strip().rstrip("/")) or ref.server


def zip_url(ref: FuelRef) -> str:
    version = "tip" if ref.version is None else str(ref.version)
    route = urllib.parse.unquote(f"{ref.owner}/{ref.kind}/{ref.name}/{version}/{ref.name}.zip")
    return f"{server_url(ref)}/{ref.api}/{urllib.parse.quote(route, safe='')}?link=true"


def _get(url: str, progress: Callable[[int, int | None], None]) -> tuple[bytes, str, dict[str, str]]:
    request = urllib.request.Request(url, headers={"User-Agent": f"GazeboFuelTools-diffctl-{__version__}"})
    try:
        with urllib.request.urlopen(request, timeout=TIMEOUT_S) as response:
            total = response.headers.get("Content-Length")
            size = int(total) if total and total.isdigit() else None
            chunks: list[bytes] = []
            done = 0
            while True:
                chunk = response.read(65536)
                if not chunk:
                    break
                chunks.append(chunk)
                done += len(chunk)
                progress(done, size)
            ctype = (response.headers.get_content_type() if response.headers.get("Content-Type") else "").lower()
            return b"".join(chunks), ctype, {k.lower(): v for k, v in response.headers.items()}
    except urllib.error.HTTPError as e:
        raise DownloadError(f"the server answered {e.code} {e.reason} for {url}") from None
    except urllib.error.URLError as e:
        raise DownloadError(f"cannot reach {url}: {e.reason}") from None
    except OSError as e:  # timeouts, resets
        raise DownloadError(f"cannot reach {url}: {e}") from None


def fetch_zip(ref: FuelRef, progress: Callable[[int, int | None], None]) -> tuple[bytes, int]:
    """The model's zip and its version number."""
    url = zip_url(ref)
    for _ in range(3):  # a link answer points at the zip; gz-fuel-tools follows it the same way
        data, ctype, headers = _get(url, progress)
        if ctype == "text/plain":
            url = data.decode("utf-8", "replace").strip()
            continue
        if ctype not in ZIP_TYPES:
            raise DownloadError(f"invalid content-type of [{ctype}] from {url}")
        version_text = headers.get("x-ign-resource-version", "")
        version = int(version_text) if version_text.isdigit() and int(version_text) > 0 else (ref.version or 1)
        return data, version
    raise DownloadError(f"too many links from {zip_url(ref)}")


def _extract(data: bytes, dest: Path) -> None:
    try:
        archive = zipfile.ZipFile(io.BytesIO(data))
    except zipfile.BadZipFile:
        raise DownloadError("the server's answer is not a zip archive") from None
    root = dest.resolve()
    with archive:
        for info in archive.infolist():
            target = (root / info.filename).resolve()
            if root != target and root not in target.parents:
                raise DownloadError(f"the archive names a file outside the model: {info.filename!r}")
        archive.extractall(root)


def fix_paths(model_dir: Path, ref: FuelRef, version: int) -> None:
    """Rewrite `model://<name>/rest` to `<server>/<api>/<owner>/models/<name>/<N>/files/rest` in the model SDF."""
    sdf = model_file_in(model_dir)
    if sdf is None:
        return
    try:
        tree = etree.parse(str(sdf), etree.XMLParser(recover=True, remove_blank_text=False))
    except (etree.XMLSyntaxError, OSError):
        return  # the loader reports an unreadable file where it is used
    base = f"{ref.server}/{ref.api}/{ref.owner}/models/{ref.name}/{version}/files/"
    changed = False
    for el in tree.iter(*FIXED_TAGS):
        text = (el.text or "").strip()
        if text.startswith("model://"):
            rest = text[len("model://") :].partition("/")[2]
            el.text = base + rest
            changed = True
    if changed:
        tree.write(str(sdf), xml_declaration=True, encoding="utf-8")


def download_model(ref: FuelRef, out: Callable[[str], None] | None = None) -> Path:
    """Fetch `ref` into the cache; returns the version folder. Prints one progress line (updated in place)."""
    say = out or (lambda text: print(text, file=sys.stderr, end="", flush=True))
    label = ref.model_url

    def progress(done: int, total: int | None) -> None:
        of = f" of {total / 1024:.0f} kB" if total else ""
        say(f"\rDownloading Fuel {what} {label}: {done / 1024:.0f} kB{of}")

    what = "model" if ref.kind == "models" else "world"
    say(f"Downloading Fuel {what} {label} …")
    try:
        data, version = fetch_zip(ref, progress)
    finally:
        say("\n")
    dest = model_root(ref) / str(version)
    if dest.is_dir() and is_complete(dest, ref.kind):
        return dest
    dest.parent.mkdir(parents=True, exist_ok=True)
    tmp = Path(tempfile.mkdtemp(prefix=f".{version}-", dir=dest.parent))
    try:
        _extract(data, tmp)
        if not is_complete(tmp, ref.kind):
            top = "model.config" if ref.kind == "models" else "world file (.sdf)"
            raise DownloadError(f"the archive has no {top} at its top")
        if ref.kind == "models":
            fix_paths(tmp, ref, version)
        try:
            tmp.rename(dest)  # atomic: a concurrent reader sees the whole model or none
        except OSError:
            if not is_complete(dest, ref.kind):
                raise
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return dest


__all__ = ["SERVER_ENV", "DownloadError", "cache_root", "download_model", "zip_url"]
