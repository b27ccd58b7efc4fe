"""Griffe extension: Sphinx cross-reference roles in docstrings as code.

The docstrings are numpydoc and name other objects with Sphinx roles (``:func:`~mawdo.plan```),
which mkdocstrings does not read: the role is written as plain code, with ``~`` keeping only the
last dotted part, as Sphinx shows it.
"""

from __future__ import annotations

import re

import griffe

ROLE = re.compile(r":(?:py:)?(?:func|class|meth|mod|data|attr|obj|exc|const|ref):`(~?)([^`]+)`")


def plain(text: str) -> str:
    """``text`` with each Sphinx role written as inline code."""
    return ROLE.sub(lambda m: f"`{m[2].rsplit('.', 1)[-1] if m[1] else m[2]}`", text)


class SphinxRoles(griffe.Extension):
    def on_instance(self, *, obj: griffe.Object, **kwargs) -> None:
        if obj.docstring is not None:
            obj.docstring.value = plain(obj.docstring.value)
