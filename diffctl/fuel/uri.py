"""Fuel URLs parsed as gz-fuel-tools parses them (FuelClient.cc's model and model-file URL patterns).

`https://fuel.gazebosim.org/1.0/OpenRobotics/models/Ground Plane/2` names a model; `…/<N|tip>/files/<path>`
one file inside it; `…/worlds/<name>` a world, the same way. The API version and the model version are
optional (absent = tip); owner and name are lowercased, as ModelIdentifier stores them; a space and `%20`
stay distinct (nothing decodes `%20`).
"""

from __future__ import annotations

import re
from dataclasses import dataclass

_HEAD = (
    r"^(?P<scheme>[A-Za-z0-9.+\-]+)://(?P<host>[^/\s]+)/+(?P<api>[0-9]+\.[0-9]+)?/*(?P<owner>[^/\s]+)/+"
    r"(?P<kind>models|worlds)/+"
)
MODEL_RE = re.compile(_HEAD + r"(?P<name>[^/]+)/*(?P<version>[0-9]*|tip)/?$")
MODEL_FILE_RE = re.compile(_HEAD + r"(?P<name>[^/]+)/+(?P<version>[0-9]*|tip)/+files/+(?P<path>.*?)/?$")
DEFAULT_API = "1.0"


@dataclass(frozen=True)
class FuelRef:
    """One Fuel model (and optionally a file inside it), as the cache and the REST API key it."""

    scheme: str
    host: str  # as written, with any port: the cache folder is derived from it
    owner: str  # lowercased
    name: str  # lowercased, spaces and %20 verbatim
    version: int | None  # None = tip: the highest version at hand
    file: str | None = None  # path inside the model for a file URL
    api: str = DEFAULT_API
    original: str = ""
    kind: str = "models"  # or "worlds" (a world URL, as `gz sim URL` takes it)

    @property
    def server(self) -> str:
        return f"{self.scheme}://{self.host}"

    @property
    def model_url(self) -> str:
        version = "tip" if self.version is None else str(self.version)
        return f"{self.server}/{self.api}/{self.owner}/{self.kind}/{self.name}/{version}"


def is_fuel_uri(uri: str) -> bool:
    return parse_fuel_uri(uri) is not None


def parse_fuel_uri(uri: str) -> FuelRef | None:
    """The model or world (or a file of one) a URL names, or None when it is not a Fuel URL."""
    text = uri.strip()
    m = MODEL_FILE_RE.match(text)
    file = None
    if m is not None:
        file = m.group("path")
    else:
        m = MODEL_RE.match(text)
        if m is None:
            return None
    version_text = m.group("version")
    version = int(version_text) if version_text.isdigit() else None
    if version == 0:
        version = None  # Fuel's versions start at 1; gz-fuel-tools treats 0 as unset (tip)
    return FuelRef(
        scheme=m.group("scheme"),
        host=m.group("host"),
        owner=m.group("owner").lower(),
        name=m.group("name").lower(),
        version=version,
        file=file,
        api=m.group("api") or DEFAULT_API,
        original=text,
        kind=m.group("kind"),
    )
