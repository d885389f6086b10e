"""Plain text into Markdown that shows exactly that text, math kept for the math renderer.

The claims' and the paper's texts are plain text with math in ``$...$`` (LaTeX); :func:`text`
escapes what Markdown would read as markup (``*``, ``_``, ``[``, ``<``, ...) outside the math, so
a product ``a*b`` or a ``theta_0`` never becomes emphasis or a link.
"""
from __future__ import annotations

import re

_MATH = re.compile(r"(\$\$.+?\$\$|\$[^$]+?\$)", re.S)
_SPECIAL = re.compile(r"([\\`*\[\]<>#$])")
_LONE_UNDERSCORE = re.compile(r"(?<![0-9A-Za-z])_|_(?![0-9A-Za-z])")


def text(s, table: bool = False) -> str:
    """``s`` as Markdown that shows exactly ``s``: markup characters escaped outside ``$...$`` math.

    ``table``: also escape ``|`` (a table cell).  Newlines become spaces.
    """
    out = []
    for i, part in enumerate(_MATH.split(str(s).replace("\n", " "))):
        if i % 2:  # math: passed through for the math renderer (a table cell unescapes \| before it)
            out.append(part.replace("|", "\\|") if table else part)
            continue
        part = _SPECIAL.sub(r"\\\1", part)
        part = _LONE_UNDERSCORE.sub(r"\\_", part)
        if table:
            part = part.replace("|", "\\|")
        out.append(part)
    return "".join(out)


_BARE_TEX = re.compile(r"\\(?:frac|dot|ddot|sqrt|theta|phi|psi|omega|left|right|hat|vec|mathbf|cos|sin|tan|cdot)\b")


_TEX_TOKEN = re.compile(r"\\[A-Za-z]+(?:\{[^{}]*\})*(?:[_^](?:\{[^{}]*\}|[A-Za-z0-9]))*")


def typeset_bare(frag: str) -> str:
    """``frag`` with each LaTeX token written in prose without its ``$`` (the paper's "Since
    \\mathbf{r}_P is a constant") put in ``$...$``, so that it is typeset, not shown as TeX."""
    parts = _MATH.split(frag)
    return "".join(p if i % 2 else _TEX_TOKEN.sub(lambda m: f"${m.group(0)}$", p) for i, p in enumerate(parts))


def is_bare_equation(frag: str) -> bool:
    """Whether ``frag`` is a LaTeX equation without its delimiters (no ``$``, TeX commands, and no
    two English words in a row outside them: "Since \\mathbf{r}_P is a constant" is prose)."""
    if "$" in frag or not _BARE_TEX.search(frag):
        return False
    rest = re.sub(r"\\(?:text|mathrm|operatorname)\{[^{}]*\}|\\[A-Za-z]+", " ", frag)
    return not re.search(r"\b[A-Za-z]{3,}\s+[A-Za-z]{2,}\b", rest)


def quote(fragments) -> list:
    """The paper's words as blockquote lines; a fragment that is a bare LaTeX equation (the paper's
    display math, which the quotation keeps without its delimiters) is shown typeset."""
    lines = []
    for frag in fragments:
        if is_bare_equation(frag):
            lines.append(f"> $${frag}$$")
        else:
            lines.append("> " + text(typeset_bare(frag)))
        lines.append(">")
    return lines[:-1]




def inline_quote(joined: str, table: bool = False) -> str:
    """A quote joined with `` ... `` (results.json's summary) as one line of Markdown: a fragment
    that is a bare LaTeX equation is typeset inline, the rest shown literally (:func:`text`)."""
    parts = []
    for frag in joined.split(" ... "):
        bare = is_bare_equation(frag)
        parts.append(text(f"${frag.strip()}$" if bare else typeset_bare(frag), table=table))
    return " ... ".join(parts)
