"""The README and docs/ as a newcomer meets them: every relative link resolves, and every command
marked quick runs.

A fenced block whose info string is ``sh quick`` holds shell commands that take seconds; one whose
info string is ``python quick`` is a Python script (docs/README.md states the rule). The commands
run page by page, in order, in one temporary folder, with ``python`` and ``.venv/bin/python``
replaced by this interpreter and the repository on PYTHONPATH.
"""
from __future__ import annotations

import os
import re
import shlex
import subprocess
import sys
import unicodedata
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]

FENCE = re.compile(r"^```([^\n`]*)\n(.*?)^```[ \t]*$", re.S | re.M)
LINK = re.compile(r"(?<!!)\[[^\]]*\]\(([^)\s]+)\)|!\[[^\]]*\]\(([^)\s]+)\)")


def blocks(text: str):
    """(info string, body) of every fenced block."""
    return [(m.group(1).strip(), m.group(2)) for m in FENCE.finditer(text)]


def prose(text: str) -> str:
    """The text outside fenced blocks and inline code."""
    text = FENCE.sub("", text)
    return re.sub(r"`[^`\n]*`", "", text)


def shell_commands(body: str):
    """The commands of a ``sh quick`` block: comments dropped, ``\\`` continuations joined."""
    commands, pending = [], ""
    for line in body.splitlines():
        line = pending + line
        pending = ""
        if line.rstrip().endswith("\\"):
            pending = line.rstrip()[:-1] + " "
            continue
        words = shlex.split(line, comments=True)
        if words:
            commands.append(words)
    assert not pending, "a quick block ends with a continuation line"
    return commands


def interpreter(words):
    """``python``/``.venv/bin/python`` -> this test's interpreter; anything else is refused."""
    head, *rest = words
    assert head in ("python", "python3", ".venv/bin/python"), f"a quick command must run Python: {words}"
    return [sys.executable, *rest]


def slug(heading: str) -> str:
    """GitHub's anchor of a heading: lower case, punctuation dropped, spaces to hyphens."""
    text = re.sub(r"`", "", heading.strip()).lower()
    text = "".join(c for c in text if c in " -_" or unicodedata.category(c)[0] in "LN")
    return text.replace(" ", "-")


def anchors(path: Path) -> set:
    text = FENCE.sub("", path.read_text(encoding="utf-8"))
    found = {slug(h) for h in re.findall(r"^#+\s+(.*)$", text, re.M)}
    found |= set(re.findall(r'<a id="([^"]+)"', text))
    return found


def links(path: Path):
    for m in LINK.finditer(prose(path.read_text(encoding="utf-8"))):
        target = m.group(1) or m.group(2)
        if not re.match(r"^[a-z]+:", target):  # http:, https:, mailto: are not checked
            yield target


def test_the_pages_exist_and_are_short():
    assert (ROOT / "docs" / "README.md").exists()
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert len(readme.splitlines()) <= 200
    assert "make report" in readme and "make test" in readme   # CI runs the README's `make test`
    for page in PAGES[1:]:
        text = page.read_text(encoding="utf-8")
        assert len(text.splitlines()) <= 250, page
        if page.name != "README.md":
            assert "(README.md)" in text.split("\n\n")[1], f"{page} does not link back to the index"


def test_the_index_lists_every_page():
    index = (ROOT / "docs" / "README.md").read_text(encoding="utf-8")
    for page in (ROOT / "docs").glob("*.md"):
        if page.name != "README.md":
            assert f"({page.name})" in index, page.name


@pytest.mark.parametrize("page", PAGES, ids=lambda p: str(p.relative_to(ROOT)))
def test_every_relative_link_resolves(page):
    for target in links(page):
        file, _, anchor = target.partition("#")
        resolved = (page.parent / file).resolve() if file else page
        assert resolved.exists(), f"{page.name}: {target} does not exist"
        if anchor and resolved.suffix == ".md":
            assert anchor in anchors(resolved), f"{page.name}: {target}: no such heading"


def test_the_link_checker_sees_a_broken_link(tmp_path):
    """Negative control: a missing file and a missing heading are both caught."""
    (tmp_path / "a.md").write_text("# A\n\n[b](b.md) [self](#nothing) [ok](#a) `[no](code.md)`\n")
    page = tmp_path / "a.md"
    found = list(links(page))
    assert found == ["b.md", "#nothing", "#a"]
    assert not (tmp_path / "b.md").exists() and "nothing" not in anchors(page) and "a" in anchors(page)
    assert slug("The ring's retrograde turn") == "the-rings-retrograde-turn"


def quick_blocks():
    out = []
    for page in PAGES:
        for info, body in blocks(page.read_text(encoding="utf-8")):
            if info in ("sh quick", "python quick"):
                out.append((page, info, body))
    return out


def test_there_are_quick_commands_in_the_readme():
    infos = [info for page, info, _ in quick_blocks() if page == ROOT / "README.md"]
    assert infos, "the README's first session is not marked quick"


def test_every_quick_command_runs(tmp_path):
    env = dict(os.environ, MPLBACKEND="Agg",
               PYTHONPATH=os.pathsep.join(filter(None, [str(ROOT), os.environ.get("PYTHONPATH")])))
    ran = 0
    for page, info, body in quick_blocks():
        if info == "python quick":
            commands = [[sys.executable, "-c", body]]
        else:
            commands = [interpreter(words) for words in shell_commands(body)]
        for command in commands:
            done = subprocess.run(command, cwd=tmp_path, env=env, capture_output=True, text=True,
                                  timeout=300)
            shown = " ".join(command[1:])[:200]
            assert done.returncode == 0, (
                f"{page.relative_to(ROOT)}: `{shown}` exited {done.returncode}\n{done.stderr[-2000:]}")
            ran += 1
    assert ran >= 5
