"""Try TCP connections and print how each went, as JSON: `python probe_connect.py HOST PORT [PORT…]`.

Run on the other test host (`ip netns exec B …`): "refused" means the host answered that nothing listens
there for it, "connected" that something accepts, "timeout" that nothing answered at all.
"""

from __future__ import annotations

import json
import socket
import sys


def probe(host: str, port: int, timeout_s: float = 2.0) -> str:
    try:
        with socket.create_connection((host, port), timeout=timeout_s):
            return "connected"
    except ConnectionRefusedError:
        return "refused"
    except TimeoutError:
        return "timeout"
    except OSError as e:
        return f"error: {e}"


if __name__ == "__main__":
    host, ports = sys.argv[1], [int(p) for p in sys.argv[2:]]
    print(json.dumps({str(p): probe(host, p) for p in ports}))
