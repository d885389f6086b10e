"""Bodies rolling on a plane, as sympy expressions ready for heyoka.

>>> from models import get_model
>>> disk = get_model("disk")                 # derived equations
>>> printed = get_model("disk", "paper")     # the paper's Eq. 18 as printed
>>> from models.ring import parameter_set
>>> parameter_set("printed")                 # the paper's ring as printed (defaults: "annular")
{'I1': '0.4993', 'I3': '0.8727', 'h': '0.4344'}

See :mod:`models.symbols` for the conventions (3-1-3 Euler angles, paper Fig. 1).
"""
from __future__ import annotations

from . import disk, effective, gyroscope, hurricane, ring, sliding_disk
from .base import Model
from .symbols import STATE_NAMES

_BUILDERS = {
    "disk": (disk.model, ("derived", "paper")),
    "ring": (ring.model, ("derived", "paper")),
    "hurricane": (hurricane.model, ("derived", "paper")),
    "sliding-disk": (sliding_disk.model, ("derived",)),
    "gyroscope": (gyroscope.model, ("derived", "paper")),
    "effective": (effective.model, ("derived",)),
}

MODEL_NAMES = tuple(_BUILDERS)


def _dissipative():
    from . import dissipative, ring_dissipation

    out = {f"disk+{n}": (lambda eq, n=n: dissipative.dissipative_disk(n)) for n in dissipative.LAW_NAMES}
    out.update({f"ring+{n}": (lambda eq, n=n: ring_dissipation.dissipative_ring(n)) for n in ring_dissipation.LAW_NAMES})
    return out


#: Models with an explicit dissipative term (derived equations only; energy + work is conserved).
DISSIPATIVE_NAMES = ("disk+moffatt", "disk+contact-rate", "ring+air-drag", "ring+rolling-friction")
ALL_NAMES = MODEL_NAMES + DISSIPATIVE_NAMES
#: Bodies that roll or slide with Coulomb friction: a rolling model plus the sliding phase of
#: :mod:`models.coulomb`, run by :mod:`verify.engine.hybrid` (not a single :class:`Model`).
COULOMB_NAMES = ("disk+coulomb", "ring+coulomb")


def sources(name: str) -> tuple:
    """The equation sources a model has ('derived', and 'paper' where transcribed)."""
    _check_name(name)
    return _BUILDERS[name][1] if name in _BUILDERS else ("derived",)


def get_model(name: str, equations: str = "derived") -> Model:
    """The model called ``name`` with equations from ``equations`` ('derived' or 'paper').

    ``name`` is one of :data:`MODEL_NAMES` (the paper's conservative bodies) or of
    :data:`DISSIPATIVE_NAMES` (a body with an explicit dissipative term).
    """
    _check_name(name)
    builder, allowed = _BUILDERS[name] if name in _BUILDERS else (_dissipative()[name], ("derived",))
    if equations not in allowed:
        raise ValueError(f"equations={equations!r} for model {name!r}; allowed: {', '.join(allowed)}")
    return builder(equations)


def _check_name(name: str) -> None:
    if name not in ALL_NAMES:
        raise ValueError(f"unknown model {name!r}; allowed: {', '.join(ALL_NAMES)}")


__all__ = ["ALL_NAMES", "COULOMB_NAMES", "DISSIPATIVE_NAMES", "Model", "MODEL_NAMES", "STATE_NAMES", "get_model", "sources"]
