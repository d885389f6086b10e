"""A sweep's axes: the values along each, computed when asked for, and the grid's points in order.

An axis of a spec (:mod:`verify.sweep.spec`, ``[[axis]]``) runs from ``from`` to ``to`` in ``count``
values, linear or geometric; its ends are kept exactly as written.  No list of values is built:
a typo in a count costs nothing until :mod:`verify.sweep.runner` refuses the sweep by its size.
"""
from __future__ import annotations

import itertools
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np


class AxisValues(Sequence):
    """The values of an axis, each computed when asked for (no list of them is ever built).

    Value j is exactly what the former tuple held: linear ``lo + (hi - lo) * j / (count - 1)``,
    geometric ``lo * (hi / lo) ** (j / (count - 1))``, the ends exactly as written.
    """

    __slots__ = ("lo", "hi", "count", "scale")

    def __init__(self, lo: float, hi: float, count: int, scale: str):
        self.lo, self.hi, self.count, self.scale = lo, hi, count, scale

    def __len__(self) -> int:
        return self.count

    def value(self, j: int) -> float:
        lo, hi, count = self.lo, self.hi, self.count
        if count == 1:
            return lo
        if j == count - 1:
            return hi
        if self.scale == "linear":
            return lo + (hi - lo) * j / (count - 1)
        return lo if j == 0 else lo * (hi / lo) ** (j / (count - 1))

    def __getitem__(self, j):
        if isinstance(j, slice):
            return tuple(self.value(i) for i in range(*j.indices(self.count)))
        j = int(j)
        if j < 0:
            j += self.count
        if not 0 <= j < self.count:
            raise IndexError(f"axis value {j} of {self.count}")
        return self.value(j)

    def take(self, js) -> np.ndarray:
        """The values at the indices ``js`` (an integer array), each computed once."""
        js = np.asarray(js, dtype=np.int64)
        uniq, inverse = np.unique(js, return_inverse=True)
        return np.array([self.value(int(j)) for j in uniq], dtype=float)[inverse.reshape(js.shape)]

    @property
    def extremes(self) -> tuple:
        """(smallest, largest) value: the ends (the axis is monotone)."""
        return (min(self.lo, self.hi), max(self.lo, self.hi))

    def __array__(self, dtype=None, copy=None):
        return np.array([self.value(j) for j in range(self.count)], dtype=dtype)

    def __eq__(self, other):
        if isinstance(other, AxisValues):
            return (self.lo, self.hi, self.count, self.scale) == (other.lo, other.hi, other.count, other.scale)
        if isinstance(other, (tuple, list)):
            return len(other) == self.count and all(a == b for a, b in zip(self, other))
        return NotImplemented

    def __hash__(self):
        return hash((self.lo, self.hi, self.count, self.scale))

    def __repr__(self) -> str:
        return f"AxisValues(from={self.lo!r}, to={self.hi!r}, count={self.count}, scale={self.scale!r})"


@dataclass(frozen=True)
class Axis:
    """One ``[[axis]]`` of a spec: the name it sweeps, its values and their scale (linear or log)."""

    name: str
    values: AxisValues
    scale: str


def product(spec):
    """Every point of the sweep ``spec`` (a :class:`verify.sweep.spec.SweepSpec`) in index order, one at a
    time (itertools.product of the lazy axes)."""
    return itertools.product(*(a.values for a in spec.axes))
