"""`diffctl fuel download URI`: fetch a Fuel model into Gazebo's cache, as `gz fuel download -u URI` does."""

from __future__ import annotations

import click

from diffctl.errors import ConfigError, RuntimeFailure


@click.group()
def fuel() -> None:
    """Gazebo Fuel models in Gazebo's cache (gz fuel).

    \b
    Example:
      diffctl fuel download "https://fuel.gazebosim.org/1.0/OpenRobotics/models/Construction Cone"
    """


@fuel.command()
@click.argument("uri")
def download(uri: str) -> None:
    """Download the model or world URI names into $GZ_FUEL_CACHE_PATH (default ~/.gz/fuel)."""
    from diffctl.console import info
    from diffctl.fuel.cache import cached_model
    from diffctl.fuel.download import DownloadError, download_model
    from diffctl.fuel.uri import parse_fuel_uri

    ref = parse_fuel_uri(uri)
    if ref is None or ref.file is not None:
        raise ConfigError(
            f"fuel download: {uri!r} is not a Fuel model or world URL",
            hint="e.g. https://fuel.gazebosim.org/1.0/OpenRobotics/models/Sun or …/worlds/<name>/<version>",
        )
    cached = cached_model(ref)
    if cached is not None and ref.version is not None:
        info(f"already cached: {cached}")
        return
    try:
        folder = download_model(ref)
    except DownloadError as e:
        raise RuntimeFailure(f"fuel download: {e}") from None
    info(f"saved: {folder}")
