"""The report's job cache: one entry per job, valid for one key (:mod:`.dependencies`).

An entry is ``jobs/<job name>.json`` holding the key, the job's data, its wall times and the
names of its images, which are stored once by content (``images/<sha256>``).  Entries are
written atomically as each job finishes, so an interrupted report resumes where it stopped;
an entry whose key differs from the job's current key is never read.  The folder is
``.report-cache/`` beside the sources (``VERIFY_REPORT_CACHE`` overrides it).
"""
from __future__ import annotations

import hashlib
import json
import os
from pathlib import Path
from typing import Optional

from ..provenance import write_atomic
from .dependencies import ROOT
from .figures import Image

FORMAT = 1


def default_folder() -> Path:
    return Path(os.environ.get("VERIFY_REPORT_CACHE") or ROOT / ".report-cache")


class JobCache:
    def __init__(self, folder=None):
        self.folder = Path(folder) if folder is not None else default_folder()

    def _entry_path(self, name: str) -> Path:
        return self.folder / "jobs" / (name.replace("/", "__") + ".json")

    def _read(self, name: str) -> Optional[dict]:
        try:
            entry = json.loads(self._entry_path(name).read_text())
        except (OSError, ValueError):
            return None
        return entry if entry.get("format") == FORMAT else None

    def get(self, name: str, key: str) -> Optional[dict]:
        """The entry of job ``name`` if it was computed for ``key`` and its images are all there, else None."""
        entry = self._read(name)
        if entry is None or entry.get("key") != key:
            return None
        try:
            entry["images"] = [Image(i["filename"], self._image_path(i["sha256"]).read_bytes(), i["alt"])
                               for i in entry["images"]]
        except OSError:
            return None
        return entry

    def last_seconds(self, name: str) -> Optional[float]:
        """The wall time of the job's last computation, whatever its key (for scheduling)."""
        entry = self._read(name)
        return None if entry is None else entry.get("seconds")

    def put(self, name: str, key: str, data, images, timing: dict, seconds: float) -> None:
        names = []
        for img in images:
            sha = hashlib.sha256(img.data).hexdigest()
            path = self._image_path(sha)
            if not path.exists():
                write_atomic(path, img.data)
            names.append({"filename": img.filename, "alt": img.alt, "sha256": sha})
        entry = {"format": FORMAT, "job": name, "key": key, "seconds": round(seconds, 2), "timing": timing,
                 "images": names, "data": data}
        write_atomic(self._entry_path(name), json.dumps(entry) + "\n")

    def _image_path(self, sha: str) -> Path:
        return self.folder / "images" / sha
