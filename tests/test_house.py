"""tools/house.py counts what the house rules ask (long modules, unexplained lazy imports, private names across
packages): each count on a snippet that breaks the rule and on one that keeps it (the negative control), the
modules already split (the hybrid driver, the disk's claims, the threshold study) keep all three, and so does the
whole tree house.py scans by default (verify/, models/, tools/, benchmarks/, examples/), but for the files of
:data:`EXCEPTIONS`, each with its reason; the same check on a made-up tree that breaks each rule once fails
(its negative control)."""
from __future__ import annotations

import ast
import importlib.util
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
_spec = importlib.util.spec_from_file_location("house", ROOT / "tools" / "house.py")
house = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(house)

CLEAN = ["verify/engine/hybrid.py", "verify/engine/hybrid_guards.py", "verify/engine/hybrid_rolling.py",
         "verify/engine/hybrid_run.py", "verify/engine/hybrid_sliding.py", "verify/engine/hybrid_switches.py",
         "verify/engine/hybrid_system.py", "verify/engine/slip_onset.py", "verify/claims/disk.py",
         "verify/claims/disk_equations.py", "verify/claims/disk_stability.py", "verify/claims/disk_spindown.py",
         "verify/studies/thresholds"]

#: Files the whole-tree check leaves out, with why.  An entry goes when its reason does (the test below fails
#: once an excepted file has no finding left, so that its exception is removed then).
EXCEPTIONS: dict = {}


def _lazy(source: str) -> list:
    return house.lazy_imports(ast.parse(source), source.splitlines())


def test_an_import_inside_a_function_counts_unless_it_says_why():
    assert len(_lazy("import os\n\ndef f():\n    import json\n    return json\n")) == 1
    assert len(_lazy("def f():\n    class A:\n        def g(self):\n            from x import y\n")) == 1
    # the controls: the reason on the line, or a module-level import, is not counted
    assert _lazy("def f():\n    import json  # lazy: the CLI's start-up time (measured)\n") == []
    assert _lazy("def f():\n    from x import (  # lazy: import cycle (x imports this module)\n        y,\n    )\n") == []
    assert _lazy("import json\ntry:\n    import numpy\nexcept ImportError:\n    numpy = None\n") == []


def test_a_private_name_counts_only_across_packages():
    def private(source, package):
        return house.private_imports(ast.parse(source), package)

    assert len(private("from ..engine.validation import _domain_end\n", "verify.studies")) == 1
    assert len(private("from verify.engine.validation import _domain_end\n", "tests")) == 1
    # the controls: the same package, a public name, a dunder
    assert private("from .validation import _domain_end\n", "verify.engine") == []
    assert private("from ..engine.validation import domain_end\n", "verify.studies") == []
    assert private("from verify import __version__\n", "tests") == []


def test_the_split_modules_keep_the_house_rules():
    found = house.survey(CLEAN)
    assert found == {"long": [], "lazy": [], "private": []}, found
    lengths = [len(p.read_text().splitlines()) for p in house.python_files(CLEAN)]
    assert len(lengths) == len(CLEAN) - 1 + 4 and max(lengths) <= house.MAX_LINES  # the package's four modules


def findings(paths, exceptions) -> list:
    """house.py's findings under ``paths`` (relative to ``house.ROOT``) outside ``exceptions``, one line each,
    as ``python tools/house.py`` prints them."""
    found = house.survey(paths)
    lines = [f"{rel}: {n} lines (more than {house.MAX_LINES}: split it by concept)" for rel, n in found["long"]]
    lines += [f"{rel}:{n}: {text}  (an import inside a function without '{house.LAZY_MARK} <reason>')"
              for rel, n, text in found["lazy"]]
    lines += [f"{rel}:{n}: {text}  (a private name imported across packages)" for rel, n, text in found["private"]]
    return [line for line in lines if line.split(":")[0] not in exceptions]


def test_the_whole_tree_keeps_the_house_rules():
    broken = findings(house.DEFAULT_PATHS, EXCEPTIONS)
    assert not broken, ("the house rules (docs/architecture.md) are broken in:\n  " + "\n  ".join(broken)
                        + "\nfix each (python tools/house.py lists them) or, for a reason that will pass, add the file "
                          "to EXCEPTIONS with that reason")


def test_each_exception_is_still_needed():
    for rel, reason in EXCEPTIONS.items():
        assert (house.ROOT / rel).is_file(), f"EXCEPTIONS names {rel}, which does not exist: remove it ({reason})"
        assert findings([rel], {}), f"{rel} keeps the house rules now: remove its exception ({reason})"


def test_the_whole_tree_check_fails_on_each_rule(tmp_path, monkeypatch):
    """The negative control: the same check on a tree that breaks each rule once lists the three, and an
    exception removes only its own file's findings."""
    monkeypatch.setattr(house, "ROOT", tmp_path)
    for package in ("pkg", "pkg/a", "pkg/b"):
        (tmp_path / package).mkdir()
        (tmp_path / package / "__init__.py").write_text("")
    (tmp_path / "pkg/a/long.py").write_text("x = 1\n" * (house.MAX_LINES + 1))
    (tmp_path / "pkg/a/lazy.py").write_text("def f():\n    import json\n    return json\n\n\n_hidden = 1\n")
    (tmp_path / "pkg/b/private.py").write_text("from ..a.lazy import _hidden\n")
    broken = findings(["pkg"], {})
    assert [line.split(":")[0] for line in broken] == ["pkg/a/long.py", "pkg/a/lazy.py", "pkg/b/private.py"], broken
    assert findings(["pkg"], {"pkg/a/lazy.py": "a reason"}) == [broken[0], broken[2]]
    # kept: the reason on the line, the long module split, the name made public
    (tmp_path / "pkg/a/long.py").write_text("x = 1\n" * house.MAX_LINES)
    (tmp_path / "pkg/a/lazy.py").write_text("def f():\n    import json  # lazy: a reason\n    return json\n\n\n"
                                            "hidden = 1\n")
    (tmp_path / "pkg/b/private.py").write_text("from ..a.lazy import hidden\n")
    assert findings(["pkg"], {}) == []
