"""The `$(name arg …)` syntax of markup launch files, parsed into substitutions.

Text outside `$(…)` is kept as text. Arguments are separated by one space; an argument is a run of
unquoted characters and nested `$(…)`, or one quoted string ('…' or "…") that may itself hold `$(…)`
(whose arguments are then unquoted). A backslash escapes the next character everywhere: `\\$(` is a
literal `$(`, `\\)` a parenthesis inside an argument, `\\'` a quote inside '…'; escapes are removed from
the resulting text (`\\x` → `x`). `$` not followed by `(` is an ordinary character.
"""

from __future__ import annotations

import re
from typing import Any

from ..substitutions.text_substitution import TextSubstitution
from ..utilities.type_utils import NormalizedValueType, StrSomeValueType
from .expose import instantiate_substitution

_ESCAPE = re.compile(r'\\(.)')


def replace_escaped_characters(data: str) -> str:
    """`data` with each backslash escape replaced by the character it escapes."""
    return _ESCAPE.sub(r'\1', data)


class _Syntax:
    """A recursive-descent reader of one string; `context` is None (unquoted), "'" or '"'."""

    def __init__(self, text: str) -> None:
        self.text = text
        self.pos = 0

    # ---- characters --------------------------------------------------------------------------------------

    def _escaped(self, i: int) -> bool:
        return i > 0 and self.text[i - 1] == '\\'

    def _at_substitution(self, i: int) -> bool:
        return self.text.startswith('$(', i) and not self._escaped(i)

    def _in_string(self, i: int, quote: str | None) -> bool:
        """Whether text[i] belongs to literal text of a template (top level, or inside quotes)."""
        c = self.text[i]
        if c == '$':
            return not self._at_substitution(i)
        if quote is None or c == '\\':
            return True
        return c != quote or self._escaped(i)

    def _in_argument(self, i: int, quote: str | None) -> bool:
        """Whether text[i] belongs to literal text of an argument of `$(…)`."""
        c = self.text[i]
        if c == '$':
            return not self._at_substitution(i)
        if c == '\\':
            return True
        if c in '()':
            return self._escaped(i)
        if c == ' ':
            return False
        if c in '\'"':
            return (quote is not None and c != quote) or self._escaped(i)
        return True

    def _fail(self, expected: str) -> ValueError:
        found = repr(self.text[self.pos]) if self.pos < len(self.text) else 'the end of the text'
        return ValueError(
            f"invalid substitution syntax in '{self.text}': expected {expected} at column {self.pos + 1}, "
            f'found {found}')

    def _literal(self, accept: Any, quote: str | None) -> TextSubstitution | None:
        start = self.pos
        while self.pos < len(self.text) and accept(self.pos, quote):
            self.pos += 1
        if self.pos == start:
            return None
        return TextSubstitution(text=replace_escaped_characters(self.text[start:self.pos]))

    # ---- grammar -----------------------------------------------------------------------------------------

    def template(self) -> list[Any]:
        """Top level: text and substitutions up to the end."""
        parts: list[Any] = []
        while self.pos < len(self.text):
            if self._at_substitution(self.pos):
                parts.append(self.substitution(None))
            else:
                parts.append(self._literal(self._in_string, None))
        return parts

    def _quoted(self) -> list[Any]:
        quote = self.text[self.pos]
        self.pos += 1
        parts: list[Any] = []
        while True:
            if self.pos >= len(self.text):
                raise self._fail(f'a closing {quote}')
            if self.text[self.pos] == quote and not self._escaped(self.pos):
                self.pos += 1
                return parts
            if self._at_substitution(self.pos):
                parts.append(self.substitution(quote))
            else:
                parts.append(self._literal(self._in_string, quote))

    def _argument(self, quote: str | None) -> list[Any]:
        if quote is None and self.pos < len(self.text) and self.text[self.pos] in '\'"':
            return self._quoted()
        parts: list[Any] = []
        while self.pos < len(self.text):
            if self._at_substitution(self.pos):
                parts.append(self.substitution(quote))
                continue
            text = self._literal(self._in_argument, quote)
            if text is None:
                break
            parts.append(text)
        if not parts:
            raise self._fail('an argument')
        return parts

    def substitution(self, quote: str | None) -> Any:
        self.pos += 2  # '$('
        start = self.pos
        if self.pos < len(self.text) and self.text[self.pos].isascii() and self.text[self.pos].isalpha():
            self.pos += 1
            while self.pos < len(self.text) and (
                (self.text[self.pos].isascii() and self.text[self.pos].isalnum()) or self.text[self.pos] in '_-'
            ):
                self.pos += 1
        name = self.text[start:self.pos]
        if not name:
            raise self._fail('a substitution name')
        arguments: list[list[Any]] = []
        while self.pos < len(self.text) and self.text[self.pos] == ' ':
            self.pos += 1
            arguments.append(self._argument(quote))
        if self.pos >= len(self.text) or self.text[self.pos] != ')':
            raise self._fail("')'")
        self.pos += 1
        return instantiate_substitution(name, arguments) if arguments else instantiate_substitution(name)


def parse_substitution(string_value: str) -> list[Any]:
    """The substitutions of a markup attribute value (text and `$(…)`), in order."""
    if not string_value:
        return [TextSubstitution(text=string_value)]
    return _Syntax(string_value).template()


def parse_if_substitutions(value: StrSomeValueType) -> NormalizedValueType:
    """A typed attribute value with its `$(…)` parsed.

    A string with substitutions becomes a list of substitutions, one without stays a string; other
    scalars are kept; a list is handled item by item and must stay uniform (ValueError otherwise).
    """
    kinds = set()

    def one(item: Any) -> Any:
        if not isinstance(item, str):
            kinds.add(type(item))
            return item
        parsed = parse_substitution(item)
        if len(parsed) == 1 and isinstance(parsed[0], TextSubstitution):
            kinds.add(str)
            return parsed[0].text
        return parsed

    result = [one(item) for item in value] if isinstance(value, list) else one(value)
    if len(kinds) > 1:
        raise ValueError('The result is a non-uniform list')
    return result
