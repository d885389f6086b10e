"""What a report job depends on, as one hash: the job's sources, its data files, its inputs, the versions.

A job's key is the sha256 of

* the Python sources its entry modules reach by ``import`` (the closure of the project's static
  import graph over ``models/`` and ``verify/``, every ``import`` anywhere in a file counted,
  including those inside functions, plus the ``__init__`` of every package on the way, since
  importing a module runs them);
* the data files beside those sources (``verify/claims/paper.md``, the sweep specs, ...): every
  non-Python file in the folder of a module of the closure, and the files the job names itself
  (a reference case);
* the job's own arguments, and the versions and machine it runs on (heyoka's SIMD width
  changes which lanes share a batch, the CPU can change the last bit).

A change anywhere in that set changes the key, so a cached result is never older than what
produced it; a change outside it (another claim module, the renderer) leaves the key alone.
"""
from __future__ import annotations

import ast
import functools
import hashlib
import json
import platform
from pathlib import Path

from ..provenance import ROOT, cpu_model, versions

PACKAGES = ("models", "verify")


def _module_path(name: str):
    """The file of project module ``name`` (a package's ``__init__.py``), or None outside the project."""
    if name.split(".")[0] not in PACKAGES:
        return None
    base = ROOT.joinpath(*name.split("."))
    if (base / "__init__.py").exists():
        return base / "__init__.py"
    if base.with_suffix(".py").exists():
        return base.with_suffix(".py")
    return None


def _package_of(name: str, path: Path) -> str:
    return name if path.name == "__init__.py" else name.rpartition(".")[0]


@functools.lru_cache(maxsize=None)
def direct_imports(name: str) -> frozenset:
    """The project modules module ``name`` imports anywhere in its file (resolved, existing ones)."""
    path = _module_path(name)
    if path is None:
        return frozenset()
    package = _package_of(name, path)
    found = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"), filename=str(path))):
        if isinstance(node, ast.Import):
            found.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                parts = package.split(".")
                base = ".".join(parts[:len(parts) - node.level + 1])
                target = f"{base}.{node.module}" if node.module else base
            else:
                target = node.module
            found.add(target)
            found.update(f"{target}.{alias.name}" for alias in node.names)  # ``from pkg import submodule``
    out = set()
    for target in found:
        parts = target.split(".")
        for i in range(1, len(parts) + 1):  # the packages on the way run their __init__
            if _module_path(".".join(parts[:i])) is not None:
                out.add(".".join(parts[:i]))
    out.discard(name)
    return frozenset(out)


def closure(entries) -> tuple:
    """Every project module reachable from ``entries`` (module names), sorted."""
    seen, todo = set(), list(entries)
    while todo:
        name = todo.pop()
        if name in seen or _module_path(name) is None:
            continue
        seen.add(name)
        parts = name.split(".")
        todo.extend(".".join(parts[:i]) for i in range(1, len(parts)))
        todo.extend(direct_imports(name))
    return tuple(sorted(seen))


def files_of(entries, extra_files=()) -> tuple:
    """The files a job reads: its modules' sources, the data files beside them, ``extra_files``."""
    files = set()
    for name in closure(entries):
        path = _module_path(name)
        files.add(path)
        files.update(p for p in path.parent.iterdir() if p.is_file() and p.suffix not in (".py", ".pyc"))
        specs = path.parent / "specs"
        if specs.is_dir():
            files.update(p for p in specs.iterdir() if p.is_file())
    files.update(Path(f).resolve() for f in extra_files)
    return tuple(sorted(files))


@functools.lru_cache(maxsize=None)
def _file_digest(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def environment() -> dict:
    """Versions and machine: part of every key.  The SIMD width is the one the batch runs use
    (:func:`verify.engine.lanes.simd_width`, which ``VERIFY_SIMD_WIDTH`` overrides): results
    differ in the last bits between widths."""
    from ..engine.lanes import simd_width  # lazy: heyoka (0.7 s) kept out of the workers' start-up (via .runner)

    return {"versions": _versions(versions), "machine": platform.machine(), "processor": cpu_model(),
            "simd_width": simd_width()}


@functools.lru_cache(maxsize=1)
def _versions(versions) -> dict:
    return versions()


def job_key(name: str, entries, args, extra_files=(), code: str = "") -> str:
    """The sha256 naming one job's result: see the module docstring for what goes in; ``code`` is
    the source of the job's own function."""
    h = hashlib.sha256()
    h.update(json.dumps({"job": name, "args": args, "environment": environment(), "code": code},
                        sort_keys=True).encode())
    for path in files_of(entries, extra_files):
        h.update(str(path.relative_to(ROOT) if path.is_relative_to(ROOT) else path).encode() + b"\0")
        h.update(_file_digest(path).encode())
    return h.hexdigest()
