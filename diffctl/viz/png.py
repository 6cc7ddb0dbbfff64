"""sensor_msgs/Image → PNG data URL for the page's camera panel, encoded with zlib (no imaging library).

Supported encodings are the ones cameras and depth sensors publish: rgb8, bgr8, rgba8, bgra8, mono8, mono16,
16UC1, 32FC1 (depth, scaled to 8-bit grey over its finite range). Large frames are decimated to MAX_WIDTH_PX.
"""

from __future__ import annotations

import base64
import struct
import zlib

import numpy as np

from diffctl.errors import MessageError

MAX_WIDTH_PX = 640
ENCODINGS = ("rgb8", "bgr8", "rgba8", "bgra8", "mono8", "8UC1", "mono16", "16UC1", "32FC1", "8UC3")


def _chunk(tag: bytes, data: bytes) -> bytes:
    return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF)


def encode_png(pixels: np.ndarray, level: int = 1) -> bytes:
    """PNG of an (h, w) grey or (h, w, 3) RGB uint8 array."""
    if pixels.dtype != np.uint8 or pixels.ndim not in (2, 3) or (pixels.ndim == 3 and pixels.shape[2] != 3):
        raise ValueError(f"need uint8 (h, w) or (h, w, 3), got {pixels.dtype} {pixels.shape}")
    h, w = pixels.shape[:2]
    colour_type = 0 if pixels.ndim == 2 else 2
    rows = pixels.reshape(h, -1)
    # Filter type 0 (None) on every row: fast, and zlib level 1 keeps a 320x240 frame in a few milliseconds.
    raw = np.hstack([np.zeros((h, 1), np.uint8), rows]).tobytes()
    ihdr = struct.pack(">IIBBBBB", w, h, 8, colour_type, 0, 0, 0)
    return (
        b"\x89PNG\r\n\x1a\n" + _chunk(b"IHDR", ihdr) + _chunk(b"IDAT", zlib.compress(raw, level)) + _chunk(b"IEND", b"")
    )


def image_pixels(
    width: int, height: int, encoding: str, step: int, data: bytes | np.ndarray, is_bigendian: bool = False
) -> np.ndarray:
    """The image as uint8 grey or RGB, decimated to at most MAX_WIDTH_PX wide."""
    enc = encoding.lower() if encoding.lower() in ("rgb8", "bgr8", "rgba8", "bgra8", "mono8", "mono16") else encoding
    channels = {"rgb8": 3, "bgr8": 3, "8UC3": 3, "rgba8": 4, "bgra8": 4, "mono8": 1, "8UC1": 1}.get(enc)
    buf = np.frombuffer(bytes(data) if not isinstance(data, np.ndarray) else data.tobytes(), np.uint8)
    if width <= 0 or height <= 0 or step <= 0:
        raise MessageError(f"image of {width}x{height} with step {step} has no pixels")
    if len(buf) < step * height:
        raise MessageError(f"image data holds {len(buf)} bytes, {height} rows of step {step} need {step * height}")
    rows = buf[: step * height].reshape(height, step)
    if channels is not None:
        if step < width * channels:
            raise MessageError(f"step {step} is shorter than {width} pixels of {encoding}")
        px = rows[:, : width * channels].reshape(height, width, channels)
        if enc in ("bgr8", "bgra8"):
            px = px[:, :, [2, 1, 0]]
        elif channels == 4:
            px = px[:, :, :3]
        elif channels == 1:
            px = px[:, :, 0]
    elif enc in ("mono16", "16UC1", "32FC1"):
        size = 2 if enc != "32FC1" else 4
        if step < width * size:
            raise MessageError(f"step {step} is shorter than {width} pixels of {encoding}")
        dtype = {2: ">u2" if is_bigendian else "<u2", 4: ">f4" if is_bigendian else "<f4"}[size]
        vals = rows[:, : width * size].copy().view(dtype).reshape(height, width).astype(np.float64)
        finite = np.isfinite(vals)
        lo, hi = (vals[finite].min(), vals[finite].max()) if finite.any() else (0.0, 1.0)
        scaled = np.where(finite, (vals - lo) / (hi - lo if hi > lo else 1.0) * 255.0, 0.0)
        px = scaled.astype(np.uint8)
    else:
        raise MessageError(f"image encoding {encoding!r} is not shown; valid: {', '.join(ENCODINGS)}")
    stride = max(1, -(-width // MAX_WIDTH_PX))
    return np.ascontiguousarray(px[::stride, ::stride])


def image_data_url(msg: object) -> tuple[str, int, int]:
    """(data URL, width, height) of a sensor_msgs/Image message."""
    px = image_pixels(
        int(msg.width),
        int(msg.height),
        str(msg.encoding),
        int(msg.step),
        msg.data,  # type: ignore[attr-defined]
        bool(msg.is_bigendian),
    )  # type: ignore[attr-defined]
    return "data:image/png;base64," + base64.b64encode(encode_png(px)).decode(), px.shape[1], px.shape[0]
