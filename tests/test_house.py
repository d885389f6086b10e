"""tools/house.py counts what the house rules ask (long modules, unexplained lazy imports, private names across
packages): each count on a snippet that breaks the rule and on one that keeps it (the negative control), and the
modules already split (the hybrid driver, the disk's claims, the threshold study) keep all three."""
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
