"""Reading the reference set's files (``reports/reference/<case>.json`` and ``index.json``), json only.

The scorer reads the cases through this module, not through :mod:`verify.reference` (whose package
imports sympy and heyoka to make and check the set); :mod:`verify.reference.store` writes the set
and re-exports these readers, so there is one reader for the whole suite.
"""
from __future__ import annotations

import hashlib
import json
from pathlib import Path

FORMAT = "rolling-verify reference trajectory, format 1"
INDEX_FORMAT = "rolling-verify reference set, format 1"
DIRECTORY = Path(__file__).resolve().parent.parent.parent / "reports" / "reference"


def file_sha256(path: Path) -> str:
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


def read_json(path: Path, format_: str, missing: str) -> dict:
    """A JSON record of the reference set, checked for its ``format``; ``ValueError`` naming the file
    otherwise (``missing``, with ``{path}`` filled in, when there is none)."""
    path = Path(path)
    try:
        record = json.loads(path.read_text())
    except FileNotFoundError:
        raise ValueError(missing.format(path=path)) from None
    except json.JSONDecodeError as err:
        raise ValueError(f"{path} is not valid JSON ({err})") from None
    if record.get("format") != format_:
        raise ValueError(f"{path} has format {record.get('format')!r}; this reader understands {format_!r}")
    return record


def read_case(path: Path) -> dict:
    """A case file, checked for its format; ``ValueError`` naming the file otherwise."""
    return read_json(path, FORMAT, "no reference case file {path}; run 'python -m verify reference --make'")


def read_index(directory: Path = DIRECTORY) -> dict:
    path = Path(directory) / "index.json"
    try:
        index = json.loads(path.read_text())
    except FileNotFoundError:
        raise ValueError(f"no reference set in {directory} (index.json missing); run 'python -m verify reference --make'") \
            from None
    if index.get("format") != INDEX_FORMAT:
        raise ValueError(f"{path} has format {index.get('format')!r}; this reader understands {INDEX_FORMAT!r}")
    return index


def load_set(directory: Path = DIRECTORY, names=None) -> list:
    """The case records of the set (all, or those named), each checked against the index's sha256."""
    directory = Path(directory)
    index = read_index(directory)
    known = {e["name"]: e for e in index["cases"]}
    wanted = list(known) if not names else list(names)
    out = []
    for n in wanted:
        if n not in known:
            raise ValueError(f"unknown reference case {n!r}; allowed: {', '.join(known)}")
        record = read_case(directory / known[n]["file"])
        if file_sha256(directory / known[n]["file"]) != known[n]["sha256"]:
            raise ValueError(f"{directory / known[n]['file']} does not match the sha256 in index.json: the file was "
                             "changed after it was made")
        out.append(record)
    return out
