"""The XML frontend's `Parser`: reads `.launch.xml` files (registered as the 'xml' frontend)."""

from __future__ import annotations

import io
import xml.etree.ElementTree as ET

from diffctl.launch import frontend

from .entity import Entity, remember_location


def _read(file: str | io.TextIOBase) -> ET.Element:
    """The root element of an XML file, each element's line remembered."""
    import xml.parsers.expat

    fileobj = open(file, 'rb') if isinstance(file, str) else file  # noqa: SIM115 (closed below)
    source = file if isinstance(file, str) else getattr(fileobj, 'name', '<string>')
    if not isinstance(source, str):
        source = '<string>'
    try:
        text = fileobj.read()
    finally:
        if fileobj is not file:
            fileobj.close()
    builder = ET.TreeBuilder()
    parser = xml.parsers.expat.ParserCreate()

    def start(tag: str, attributes: dict) -> None:
        remember_location(builder.start(tag, attributes), source, parser.CurrentLineNumber)

    parser.StartElementHandler = start
    parser.EndElementHandler = builder.end
    parser.CharacterDataHandler = builder.data
    parser.buffer_text = True
    try:
        parser.Parse(text, True)
    except xml.parsers.expat.ExpatError as e:
        raise ET.ParseError(f'{source}:{e.lineno}: {xml.parsers.expat.ErrorString(e.code)} '
                            f'(column {e.offset + 1})') from None
    return builder.close()


class Parser(frontend.Parser):
    """Loads XML launch files."""

    @classmethod
    def load(cls, file: str | io.TextIOBase) -> tuple[Entity, Parser]:
        """(root entity, parser) of an XML file (a path or an open file)."""
        return Entity(_read(file)), cls()

    @classmethod
    def get_file_extensions(cls) -> set[str]:
        return {'launch.xml', 'xml', 'launch'}
