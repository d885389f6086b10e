"""report.html: the report as one self-contained page, rendered from results.json by kept libraries.

Markdown goes through markdown-it-py (CommonMark + tables), math (``$...$``, ``$$...$$``) through
the dollarmath plugin into MathML by latex2mathml (browsers render it natively, offline), and the
page is a Jinja2 template (``templates/report.html.j2``): a table of contents with an anchor for
every section and every claim (``report.html#eq-61``), the summary first, each claim as a card
with the paper's words beside the verdict and the evidence, figures inlined with their alt text.
"""
from __future__ import annotations

import base64
import hashlib
import html
import io
import mimetypes
import re
from functools import lru_cache
from typing import Optional

import jinja2
import numpy as np
from latex2mathml.converter import convert as latex_to_mathml
from markdown_it import MarkdownIt
from matplotlib.colors import to_rgb
from mdit_py_plugins.dollarmath import dollarmath_plugin
from PIL import Image as PILImage

from ..provenance import write_atomic
from ..style import LINE_COLOURS
from .cache import default_folder
from .markdown import sections, verdict_label
from .markup import is_bare_equation, quote, text
from .prose_math import typeset_prose
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
SMALL_TABLE = 3  # columns: a table with at most these stays a table on a narrow screen too (it fits 320 px)

_TABLE_HEAD = re.compile(r"<table>(<thead><tr>(?:<th[^>]*>.*?</th>)+</tr></thead>)", re.S)


def labelled_tables(html_text: str) -> str:
    """A table of more than :data:`WIDE_TABLE` columns marked ``class="wide"``: the page lays it out
    one block per row, each cell after its column's heading (set by the page's script from the
    heading row: 70 KB less than writing it into every cell), as it does every table of more than
    :data:`SMALL_TABLE` columns on a narrow screen (those are marked ``class="small"``)."""
    def one(m):
        columns = m.group(1).count("<th")
        kind = "wide" if columns > WIDE_TABLE else "small" if columns <= SMALL_TABLE else None
        return (f'<table class="{kind}">' if kind else "<table>") + m.group(1)

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
    frags = [fragments] if isinstance(fragments, str) else fragments
    rows = [re.sub(r"\\(?:begin|end)\{\w+\*?\}|\\(?:left|right|mathbf|boldsymbol|dot|ddot|frac)\b|[{}]", "", row)
            for f in frags if is_bare_equation(f) for row in f.split("\\\\")]
    return any(len(row) > WIDE_FORMULA for row in rows)


def data_uri(name: str, data: bytes) -> str:
    """The figure as a data URI; a PNG is embedded as lossless WebP of its palette reduced for the page
    (:func:`page_palette`)."""
    if name.endswith(".png"):
        return f"data:image/webp;base64,{base64.b64encode(lossless_webp(data)).decode()}"
    mime = mimetypes.guess_type(name)[0] or "application/octet-stream"
    return f"data:{mime};base64,{base64.b64encode(data).decode()}"


PAGE_COLOURS = 16  # WebP packs two pixels of a palette of at most 16 colours into a byte, four of at most 4
#: how the page's four-colour figures draw a grey pixel (value v of r = g = b): white from LIGHT up, the
#: grid's grey from DARK up, black below (text, axes; their antialiasing steps split between the three)
LIGHT, DARK, GRID = 240, 160, 224
#: an antialiasing step of a curve at least this far from white towards its colour is drawn in that colour
THRESHOLD = 0.5


def page_palette(im):
    """The palette the page embeds a figure with (the full-quality PNG stays in reports/figures/).

    A line figure (:data:`verify.style.LINE_PALETTE`: white, and 6 antialiasing steps towards each of
    :data:`verify.style.LINE_COLOURS`) whose curves are of one colour (every caption's figure: the runs in
    :data:`verify.style.RUN`, black text, the grey grid) is drawn in four colours: white, the grid's grey,
    black and that colour, a curve's antialiasing step taking the curve's colour from half-way on
    (:data:`THRESHOLD`) and a grey going to the nearest of the three greys (:data:`LIGHT`, :data:`DARK`).
    WebP packs four such pixels to a byte: the figures' bytes on the page fall from 0.86 to about 0.55 MB,
    the text and curves lose their smoothing, not a stroke.  Any other line figure keeps its
    :data:`PAGE_COLOURS` most used colours exactly, the rarer steps drawn as the nearest kept one (RGB);
    any other image (colour maps) as it is.
    """
    if im.mode != "P":
        return im
    index = np.asarray(im)
    palette = np.array(im.getpalette()[:768], float).reshape(-1, 3)
    counts = np.bincount(index.ravel(), minlength=len(palette))
    used = np.nonzero(counts)[0]
    if len(used) <= 4 or len(used) > 64:
        return im
    white = np.full(3, 255.0)
    hues = [np.round(np.array(to_rgb(c)) * 255) for c in LINE_COLOURS]
    hues = [h for h in hues if np.ptp(h) > 0]  # the curves' colours (the greys are handled by value)
    target, fits = {}, True
    for u in used:
        colour = palette[u]
        if np.ptp(colour) == 0:
            v = colour[0]
            target[u] = (255.0,) * 3 if v >= LIGHT else (float(GRID),) * 3 if v >= DARK else (0.0,) * 3
            continue
        best = None
        for hue in hues:
            d = hue - white
            t = float(np.clip(np.dot(colour - white, d) / np.dot(d, d), 0, 1))
            miss = float(np.sum((white + t * d - colour) ** 2))
            if best is None or miss < best[0]:
                best = (miss, t, tuple(hue))
        fits &= best[0] <= 3.0  # within rounding of a step of the style's ramps
        target[u] = best[2] if best[1] >= THRESHOLD else (255.0,) * 3
    kept = [(255.0,) * 3, (float(GRID),) * 3, (0.0,) * 3]
    kept += sorted(set(target.values()) - set(kept))
    if fits and len(kept) <= 4:
        lut = np.zeros(len(palette), int)
        for u in used:
            lut[u] = kept.index(target[u])
        colours = np.array(kept, float)
    else:
        if len(used) <= PAGE_COLOURS:
            return im
        # the style's full colours first (a curve's own colour, however few its pixels), then the most used steps
        full = {tuple(np.round(np.array(to_rgb(c)) * 255)) for c in LINE_COLOURS} | {(255.0, 255.0, 255.0)}
        pure = [u for u in used if tuple(palette[u]) in full]
        rest = [u for u in used[np.argsort(-counts[used], kind="stable")] if u not in pure]
        keep = np.sort(np.array((pure + rest)[:max(PAGE_COLOURS, len(pure))]))
        lut = np.zeros(len(palette), int)
        lut[used] = np.argmin(((palette[used][:, None, :] - palette[keep][None, :, :]) ** 2).sum(-1), axis=1)
        colours = palette[keep]
    out = PILImage.fromarray(lut[index].astype(np.uint8), "P")
    out.putpalette(colours.astype(np.uint8).tobytes())
    return out


def lossless_webp(png: bytes) -> bytes:
    """``png`` re-encoded as lossless WebP, its palette first reduced by :func:`page_palette` (Pillow, method 6:
    about a minute for the report's figures once, against 2 s for method 4, for a few KB less), remembered in the job
    cache's folder by the PNG's sha256 (a pure function of the bytes: the page is the same whether it was
    remembered or not, and a figure pays the encoding only when it changes)."""
    memo = default_folder() / "webp6-page-palette-4" / hashlib.sha256(png).hexdigest()
    try:
        return memo.read_bytes()
    except OSError:
        pass
    buf = io.BytesIO()
    with PILImage.open(io.BytesIO(png)) as im:
        page_palette(im).save(buf, "WEBP", lossless=True, quality=100, method=6, exact=True)
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


def render_html(results: dict, images: dict, benchmarks: Optional[dict] = None, engines: Optional[dict] = None) -> str:
    """The page.  ``images``: file name -> bytes of every figure results.json names."""
    alts = {f["file"]: f["alt"] for f in results.get("figures", ())}
    r = _Renderer(images, alts)
    blocks = []
    for anchor, title, body, claims in sections(results, benchmarks, engines):
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
    return typeset_prose(_environment().get_template("report.html.j2").render(
        blocks=blocks, provenance=prov, failures=results.get("failures", []),
        commit=(prov.get("source_commit") or {}).get("commit") or "unknown"))
