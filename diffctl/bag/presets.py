"""`--storage-preset-profile`: the MCAP writer settings of rosbag2_storage_mcap's preset profiles (Jazzy).

rosbag2's plugin starts from mcap's McapWriterOptions (768 KiB chunks), sets its own defaults (chunks
uncompressed, no chunk CRCs) and then applies the preset:

| preset       | chunks          | compression          | chunk CRCs | summary CRC |
|--------------|-----------------|----------------------|------------|-------------|
| none / ""    | 768 KiB         | none                 | no         | yes         |
| `fastwrite`  | none (unchunked)| none                 | —          | no          |
| `zstd_fast`  | 768 KiB         | zstd, level Fastest  | no         | yes         |
| `zstd_small` | 4 MiB           | zstd, level Slowest  | no         | yes         |

There is no lz4 preset. Where the `mcap` package's Writer cannot follow (it has one switch for chunk and
summary CRCs, and compresses zstd at zstandard's default level), `WriterOptions` says so.
"""

from __future__ import annotations

import difflib
from dataclasses import dataclass

from diffctl.errors import ConfigError

KIB = 1024
MCAP_DEFAULT_CHUNK_BYTES = 768 * KIB  # mcap's McapWriterOptions::chunkSize, which rosbag2 keeps


@dataclass(frozen=True)
class McapPreset:
    name: str
    use_chunking: bool
    chunk_size_bytes: int
    compression: str  # "none" | "zstd"
    zstd_level: str  # mcap's CompressionLevel the preset asks for ("" when uncompressed)
    chunk_crcs: bool
    summary_crc: bool


PRESETS = {
    "none": McapPreset("none", True, MCAP_DEFAULT_CHUNK_BYTES, "none", "", chunk_crcs=False, summary_crc=True),
    "fastwrite": McapPreset("fastwrite", False, MCAP_DEFAULT_CHUNK_BYTES, "none", "", chunk_crcs=False,
                            summary_crc=False),
    "zstd_fast": McapPreset("zstd_fast", True, MCAP_DEFAULT_CHUNK_BYTES, "zstd", "Fastest", chunk_crcs=False,
                            summary_crc=True),
    "zstd_small": McapPreset("zstd_small", True, 4 * 1024 * KIB, "zstd", "Slowest", chunk_crcs=False,
                             summary_crc=True),
}


def preset(name: str) -> McapPreset:
    """The preset of `--storage-preset-profile NAME` ("" is rosbag2's default, as `none`)."""
    found = PRESETS.get(name or "none")
    if found is None:
        close = difflib.get_close_matches(name, PRESETS, n=1)
        raise ConfigError(
            f"--storage-preset-profile {name!r} is not an MCAP storage preset",
            hint=(f"did you mean {close[0]!r}? " if close else "") + "valid: " + ", ".join(PRESETS),
        )
    return found
