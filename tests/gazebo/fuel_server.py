"""A Fuel server on loopback that answers as fuel.gazebosim.org does for model downloads (test helper).

`GET /1.0/<owner%2Fmodels%2Fname%2Fversion%2Fname.zip>?link=true`, the route escaped whole: a zip of the model
with `X-Ign-Resource-Version`, or (with `link=True`) a text/plain link to the zip, as the real server answers.
"""

from __future__ import annotations

import io
import threading
import urllib.parse
import zipfile
from collections.abc import Iterator
from contextlib import contextmanager
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer


class FuelModels:
    def __init__(self) -> None:
        self.models: dict[tuple[str, str], dict[int, dict[str, str]]] = {}  # (owner, name) → version → files
        self.requests: list[str] = []
        self.link = False

    def add(self, owner: str, name: str, version: int, files: dict[str, str]) -> None:
        self.models.setdefault((owner.lower(), name.lower()), {})[version] = files

    def zip_of(self, owner: str, name: str, version: str) -> tuple[bytes, int] | None:
        versions = self.models.get((owner, name))
        if not versions:
            return None
        number = max(versions) if version == "tip" else int(version)
        if number not in versions:
            return None
        buf = io.BytesIO()
        with zipfile.ZipFile(buf, "w") as z:
            for path, text in versions[number].items():
                z.writestr(path, text)
        return buf.getvalue(), number


@contextmanager
def fuel_server(models: FuelModels) -> Iterator[str]:
    class Handler(BaseHTTPRequestHandler):
        def log_message(self, *args: object) -> None:
            pass

        def do_GET(self) -> None:
            models.requests.append(self.path)
            path, _, query = self.path.partition("?")
            if path.startswith("/zips/"):
                owner, name, version = (urllib.parse.unquote(p) for p in path[len("/zips/") :].split("/"))
                return self._zip(owner, name, version)
            api, _, route = path.lstrip("/").partition("/")
            parts = urllib.parse.unquote(route).split("/")
            if api != "1.0" or len(parts) != 5 or parts[1] not in ("models", "worlds") or parts[4] != parts[2] + ".zip":
                return self._answer(404, "text/html", b"not found")
            owner, _, name, version, _ = parts
            if models.link and "link=true" in query:
                q = urllib.parse.quote
                link = f"http://{self.headers['Host']}/zips/{q(owner)}/{q(name)}/{version}"
                return self._answer(200, "text/plain", link.encode())
            return self._zip(owner, name, version)

        def _zip(self, owner: str, name: str, version: str) -> None:
            found = models.zip_of(owner, name, version)
            if found is None:
                return self._answer(404, "text/html", b"not found")
            data, number = found
            self._answer(200, "application/zip", data, {"X-Ign-Resource-Version": str(number)})

        def _answer(self, code: int, ctype: str, body: bytes, headers: dict[str, str] | None = None) -> None:
            self.send_response(code)
            self.send_header("Content-Type", ctype)
            self.send_header("Content-Length", str(len(body)))
            for k, v in (headers or {}).items():
                self.send_header(k, v)
            self.end_headers()
            self.wfile.write(body)

    server = ThreadingHTTPServer(("127.0.0.1", 0), Handler)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        yield f"http://127.0.0.1:{server.server_address[1]}"
    finally:
        server.shutdown()
        server.server_close()
        thread.join(5)
