"""Robot and world descriptions: SDF parsed with lxml into frozen dataclasses with resolved poses (no bus)."""
