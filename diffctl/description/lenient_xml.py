"""Parse XML as leniently as sdformat's TinyXML2 does, keeping every element's line number.

Strict libxml2 rejects files Gazebo loads every day: `--` inside a comment (gz-sim's own empty.sdf has one),
whitespace before `<?xml?>`, a bare `&` or an unknown entity such as `&nbsp;` (TinyXML2 keeps them literally),
an undeclared prefix like `<gz:x>`, `<` inside an attribute value, content after the root element. Valid XML
takes the strict path unchanged; otherwise a pre-pass rewrites the first three without moving a line, and
libxml2's recovery mode takes the rest. What TinyXML2 also rejects (mismatched or unclosed tags, duplicate
attributes) stays an error at its line.
"""

from __future__ import annotations

import re

from lxml import etree

_COMMENT = re.compile(rb"<!--.*?-->", re.S)
_LATE_DECLARATION = re.compile(rb"<\?xml\s[^>]*\?>")
_BARE_AMPERSAND = re.compile(rb"&(?!(?:#[0-9]+|#x[0-9A-Fa-f]+|amp|lt|gt|quot|apos);)")
# libxml2 complaints that recovery mode fixes the way TinyXML2 reads the text.
_RECOVERABLE = ("Namespace prefix", "Unescaped '<' not allowed in attributes values", "Extra content at the end")


def _blank(match: re.Match[bytes]) -> bytes:
    return b"\n" * match.group(0).count(b"\n")  # the lines stay where they were


def _tinyxml_text(data: bytes) -> bytes:
    data = _COMMENT.sub(_blank, data)
    head = len(data) - len(data.lstrip())
    data = data[:head] + _LATE_DECLARATION.sub(_blank, data[head:]) if head else data
    return _BARE_AMPERSAND.sub(b"&amp;", data)


def parse_lenient(data: bytes) -> etree._Element:
    """The root element; raises etree.XMLSyntaxError (with the original message and line) when TinyXML2
    would refuse the text too."""
    parser = etree.XMLParser(remove_comments=True, resolve_entities=False)
    try:
        return etree.fromstring(data, parser=parser)
    except etree.XMLSyntaxError as first:
        error = first
    fixed = _tinyxml_text(data)
    try:
        return etree.fromstring(fixed, parser=parser)
    except etree.XMLSyntaxError as e:
        if not any(text in e.msg for text in _RECOVERABLE):
            raise (e if fixed != data else error) from None
    recover = etree.XMLParser(remove_comments=True, resolve_entities=False, recover=True)
    root = etree.fromstring(fixed, parser=recover)
    if root is None:
        raise error
    return root
