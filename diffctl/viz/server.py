"""HTTP and WebSocket server of the visualizer: the static page, live streams, and the page's commands.

One asyncio loop serves the files in `static/` through websockets' `process_request` hook and one socket
per open page on `/ws`. A tick at the display frame rate sends each page the streams whose content
changed, each capped at its own rate; a slow page skips ticks instead of queueing them. Commands that
publish need the token; a teleop command not refreshed within the timeout is followed by a zero.
"""

from __future__ import annotations

import asyncio
import contextlib
import errno
import json
import math
import time
from dataclasses import dataclass, field
from http import HTTPStatus
from pathlib import Path
from typing import Any

import yaml
from websockets.asyncio.server import Server, ServerConnection, serve
from websockets.datastructures import Headers
from websockets.exceptions import ConnectionClosed
from websockets.http11 import Request, Response

from diffctl import __version__
from diffctl.errors import ConfigError, DiffctlError, MessageError
from diffctl.viz.bus_feed import BusFeed
from diffctl.viz.commands import PublishJob, TeleopCommand, parse_publish, parse_teleop
from diffctl.viz.png import image_data_url
from diffctl.viz.rviz_config import RvizConfig
from diffctl.viz.scene import Scene
from diffctl.viz.security import HostPolicy, query_token, token_matches

STATIC_DIR = Path(__file__).parent / "static"
STATIC_FILES = {
    "/": ("index.html", "text/html; charset=utf-8"),
    "/index.html": ("index.html", "text/html; charset=utf-8"),
    "/viz.js": ("viz.js", "text/javascript; charset=utf-8"),
    "/panels.js": ("panels.js", "text/javascript; charset=utf-8"),
    "/viz.css": ("viz.css", "text/css; charset=utf-8"),
}
# The page may load nothing from anywhere else: no CDN, no fonts, works offline.
CSP = (
    "default-src 'none'; script-src 'self'; style-src 'self'; img-src 'self' data:; connect-src 'self'; "
    "base-uri 'none'; form-action 'none'; frame-ancestors 'none'"
)
MAX_JOBS_PER_PAGE = 16
# A taken port moves the page to the next free one among this many (several rviz2 run side by side).
PORT_SEARCH = 100
TELEOP_MIN_INTERVAL_S = 0.02


class _TemplateDumper(yaml.SafeDumper):
    """Mappings one field per line, arrays on one line: a covariance stays readable."""


_TemplateDumper.add_representer(list, lambda d, v: d.represent_sequence("tag:yaml.org,2002:seq", v, flow_style=True))


def _finite(value: Any) -> Any:
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if isinstance(value, dict):
        return {k: _finite(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_finite(v) for v in value]
    return value


def to_json(payload: dict[str, Any]) -> str:
    try:
        return json.dumps(payload, separators=(",", ":"), allow_nan=False)
    except ValueError:  # JSON has no NaN; the page shows null as "—"
        return json.dumps(_finite(payload), separators=(",", ":"), allow_nan=False)


@dataclass(eq=False)
class _Page:
    ws: ServerConnection
    authorized: bool
    fixed: str
    image_topic: str | None = None
    sent: dict[str, int] = field(default_factory=dict)
    next_due: dict[str, float] = field(default_factory=dict)
    teleop: TeleopCommand | None = None  # the last non-zero command, while it is held
    teleop_at: float = 0.0
    jobs: dict[str, asyncio.Task] = field(default_factory=dict)
    sending: asyncio.Task | None = None


class VizServer:
    def __init__(self, scene: Scene, feed: BusFeed, config: RvizConfig, token: str, log: Any) -> None:
        self.scene = scene
        self.feed = feed
        self.config = config
        self.settings = scene.settings
        self.token = token
        self.log = log
        self.pages: set[_Page] = set()
        self.policy = HostPolicy(self.settings.host, self.settings.port)
        self._server: Server | None = None
        self._static = {path: ((STATIC_DIR / name).read_bytes(), ctype) for path, (name, ctype) in STATIC_FILES.items()}
        rate = min(self.settings.frame_rate_hz, config.frame_rate_hz)
        self.periods = {
            "robot": 0.0,
            "frame": 1.0 / rate,
            "scan": 1.0 / self.settings.scan_rate_hz,
            "paths": 0.5,
            "status": 0.1,
            "graph": 1.0,
            "image": 1.0 / self.settings.image_rate_hz,
        }
        self.tick_s = 1.0 / rate
        self.fixed_default = self.settings.fixed_frame or config.fixed_frame

    # ---- lifetime ----------------------------------------------------------------------------------------

    async def start(self) -> int:
        """Bind and return the port: the one asked for, else (taken by another visualizer, say) the next free
        one, said in one line; a free one of the system's choosing for port 0."""
        first = self.settings.port
        last = min(65535, first + PORT_SEARCH) if first else 0
        for port in range(first, last + 1):
            try:
                self._server = await serve(
                    self._handle,
                    self.settings.host,
                    port,
                    process_request=self._process_request,
                    max_size=256 * 1024,
                    server_header=f"diffctl-viz/{__version__}",
                    compression=None,
                )
                break
            except OSError as e:
                if e.errno == errno.EADDRINUSE and port < last:
                    continue
                raise ConfigError(
                    f"cannot listen on {self.settings.host}:{port}: {e.strerror or e}"
                    + (f" (ports {first}..{port} are all taken)" if port > first else ""),
                    hint="pass another --port, or --port 0 to pick a free one",
                ) from None
        port = self._server.sockets[0].getsockname()[1] if self._server.sockets else port
        if first and port != first:
            self.log.warn(f"port {first} is taken (another visualizer?): serving on port {port}")
        self.policy = HostPolicy(self.settings.host, port)
        return port

    async def run(self, stop: asyncio.Event) -> None:
        tasks = [asyncio.create_task(self._tick_loop()), asyncio.create_task(self._poll_loop())]
        try:
            await stop.wait()
        finally:
            for t in tasks:
                t.cancel()
            for page in list(self.pages):
                self._release(page, "visualizer stopping")
            if self._server is not None:
                self._server.close()
                with contextlib.suppress(Exception):
                    await asyncio.wait_for(self._server.wait_closed(), 1.0)

    # ---- HTTP ------------------------------------------------------------------------------------------

    def _response(self, status: HTTPStatus, body: bytes, ctype: str) -> Response:
        headers = Headers()
        headers["Content-Type"] = ctype
        headers["Content-Length"] = str(len(body))
        headers["Cache-Control"] = "no-store"
        headers["Content-Security-Policy"] = CSP
        headers["X-Content-Type-Options"] = "nosniff"
        headers["Referrer-Policy"] = "no-referrer"
        headers["Connection"] = "close"
        return Response(status.value, status.phrase, headers, body)

    def _process_request(self, connection: ServerConnection, request: Request) -> Response | None:
        host = request.headers.get("Host")
        if not self.policy.host_ok(host):
            return self._response(HTTPStatus.FORBIDDEN, b"unknown Host header\n", "text/plain; charset=utf-8")
        path = request.path.split("?", 1)[0]
        if path == "/ws":
            if not self.policy.origin_ok(request.headers.get("Origin"), host):
                self.log.warn(f"refused a WebSocket from Origin {request.headers.get('Origin')!r}")
                return self._response(
                    HTTPStatus.FORBIDDEN, b"cross-origin WebSocket refused\n", "text/plain; charset=utf-8"
                )
            return None  # continue with the WebSocket handshake
        if path in self._static:
            body, ctype = self._static[path]
            return self._response(HTTPStatus.OK, body, ctype)
        return self._response(HTTPStatus.NOT_FOUND, b"not found\n", "text/plain; charset=utf-8")

    # ---- WebSocket -------------------------------------------------------------------------------------

    async def _handle(self, ws: ServerConnection) -> None:
        authorized = token_matches(query_token(ws.request.path if ws.request else ""), self.token)
        page = _Page(ws, authorized, self.fixed_default)
        self.pages.add(page)
        self.feed.watch_live(True)
        self.log.info(f"page connected from {ws.remote_address[0]} ({'can' if authorized else 'cannot'} drive)")
        try:
            await ws.send(to_json(self._hello(page)))
            async for raw in ws:
                await self._on_message(page, raw)
        except ConnectionClosed:
            pass
        finally:
            self.pages.discard(page)
            if not self.pages:
                self.feed.watch_live(False)
            self._release(page, "page closed")
            self._update_image_watch()

    def _hello(self, page: _Page) -> dict[str, Any]:
        s = self.settings
        from diffctl.interfaces import types

        return {
            "type": "hello",
            "version": __version__,
            "authorized": page.authorized,
            "config": self.config.to_json(),
            "fixed_frame": page.fixed,
            "teleop": {
                "topic": s.teleop_topic,
                "stamped": s.teleop_stamped,
                "max_linear": s.max_linear_mps,
                "max_angular": s.max_angular_radps,
                "timeout": s.teleop_timeout_s,
            },
            "publisher_max_rate": s.publisher_max_rate_hz,
            "types": [t for t in types.known_types() if "/msg/" in t],
        }

    async def _on_message(self, page: _Page, raw: str | bytes) -> None:
        try:
            msg = json.loads(raw)
        except ValueError:
            await self._reply(page, {"type": "error", "text": "not JSON"})
            return
        if not isinstance(msg, dict):
            return
        op = msg.get("op")
        try:
            if op == "auth":
                page.authorized = token_matches(str(msg.get("token", "")), self.token)
                await self._reply(
                    page,
                    {
                        "type": "auth",
                        "authorized": page.authorized,
                        "text": None if page.authorized else "wrong token: commands refused",
                    },
                )
            elif op == "fixed_frame":
                frame = msg.get("frame")
                if isinstance(frame, str) and 0 < len(frame) <= 256:
                    page.fixed = frame.lstrip("/")
                    page.sent.clear()
            elif op == "image":
                topic = msg.get("topic")
                page.image_topic = topic if isinstance(topic, str) and topic.startswith("/") else None
                page.sent.pop("image", None)
                self._update_image_watch()
            elif op == "template":
                await self._reply(page, self._template(msg.get("type")))
            elif op in ("teleop", "publish", "publish_stop"):
                if not page.authorized:
                    self.log.warning(f"refused '{op}' from a page without the token", throttle_duration_sec=5.0)
                    await self._reply(
                        page,
                        {
                            "type": "refused",
                            "op": op,
                            "text": "refused: commands that move the robot need the token printed "
                            "at start (open the URL with ?token=…)",
                        },
                    )
                elif op == "teleop":
                    await self._teleop(page, msg)
                elif op == "publish":
                    await self._publish(page, msg)
                else:
                    task = page.jobs.pop(str(msg.get("id", "")), None)
                    if task:
                        task.cancel()
                    await self._reply(page, {"type": "publish_state", "id": str(msg.get("id", "")), "running": False})
            else:
                await self._reply(page, {"type": "error", "text": f"unknown op {op!r}"})
        except DiffctlError as e:
            await self._reply(page, {"type": "error", "op": op, "id": msg.get("id"), "text": str(e)})

    @staticmethod
    def _template(type_name: Any) -> dict[str, Any]:
        """The fields of a message type with their defaults, as YAML for the publisher panel's body."""
        from diffctl.interfaces import types

        if not isinstance(type_name, str) or not type_name.strip():
            raise MessageError("message type is missing, e.g. geometry_msgs/msg/TwistStamped")
        t = types.check(type_name)
        text = yaml.dump(types.to_dict(types.new(t, {})), Dumper=_TemplateDumper, sort_keys=False, width=100)
        return {"type": "template", "type_name": t, "yaml": text}

    async def _reply(self, page: _Page, payload: dict[str, Any]) -> None:
        with contextlib.suppress(ConnectionClosed):
            await page.ws.send(to_json(payload))

    async def _teleop(self, page: _Page, msg: dict[str, Any]) -> None:
        cmd = parse_teleop(msg, self.settings)
        now = time.monotonic()
        if not cmd.is_zero and page.teleop == cmd and now - page.teleop_at < TELEOP_MIN_INTERVAL_S:
            return  # a page repeating itself faster than any controller needs
        first = page.teleop is None or page.teleop.topic != cmd.topic or page.teleop.stamped != cmd.stamped
        self.feed.publish_teleop(cmd)
        if page.teleop is not None and (page.teleop.topic, page.teleop.stamped) != (cmd.topic, cmd.stamped):
            self.feed.publish_teleop(page.teleop.zero())  # switching topic must not leave the old one moving
        page.teleop, page.teleop_at = (None if cmd.is_zero else cmd), now
        if first and not cmd.is_zero:
            others = self.feed.other_types(cmd.topic, cmd.type_name)
            if others:
                await self._reply(
                    page,
                    {
                        "type": "notice",
                        "level": "warn",
                        "text": f"{cmd.topic} is used with {', '.join(others)}, not {cmd.type_name}: "
                        "the controller will not see these commands (toggle 'stamped')",
                    },
                )

    async def _publish(self, page: _Page, msg: dict[str, Any]) -> None:
        job = parse_publish(msg, self.settings)
        old = page.jobs.pop(job.id, None)
        if old:
            old.cancel()
        if len(page.jobs) >= MAX_JOBS_PER_PAGE:
            raise ConfigError(f"at most {MAX_JOBS_PER_PAGE} publishers run at once; stop one first")
        self.feed.publish_job(job)
        if job.rate_hz > 0:
            page.jobs[job.id] = asyncio.create_task(self._repeat(page, job))
        await self._reply(
            page,
            {
                "type": "publish_state",
                "id": job.id,
                "running": job.rate_hz > 0,
                "text": f"published {job.type_name} on {job.topic}"
                + (f" at {job.rate_hz:g} Hz" if job.rate_hz > 0 else " once"),
            },
        )

    async def _repeat(self, page: _Page, job: PublishJob) -> None:
        period = 1.0 / job.rate_hz
        next_t = time.monotonic() + period
        while True:
            await asyncio.sleep(max(0.0, next_t - time.monotonic()))
            next_t += period
            try:
                self.feed.publish_job(job)
            except DiffctlError as e:
                await self._reply(page, {"type": "error", "op": "publish", "id": job.id, "text": str(e)})
                return

    def _release(self, page: _Page, why: str) -> None:
        """Stop what a page was doing: its publishers, and a held teleop command gets its zero."""
        for task in page.jobs.values():
            task.cancel()
        page.jobs.clear()
        if page.teleop is not None:
            with contextlib.suppress(DiffctlError):
                self.feed.publish_teleop(page.teleop.zero())
            self.log.info(f"teleop: sent zero on {page.teleop.topic} ({why})")
            page.teleop = None

    def _update_image_watch(self) -> None:
        wanted = {p.image_topic for p in self.pages if p.image_topic}
        known = self.config.topics("image", enabled_only=False)
        for topic in known:
            self.feed.watch_image(topic, topic in wanted)
        for topic in wanted - set(known):
            self.feed.watch_image(topic, True)

    # ---- periodic work -----------------------------------------------------------------------------------

    async def _poll_loop(self) -> None:
        while True:
            with contextlib.suppress(Exception):
                await asyncio.to_thread(self.feed.poll_graph, bool(self.pages))
                await asyncio.to_thread(self.feed.poll_controllers)
            await asyncio.sleep(1.0)

    async def _tick_loop(self) -> None:
        while True:
            started = time.monotonic()
            try:
                await self._tick(started)
            except Exception as e:  # a bad frame must not stop the page from updating
                self.log.error(f"frame failed: {type(e).__name__}: {e}", throttle_duration_sec=5.0)
            await asyncio.sleep(max(0.0, self.tick_s - (time.monotonic() - started)))

    async def _tick(self, now: float) -> None:
        for page in list(self.pages):
            if page.teleop is not None and now - page.teleop_at > self.settings.teleop_timeout_s:
                self._release(page, f"no command for {self.settings.teleop_timeout_s:g} s")
                await self._reply(
                    page,
                    {"type": "notice", "level": "warn", "text": "teleop: no command received in time, robot stopped"},
                )
        cache: dict[tuple[str, str], str] = {}
        versions = dict(self.scene.versions)
        for page in list(self.pages):
            if page.sending is not None and not page.sending.done():
                continue  # this page is slow: skip, the next tick carries newer data anyway
            out: list[str] = []
            for stream, period in self.periods.items():
                if page.sent.get(stream) == versions[stream] or now < page.next_due.get(stream, 0.0):
                    continue
                if stream == "image" and not page.image_topic:
                    continue
                key = (stream, page.fixed if stream in ("frame", "scan", "paths") else page.image_topic or "")
                if key not in cache:
                    view = await self._view(stream, page)
                    cache[key] = to_json(view) if view is not None else ""
                if cache[key]:
                    out.append(cache[key])
                page.sent[stream] = versions[stream]
                page.next_due[stream] = now + period
            if out:
                page.sending = asyncio.create_task(self._send_all(page, out))

    async def _view(self, stream: str, page: _Page) -> dict[str, Any] | None:
        s = self.scene
        if stream == "robot":
            return s.robot_view()
        if stream == "frame":
            return s.frame_view(page.fixed)
        if stream == "scan":
            return s.scan_view(page.fixed)
        if stream == "paths":
            return s.paths_view(page.fixed)
        if stream == "status":
            return s.status_view()
        if stream == "graph":
            return s.graph_view()
        msg = s.latest_image(page.image_topic or "")
        if msg is None:
            return None
        try:
            url, w, h = await asyncio.to_thread(image_data_url, msg)
        except DiffctlError as e:
            return {"type": "image", "topic": page.image_topic, "error": str(e)}
        return {
            "type": "image",
            "topic": page.image_topic,
            "url": url,
            "width": w,
            "height": h,
            "encoding": str(msg.encoding),
        }

    async def _send_all(self, page: _Page, texts: list[str]) -> None:
        with contextlib.suppress(ConnectionClosed):
            for t in texts:
                await page.ws.send(t)
