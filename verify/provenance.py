"""What produced a report: versions, a hash of the source tree, the precisions used."""
from __future__ import annotations

import hashlib
import os
import platform
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SOURCE_DIRS = ("models", "verify")


def source_hash() -> str:
    """sha256 over the Python sources of models/ and verify/ (paths and contents)."""
    h = hashlib.sha256()
    for d in SOURCE_DIRS:
        for path in sorted((ROOT / d).rglob("*.py")):
            h.update(str(path.relative_to(ROOT)).encode())
            h.update(b"\0")
            h.update(path.read_bytes())
    return h.hexdigest()


def versions() -> dict:
    import heyoka
    import matplotlib
    import mpmath
    import numpy
    import sympy

    return {
        "python": platform.python_version(),
        "heyoka": heyoka.__version__,
        "numpy": numpy.__version__,
        "mpmath": mpmath.__version__,
        "sympy": sympy.__version__,
        "matplotlib": matplotlib.__version__,
    }


def provenance(precisions) -> dict:
    return {"versions": versions(), "source_sha256": source_hash(), "precisions": list(precisions)}


def write_atomic(path: Path, data: bytes | str) -> None:
    """Write a file so that readers see either the old or the whole new content."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    if isinstance(data, str):
        data = data.encode()
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
            f.flush()
            os.fsync(f.fileno())
        os.chmod(tmp, 0o644)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
