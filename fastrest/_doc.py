"""Docstrings written once: shared numpydoc paragraphs, filled into ``{placeholders}``.

The text several functions share (a parameter's description, a Raises or Warns block) is written
once, in a dict of paragraphs, and each docstring names it by a placeholder: ``{name}`` alone on
its line, indented as the paragraph is to be. :func:`fill` puts the paragraph there, every line of
it at the placeholder's indentation (the paragraph itself is written flush left, or indented
uniformly: it is dedented first; an empty paragraph takes its line away); :func:`doc` does so for a function's or class's docstring when
it is defined, so that ``help()``, Sphinx autodoc, numpydoc and doctest read the whole text. A
paragraph may itself hold placeholders (filled from the same dicts). The templates of
:mod:`fastrest.curve` (``_METHOD_DOC.format(...)``) are the same idea for whole docstrings; a
template that ``str.format`` fills writes a shared paragraph's placeholder ``{{name}}`` and is
filled after formatting (``fill(TEMPLATE.format(...), PARAGRAPHS)``).

Only a line that holds nothing but ``{name}`` is a placeholder: the braces of sets
(``{"jcg", "etsion"}``) and of dict displays in examples are text. A placeholder that names no
paragraph raises KeyError when its module is imported. Under ``python -OO`` (no docstrings) there
is nothing to fill.

Put :func:`doc` below ``@jit``: a Numba dispatcher copies its function's docstring when it is
made. Nothing here imports from fastrest: every module may use it.
"""
from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import TypeVar
import re
import textwrap

__all__ = ["fill", "doc", "paragraphs"]

_T = TypeVar("_T")

# a line holding only {name} (an identifier), with its indentation and its end of line
_PLACEHOLDER = re.compile(r"^([ \t]*)\{([A-Za-z_][A-Za-z0-9_]*)\}[ \t]*(\n|$)", re.MULTILINE)


def paragraphs(**texts: str) -> dict[str, str]:
    """The dict of shared paragraphs ``texts``, each dedented and stripped of its outer blank lines
    (so that each may be written as an indented triple-quoted string)."""
    return {k: textwrap.dedent(v).strip("\n") for k, v in texts.items()}


def fill(text: str, *parts: Mapping[str, str], **more: str) -> str:
    """``text`` with each whole-line ``{name}`` replaced by paragraph ``name``, indented as the
    placeholder; the paragraphs come from ``parts`` (later ones win) and ``more``."""
    table: dict[str, str] = {}
    for p in parts:
        table.update(p)
    table.update(paragraphs(**more))

    def put(m: re.Match[str], depth: int) -> str:
        indent, name, end = m.group(1), m.group(2), m.group(3)
        if name not in table:
            raise KeyError(f"docstring placeholder {{{name}}} names no shared paragraph")
        body = textwrap.dedent(table[name]).strip("\n")
        if depth < 8:  # a paragraph's own placeholders
            body = _PLACEHOLDER.sub(lambda n: put(n, depth + 1), body)
        if not body:  # an empty paragraph takes its line away
            return ""
        return "\n".join(indent + line if line.strip() else "" for line in body.split("\n")) + end

    return _PLACEHOLDER.sub(lambda m: put(m, 0), text)


def doc(*parts: Mapping[str, str], **more: str) -> Callable[[_T], _T]:
    """Decorator: fill the placeholders of the decorated object's docstring (:func:`fill`) and
    return the object itself."""

    def wrap(obj: _T) -> _T:
        text = getattr(obj, "__doc__", None)
        if text:
            obj.__doc__ = fill(text, *parts, **more)
        return obj

    return wrap
