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
    browser = shutil.which("chromium") or shutil.which("chromium-browser") or shutil.which("google-chrome")
    if browser is None:
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
            shoot(browser, copy.as_uri(), target, args.width, args.height)
        print(target)
    return 0


# hide every element before the anchor (in document order, outside the table of contents)
SCROLL = """<script>(function () {
  var t = document.getElementById("ANCHOR"); if (!t) return;
  for (var n = t; n && n.tagName !== "MAIN"; n = n.parentElement) {
    for (var s = n.previousElementSibling; s; s = s.previousElementSibling) s.style.display = "none";
  }
})();</script>"""


if __name__ == "__main__":
    sys.exit(main())
