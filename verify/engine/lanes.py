"""The SIMD width the batch integrators use: one setting for the whole suite.

heyoka's batch mode runs ``batch_size`` trajectories in the lanes of SIMD registers.  The
width it recommends depends on the CPU (4 doubles with AVX2, 8 with AVX-512), and results
of batch runs differ at round-off between widths, so the width is an explicit setting:

* ``VERIFY_SIMD_WIDTH=N`` in the environment fixes it (e.g. to reproduce on an AVX2 machine
  what an AVX-512 machine computes, or to run the batch-dependent tests at both widths);
* otherwise :func:`heyoka.recommended_simd_size` decides.

Nothing in the suite may assume a particular width.
"""
from __future__ import annotations

import os

import heyoka as hy

ENV = "VERIFY_SIMD_WIDTH"


def simd_width() -> int:
    """Lanes of one SIMD register for double precision (``VERIFY_SIMD_WIDTH`` or heyoka's choice)."""
    text = os.environ.get(ENV, "").strip()
    if not text:
        return int(hy.recommended_simd_size())
    try:
        width = int(text)
    except ValueError:
        width = 0
    if width < 1 or width > 64:
        raise ValueError(f"{ENV}={text!r}: allowed a whole number of lanes from 1 to 64 (e.g. 4 or 8)")
    return width
