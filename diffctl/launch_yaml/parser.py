"""The YAML frontend's `Parser`: reads `.launch.yaml` files (registered as the 'yaml' frontend)."""

from __future__ import annotations

from typing import Any, TextIO

import yaml

from diffctl.launch import frontend
from diffctl.launch.utilities.typing_file_path import FilePath

from .entity import Entity, LocatedDict

_Base = getattr(yaml, 'CSafeLoader', yaml.SafeLoader)


class _LocatingLoader(_Base):  # type: ignore[misc, valid-type]
    """YAML's safe loader, whose mappings remember their file and line."""

    source = '<string>'


def _mapping(loader: _LocatingLoader, node: yaml.MappingNode) -> LocatedDict:
    mapping = LocatedDict()
    mapping.source = loader.source
    mapping.line = node.start_mark.line + 1
    yield mapping
    mapping.update(loader.construct_mapping(node, deep=True))
    # the text each scalar value was written as: where text is expected, `respawn: true` is read as 'true'
    mapping.texts = {
        key.value: value.value
        for key, value in node.value
        if isinstance(key, yaml.ScalarNode) and isinstance(value, yaml.ScalarNode)
    }


_LocatingLoader.add_constructor('tag:yaml.org,2002:map', _mapping)


def _load(stream: Any, source: str) -> Any:
    loader = _LocatingLoader(stream)
    loader.source = source
    try:
        return loader.get_single_data()
    finally:
        loader.dispose()


class Parser(frontend.Parser):
    """Loads YAML launch files."""

    @classmethod
    def load(cls, file: FilePath | TextIO) -> tuple[Entity, Parser]:
        """(root entity, parser) of a YAML file (a path or an open file)."""
        try:
            fileobj = open(file)  # noqa: SIM115 (closed below)
            opened = True
        except TypeError:
            fileobj, opened = file, False
        try:
            source = getattr(fileobj, 'name', '<string>')
            tree = _load(fileobj, source if isinstance(source, str) else '<string>')
        finally:
            if opened:
                fileobj.close()
        if not isinstance(tree, dict) or len(tree) != 1:
            raise RuntimeError('Expected only one root')
        (type_name, body), = tree.items()
        return Entity(body, type_name), cls()

    @classmethod
    def get_file_extensions(cls) -> set[str]:
        return {'launch.yaml', 'launch.yml', 'yaml', 'yml', 'launch'}
