"""report.html: REPORT.md rendered as one self-contained page (figures inlined)."""
from __future__ import annotations

import base64
import html


def render_html(markdown_text: str, images: dict) -> str:
    """A self-contained page: the Markdown rendered by a small converter (tables, headings, lists)."""
    body, in_table = [], False
    for raw in markdown_text.splitlines():
        line = raw.rstrip()
        if line.startswith("|"):
            cells = [html.escape(c.strip().replace("\\|", "|")) for c in line.strip("|").split(" | ")]
            if set(line.replace("|", "").strip()) <= set("-: "):
                continue
            if not in_table:
                body.append("<table>")
                body.append("<tr>" + "".join(f"<th>{c}</th>" for c in cells) + "</tr>")
                in_table = True
            else:
                body.append("<tr>" + "".join(f"<td>{c}</td>" for c in cells) + "</tr>")
            continue
        if in_table:
            body.append("</table>")
            in_table = False
        if line.startswith("![") and "](" in line:
            target = line.split("](", 1)[1].rstrip(")")
            name = target.rsplit("/", 1)[-1]
            if name in images:
                data = base64.b64encode(images[name]).decode()
                body.append(f"<p><img alt='{html.escape(name)}' src='data:image/png;base64,{data}'></p>")
            continue
        if line.startswith("#"):
            level = len(line) - len(line.lstrip("#"))
            body.append(f"<h{level}>{html.escape(line[level:].strip())}</h{level}>")
        elif line.startswith("- "):
            text = html.escape(line[2:]).replace("**", "")
            body.append(f"<li>{text}</li>")
        elif line.startswith("```"):
            body.append("<pre>" if not body or body[-1] != "<pre>" else "</pre>")
        elif line:
            body.append(f"<p>{html.escape(line)}</p>")
    if in_table:
        body.append("</table>")
    style = ("body{font-family:sans-serif;max-width:80em;margin:auto}table{border-collapse:collapse}"
             "td,th{border:1px solid #ccc;padding:2px 6px;font-size:90%;vertical-align:top}")
    return ("<!DOCTYPE html>\n<html><head><meta charset='utf-8'><title>Verification report</title>"
            f"<style>{style}</style></head><body>\n" + "\n".join(body) + "\n</body></html>\n")
