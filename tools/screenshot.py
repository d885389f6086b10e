"""Screenshots of report.html in headless Chromium, for a person to look at (not part of `make test`).

    python tools/screenshot.py [--page reports/report.html] [--anchor eq-61] [--out /tmp/report-shots]

writes top.png (the page as it opens) and <anchor>.png (the page from that claim on: headless
Chromium's --screenshot captures the top of a document only, so a temporary copy of the page hides
what comes before the anchor, as if scrolled there; the table of contents stays). Needs
Chromium (Debian: `apt-get install chromium`); the flags keep it off the network, which the page
does not need (it is self-contained).
"""
from __future__ import annotations

import argparse
import html as html_module
import json
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync", "--hide-scrollbars", "--virtual-time-budget=10000"]


def shoot(browser: str, url: str, target: Path, width: int, height: int) -> None:
    with tempfile.TemporaryDirectory(prefix="chromium-") as profile:
        cmd = [browser, *FLAGS, f"--user-data-dir={profile}", f"--window-size={width},{height}",
               f"--screenshot={target}", url]
        subprocess.run(cmd, check=True, capture_output=True, timeout=120)


def browser():
    """The Chromium on PATH, or None."""
    return shutil.which("chromium") or shutil.which("chromium-browser") or shutil.which("google-chrome")


def measure(page, width: int, height: int = 1000, chromium: str = None) -> dict:
    """The page as laid out by headless Chromium at ``width`` px: the document's scroll width against
    the viewport's, the elements whose box reaches past the viewport's right edge, the boxes whose
    content scrolls sideways (``[name, content width, box width]``; what they clip is not listed as
    past the edge), and the
    characters ``$`` and ``\\`` in the text a reader sees (``innerText``: MathML shows as its
    glyphs, so raw TeX shows up here).  A temporary copy of the page runs the measuring script on
    load and writes the answer into the DOM, which ``--dump-dom`` prints."""
    chromium = chromium or browser()
    html = Path(page).read_text(encoding="utf-8").replace("</body>", MEASURE + "</body>")
    with tempfile.TemporaryDirectory(prefix="report-measure-") as tmp:
        copy = Path(tmp) / "page.html"
        copy.write_text(html, encoding="utf-8")
        cmd = [chromium, *FLAGS, f"--user-data-dir={Path(tmp) / 'profile'}", f"--window-size={width},{height}",
               "--dump-dom", copy.as_uri()]
        dom = subprocess.run(cmd, check=True, capture_output=True, timeout=180, text=True).stdout
    m = re.search(r'<pre id="measure-result">(.*?)</pre>', dom, re.S)
    if not m:
        raise RuntimeError(f"the measuring script left no result (chromium printed {len(dom)} characters)")
    return json.loads(html_module.unescape(m.group(1)))


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--page", default="reports/report.html")
    p.add_argument("--anchor", action="append", help="a claim or section id (default: eq-61); repeatable")
    p.add_argument("--out", default=str(Path(tempfile.gettempdir()) / "report-shots"))
    p.add_argument("--width", type=int, default=1400)
    p.add_argument("--height", type=int, default=1000)
    args = p.parse_args(argv)
    page = Path(args.page).resolve()
    if not page.exists():
        print(f"--page {args.page!r}: no such file; run 'make report' first", file=sys.stderr)
        return 2
    chromium = browser()
    if chromium is None:
        print("no Chromium found (Debian: apt-get install chromium)", file=sys.stderr)
        return 2
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    html = page.read_text(encoding="utf-8")
    for anchor in [None, *(args.anchor or ["eq-61"])]:
        target = out / f"{anchor or 'top'}.png"
        with tempfile.TemporaryDirectory(prefix="report-shot-") as tmp:
            copy = Path(tmp) / "page.html"
            copy.write_text(html if anchor is None else html.replace("</body>", SCROLL.replace("ANCHOR", anchor) + "</body>"),
                            encoding="utf-8")
            shoot(chromium, copy.as_uri(), target, args.width, args.height)
        print(target)
    return 0


# hide every element before the anchor (in document order, outside the table of contents)
SCROLL = """<script>(function () {
  var t = document.getElementById("ANCHOR"); if (!t) return;
  for (var n = t; n && n.tagName !== "MAIN"; n = n.parentElement) {
    for (var s = n.previousElementSibling; s; s = s.previousElementSibling) s.style.display = "none";
  }
})();</script>"""


# what the page looks like to a reader at this width, written into the DOM for --dump-dom
MEASURE = r"""<script>window.addEventListener("load", function () {
  var vw = document.documentElement.clientWidth, wide = [], scrolls = [];
  function name(e) {
    var s = e.tagName.toLowerCase() + (e.id ? "#" + e.id : "");
    for (var p = e.parentElement; p; p = p.parentElement) if (p.id) { s += " in #" + p.id; break; }
    return s;
  }
  var all = document.body.getElementsByTagName("*"), clipped = [];
  for (var i = 0; i < all.length; i++) {
    var e = all[i], r = e.getBoundingClientRect();
    if (r.width === 0 && r.height === 0) continue;
    var inside = false;  // within a box that scrolls sideways: listed there, not here
    for (var j = 0; j < clipped.length && !inside; j++) inside = clipped[j].contains(e);
    if (!inside && r.right > vw + 0.5) wide.push([name(e), Math.round(r.right)]);
    var st = getComputedStyle(e);
    if (/auto|scroll|hidden/.test(st.overflowX) && e.scrollWidth > e.clientWidth + 1) {
      scrolls.push([name(e), e.scrollWidth, e.clientWidth]);
      clipped.push(e);
    }
  }
  var text = document.body.innerText, visible = [];
  var re = /[$\\]/g, m;
  while ((m = re.exec(text)) && visible.length < 50) visible.push(text.slice(Math.max(0, m.index - 40), m.index + 40));
  var out = document.createElement("pre");
  out.id = "measure-result";
  out.textContent = JSON.stringify({viewport: vw, scroll_width: document.documentElement.scrollWidth,
                                    wider_than_viewport: wide, scrolls_sideways: scrolls, dollar_or_backslash: visible});
  document.body.appendChild(out);
});</script>"""


if __name__ == "__main__":
    sys.exit(main())
