"""Count what the house rules of the developers' guide ask of the code's layout (issue 33, item 4).

    python tools/house.py                 # verify/, models/, tools/, benchmarks/, examples/: findings and counts
    python tools/house.py --counts        # the three counts only
    python tools/house.py verify/engine   # only these folders or files
    python tools/house.py --strict        # exit 1 if anything is found (for CI, once the tree is clean)

Three counts, each read from the source by Python's own parser (:mod:`ast`), nothing imported or run:

* **long modules** -- a module of more than :data:`MAX_LINES` lines (one module per concept, <= ~500 lines);
* **unexplained lazy imports** -- an ``import`` inside a function (or a method) without ``# lazy: <reason>`` on
  one of its lines: imports belong at the module's top unless they are lazy on purpose (a heavy optional
  package, an import cycle, the CLI's start-up time), and then the line says why;
* **private names across packages** -- ``from X import _name`` where X is not in the importing module's own
  package (``from ..engine.validation import _x`` in ``verify/studies``, ``from verify.x import _y`` in
  ``tests``): a name shared across packages is public, with a docstring, or it moves.

Tests (``tests/``) are not scanned by default (a test imports inside its function on purpose, to keep
collection light); name the folder to scan it.  ``tests/test_house.py`` fails on any finding in the default
scope but for the files its ``EXCEPTIONS`` name with their reasons; ``--strict`` exits 1 on any finding.
"""
from __future__ import annotations

import argparse
import ast
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
DEFAULT_PATHS = ("verify", "models", "tools", "benchmarks", "examples")
#: Lines above which a module counts as long (the guide's "<= ~500 lines").
MAX_LINES = 500
LAZY_MARK = "# lazy:"


def python_files(paths) -> list:
    """The .py files under ``paths`` (folders or files, relative to the repository), sorted, without
    virtual environments and caches."""
    out = []
    for p in paths:
        path = (ROOT / p) if not Path(p).is_absolute() else Path(p)
        if path.is_file() and path.suffix == ".py":
            out.append(path)
        elif path.is_dir():
            out += [f for f in path.rglob("*.py")
                    if not any(part.startswith(".") or part in ("__pycache__", "build") for part in f.relative_to(ROOT).parts)]
    return sorted(set(out))


def module_name(path: Path) -> tuple:
    """(dotted module name, its package) of a file under the repository: ``verify/engine/hybrid.py`` is
    (``verify.engine.hybrid``, ``verify.engine``); a package's ``__init__.py`` is its own package."""
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts = parts[:-1]
        return ".".join(parts), ".".join(parts)
    return ".".join(parts), ".".join(parts[:-1])


def target_package(module: str) -> str:
    """The package a module name belongs to: the module itself if it is a package (a folder with
    ``__init__.py`` in the repository), else its parent."""
    folder = ROOT.joinpath(*module.split("."))
    if (folder / "__init__.py").exists():
        return module
    return module.rpartition(".")[0]


def resolve(node: ast.ImportFrom, package: str) -> str:
    """The absolute module name of ``from <node.module> import ...`` written in ``package``."""
    if not node.level:
        return node.module or ""
    base = package.split(".") if package else []
    base = base[: len(base) - (node.level - 1)] if node.level > 1 else base
    return ".".join(base + ([node.module] if node.module else []))


def lazy_imports(tree: ast.AST, lines: list) -> list:
    """[(line, text)] of the imports inside functions with no ``# lazy:`` on any of their lines."""
    found = []

    def visit(node, inside_function):
        for child in ast.iter_child_nodes(node):
            in_fn = inside_function or isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda))
            if inside_function and isinstance(child, (ast.Import, ast.ImportFrom)):
                span = lines[child.lineno - 1: (child.end_lineno or child.lineno)]
                if not any(LAZY_MARK in line for line in span):
                    found.append((child.lineno, lines[child.lineno - 1].strip()))
            visit(child, in_fn)

    visit(tree, False)
    return found


def private_imports(tree: ast.AST, package: str) -> list:
    """[(line, text)] of ``from X import _name`` with X outside ``package`` (dunder names are not private)."""
    found = []
    for node in ast.walk(tree):
        if not isinstance(node, ast.ImportFrom) or node.module == "__future__":
            continue
        source = resolve(node, package)
        if target_package(source) == package:
            continue
        for alias in node.names:
            if alias.name.startswith("_") and not alias.name.startswith("__"):
                found.append((node.lineno, f"from {'.' * node.level}{node.module or ''} import {alias.name}"))
    return found


def survey(paths) -> dict:
    """{'long': [(file, lines)], 'lazy': [(file, line, text)], 'private': [(file, line, text)]}."""
    out = {"long": [], "lazy": [], "private": []}
    for path in python_files(paths):
        text = path.read_text(encoding="utf-8")
        lines = text.splitlines()
        rel = str(path.relative_to(ROOT))
        if len(lines) > MAX_LINES:
            out["long"].append((rel, len(lines)))
        tree = ast.parse(text, filename=rel)
        _, package = module_name(path)
        out["lazy"] += [(rel, n, t) for n, t in lazy_imports(tree, lines)]
        out["private"] += [(rel, n, t) for n, t in private_imports(tree, package)]
    return out


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description="Count long modules, unexplained lazy imports and private names "
                                                 "imported across packages.")
    parser.add_argument("paths", nargs="*", default=list(DEFAULT_PATHS),
                        help=f"folders or files to scan (default: {' '.join(DEFAULT_PATHS)})")
    parser.add_argument("--counts", action="store_true", help="print the three counts only")
    parser.add_argument("--strict", action="store_true", help="exit 1 if anything is found")
    args = parser.parse_args(argv)
    missing = [p for p in args.paths if not (ROOT / p).exists()]
    if missing:
        print(f"house.py: path {missing[0]!r} does not exist; allowed: folders or .py files under {ROOT}",
              file=sys.stderr)
        return 2
    found = survey(args.paths)
    if not args.counts:
        print(f"Modules over {MAX_LINES} lines:")
        for rel, n in sorted(found["long"], key=lambda r: -r[1]):
            print(f"  {rel}: {n} lines")
        print(f"Imports inside functions without '{LAZY_MARK} <reason>':")
        for rel, n, t in found["lazy"]:
            print(f"  {rel}:{n}: {t}")
        print("Private names imported across packages:")
        for rel, n, t in found["private"]:
            print(f"  {rel}:{n}: {t}")
    files = len({r[0] for r in found["lazy"]})
    print(f"long modules: {len(found['long'])}; unexplained lazy imports: {len(found['lazy'])} (in {files} files); "
          f"private names across packages: {len(found['private'])}")
    if not args.counts:
        print("Next: split a long module by concept, move an import to the top or write '# lazy: <reason>' on its "
              "line, make a shared name public (with a docstring) or move it; then run this again.")
    return 1 if args.strict and any(found.values()) else 0


if __name__ == "__main__":
    sys.exit(main())
