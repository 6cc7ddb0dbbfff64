"""Version checks of launch_ros's extension points (`launch_ros.node_action`): caret ranges as npm has them."""

from __future__ import annotations


class PluginException(Exception):
    """An extension that cannot be used with this extension point."""


def _release(version: str) -> tuple[int, int, int]:
    """'1.2.3' → (1, 2, 3); missing parts are 0, anything after the numbers is ignored."""
    numbers = []
    for part in str(version).split(".")[:3]:
        digits = "".join(c for c in part if c.isdigit()) if not part.isdigit() else part
        numbers.append(int(digits or 0))
    return tuple([*numbers, 0, 0, 0][:3])  # type: ignore[return-value]


def get_upper_bound_caret_version(version: str) -> str:
    """The first version a `^version` range excludes: the next major, or the next minor below 1.0."""
    major, minor, _ = _release(version)
    return f"{major + 1}.0.0" if major > 0 else f"0.{minor + 1}.0"


def satisfies_version(version: str, caret_range: str) -> None:
    """Raise PluginException unless the extension point's `version` lies in the extension's `^x.y` range."""
    assert caret_range.startswith("^"), "Only supports caret ranges"
    wanted = caret_range[1:]
    if _release(version) < _release(wanted):
        raise PluginException(f"Extension point is too old ({version}), the extension requires '{wanted}'")
    if _release(version) >= _release(get_upper_bound_caret_version(wanted)):
        raise PluginException(f"Extension point is newer ({version}), than what the extension supports '{wanted}'")
