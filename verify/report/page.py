"""report.html: the report as one self-contained page, rendered from results.json by kept libraries.

Markdown goes through markdown-it-py (CommonMark + tables), math (``$...$``, ``$$...$$``) through
the dollarmath plugin into MathML by latex2mathml (browsers render it natively, offline), and the
page is a Jinja2 template (``templates/report.html.j2``): a table of contents with an anchor for
every section and every claim (``report.html#eq-61``), the summary first, each claim as a card
with the paper's words beside the verdict and the evidence, figures inlined with their alt text.
"""
from __future__ import annotations

import base64
import html
import io
import mimetypes
import re
from functools import lru_cache
from typing import Optional

import jinja2
from latex2mathml.converter import convert as latex_to_mathml
from markdown_it import MarkdownIt
from mdit_py_plugins.dollarmath import dollarmath_plugin

from .markdown import sections, verdict_label
from .markup import quote, text
from .summary import SEVERITY_WORDS


def _math(content: str, options: dict) -> str:
    """MathML for one formula; the TeX shown as code where latex2mathml cannot read it."""
    try:
        return compact_mathml(latex_to_mathml(content, display="block" if options.get("display_mode") else "inline"))
    except Exception:  # noqa: BLE001 -- a formula it cannot read is shown, not lost
        return f'<code class="tex">{html.escape(content)}</code>'


_CHAR_REF = re.compile(r"&#x([0-9A-Fa-f]+);")
_LONE_MROW = re.compile(r"<mrow>(<(mi|mn|mo)(?: [^>]*)?>[^<]*</\2>)</mrow>")
_KEEP_ESCAPED = {0x26, 0x3C, 0x3E, 0x22}  # & < > "


def compact_mathml(mathml: str) -> str:
    """The same MathML in fewer bytes (a page has about 900 formulas): characters written as
    themselves instead of ``&#x003D5;`` (the page is UTF-8), and the defaults HTML5 implies left
    out (the MathML namespace of a ``<math>`` in HTML, ``display="inline"``), and an ``<mrow>``
    around a single token dropped (MathML: an mrow with one argument is that argument)."""
    mathml = _LONE_MROW.sub(r"\1", mathml)
    mathml = mathml.replace(' xmlns="http://www.w3.org/1998/Math/MathML"', "").replace(' display="inline"', "")
    return _CHAR_REF.sub(lambda m: m.group(0) if int(m.group(1), 16) in _KEEP_ESCAPED else chr(int(m.group(1), 16)),
                         mathml)


_TABLE_BREAK = re.compile(r">\n(?=</?(?:table|thead|tbody|tr|th|td)\b)")


def compact_tables(html_text: str) -> str:
    """markdown-it's tables without the line break it writes before every row and cell tag (about
    6 KB of the page's 1.5 MB budget): whitespace between table elements is not rendered."""
    return _TABLE_BREAK.sub(">", html_text)


WIDE_TABLE = 8  # columns: a table with more is laid out row by row (each cell labelled) at every width

_TABLE_HEAD = re.compile(r"<table>(<thead><tr>(?:<th[^>]*>.*?</th>)+</tr></thead>)", re.S)


def labelled_tables(html_text: str) -> str:
    """A table of more than :data:`WIDE_TABLE` columns marked ``class="wide"``: the page lays it out
    one block per row, each cell after its column's heading (set by the page's script from the
    heading row: 70 KB less than writing it into every cell), as it does every table on a narrow
    screen."""
    def one(m):
        columns = m.group(1).count("<th")
        return (f'<table class="wide">' if columns > WIDE_TABLE else "<table>") + m.group(1)

    return _TABLE_HEAD.sub(one, html_text)


class _Renderer:
    """markdown-it configured for the report, with figures resolved to inline data."""

    def __init__(self, images: dict, alts: dict):
        self.images, self.alts = images, alts
        md = MarkdownIt("commonmark", {"html": True}).enable("table")
        dollarmath_plugin(md, renderer=_math)
        md.add_render_rule("image", lambda renderer, tokens, idx, options, env: self._image(renderer, tokens, idx,
                                                                                            options, env))
        self.md = md

    def _image(self, renderer, tokens, idx, options, env):
        token = tokens[idx]
        src = str(token.attrGet("src") or "")
        name = src.rsplit("/", 1)[-1]
        alt = renderer.renderInlineAsText(token.children or [], options, env) or self.alts.get(name, "")
        if name not in self.images:
            return f'<span class="missing-figure">figure {html.escape(name)} is missing</span>'
        return f'<img src="{data_uri(name, self.images[name])}" alt="{html.escape(alt, quote=True)}">'

    def block(self, markdown: str) -> str:
        return labelled_tables(compact_tables(self.md.render(markdown)))

    def inline(self, markdown: str) -> str:
        return self.md.renderInline(markdown)


WIDE_FORMULA = 90  # characters of TeX in one row of a displayed equation: wider than the card's quote column


def wide_quote(fragments) -> bool:
    """Whether the quote has a displayed equation with a row too long for the card's narrow quote
    column (about 400 px at 1400 px): the card then stacks the quote above the verdict."""
    from .markup import is_bare_equation

    frags = [fragments] if isinstance(fragments, str) else fragments
    rows = [re.sub(r"\\(?:begin|end)\{\w+\*?\}|\\(?:left|right|mathbf|boldsymbol|dot|ddot|frac)\b|[{}]", "", row)
            for f in frags if is_bare_equation(f) for row in f.split("\\\\")]
    return any(len(row) > WIDE_FORMULA for row in rows)


def data_uri(name: str, data: bytes) -> str:
    """The figure as a data URI; a PNG is embedded as lossless WebP of its palette reduced to 16
    colours (:func:`sixteen_colours`; 30 % fewer bytes than the PNG)."""
    if name.endswith(".png"):
        return f"data:image/webp;base64,{base64.b64encode(lossless_webp(data)).decode()}"
    mime = mimetypes.guess_type(name)[0] or "application/octet-stream"
    return f"data:{mime};base64,{base64.b64encode(data).decode()}"


PAGE_COLOURS = 16  # WebP packs two pixels of a palette of at most 16 colours into a byte


def sixteen_colours(im):
    """A palette image of 17 to 64 colours (a line figure: the style's curves, text and grid with 6
    antialiasing steps each) with its 16 most used colours kept exactly and each other one, a rare
    antialiasing step, drawn as the nearest kept colour (RGB); any other image as it is.  On the
    report's figures: 10 % fewer WebP bytes, no difference a reader sees."""
    import numpy as np
    from PIL import Image as PILImage

    if im.mode != "P":
        return im
    index = np.asarray(im)
    palette = np.array(im.getpalette()[:768], float).reshape(-1, 3)
    counts = np.bincount(index.ravel(), minlength=len(palette))
    used = np.nonzero(counts)[0]
    if not PAGE_COLOURS < len(used) <= 64:
        return im
    keep = np.sort(used[np.argsort(-counts[used], kind="stable")[:PAGE_COLOURS]])
    lut = np.zeros(len(palette), int)
    lut[used] = np.argmin(((palette[used][:, None, :] - palette[keep][None, :, :]) ** 2).sum(-1), axis=1)
    out = PILImage.fromarray(lut[index].astype(np.uint8), "P")
    out.putpalette(palette[keep].astype(np.uint8).tobytes())
    return out


def lossless_webp(png: bytes) -> bytes:
    """``png`` re-encoded as lossless WebP, its palette first reduced by :func:`sixteen_colours` (Pillow, method 6: 52 s for the report's figures once, against
    2 s for method 4, for 8.5 KB less, which keeps the page under its 1.5 MB bound), remembered in the job
    cache's folder by the PNG's sha256 (a pure function of the bytes: the page is the same whether it was
    remembered or not, and a figure pays the encoding only when it changes)."""
    import hashlib

    from PIL import Image as PILImage

    from ..provenance import write_atomic
    from .cache import default_folder

    memo = default_folder() / f"webp6-{PAGE_COLOURS}" / hashlib.sha256(png).hexdigest()
    try:
        return memo.read_bytes()
    except OSError:
        pass
    buf = io.BytesIO()
    with PILImage.open(io.BytesIO(png)) as im:
        sixteen_colours(im).save(buf, "WEBP", lossless=True, quality=100, method=6, exact=True)
    try:
        write_atomic(memo, buf.getvalue())
    except OSError:
        pass  # a read-only folder only costs the 2 s next time
    return buf.getvalue()


@lru_cache(maxsize=1)
def _environment() -> jinja2.Environment:
    env = jinja2.Environment(loader=jinja2.PackageLoader("verify.report", "templates"),
                             autoescape=jinja2.select_autoescape(["html", "j2"]), undefined=jinja2.StrictUndefined,
                             trim_blocks=True, lstrip_blocks=True)
    return env


def render_html(results: dict, images: dict, benchmarks: Optional[dict] = None) -> str:
    """The page.  ``images``: file name -> bytes of every figure results.json names."""
    alts = {f["file"]: f["alt"] for f in results.get("figures", ())}
    r = _Renderer(images, alts)
    blocks = []
    for anchor, title, body, claims in sections(results, benchmarks):
        if claims is None:
            blocks.append({"anchor": anchor, "title": title, "html": r.block(body), "claims": None})
            continue
        cards = []
        for rec in claims:
            fields = [("read as", rec.get("reading")), ("independent route", rec["expected"]),
                      ("the paper", rec["observed"]), ("corrected", rec.get("correction")),
                      ("qualification", rec.get("qualification")),
                      ("measures", "; ".join(f"{m['measure']}: {m['value']}" for m in rec.get("measures", ())) or None),
                      ("detail", rec["detail"]), ("method", f"{rec['method']}; tolerance: {rec['tolerance']}")]
            cards.append({
                "id": rec["id"], "source": rec["source"], "verdict": rec["verdict"], "label": verdict_label(rec),
                "severity_words": SEVERITY_WORDS.get(rec.get("severity"), ""),
                "quote": r.block("\n".join(quote(rec["quote"]))), "wide": wide_quote(rec["quote"]),
                "quote_missing": rec.get("quote_not_in_paper", False),
                "fields": [(name, r.inline(text(value))) for name, value in fields if value],
                "figures": [{"src": data_uri(f["file"], images[f["file"]]) if f["file"] in images else None,
                             "alt": f["alt"], "title": f["title"], "file": f["file"]} for f in rec.get("figures", ())],
            })
        blocks.append({"anchor": anchor, "title": title, "html": None, "claims": cards})
    prov = results["provenance"]
    return _environment().get_template("report.html.j2").render(
        blocks=blocks, provenance=prov, failures=results.get("failures", []),
        commit=(prov.get("source_commit") or {}).get("commit") or "unknown")
