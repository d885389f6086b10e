"""Parameters shared by every model."""
import sympy as sp

from .base import Parameter
from .symbols import g

#: The paper's g: g/L = 980 s^-2 (g = 980 cm s^-2, L = 1 cm), the default of every model's ``g``.
#: An int, so that ``sp.Integer``, ``mpmath.mpf`` and ``float`` of it are all exact.
PAPER_G = 980

GRAVITY = Parameter(
    "g", g, sp.Integer(PAPER_G),
    "g/L in s^-2, L = R (disk, ring) or a (hurricane balls); 980 is g with L = 1 cm",
    lower=0.0,
)


def inertia_parameters(I1_default, I3_default, what: str, notes=("", "")):
    """The parameters I1, I3 (positive) with their defaults; ``notes`` (I1's, I3's) are appended to
    the descriptions in parentheses, e.g. where a default comes from."""
    I1 = sp.Symbol("I1", positive=True)
    I3 = sp.Symbol("I3", positive=True)
    n1, n3 = (f" ({n})" if n else "" for n in notes)
    return (
        Parameter("I1", I1, I1_default, f"transverse moment of inertia about C in units of {what}{n1}", lower=0.0),
        Parameter("I3", I3, I3_default, f"axial moment of inertia about C in units of {what}{n3}", lower=0.0),
    )


#: I3 <= 2 I1 holds for any body of revolution (2 I1 - I3 = 2 sum m z^2 >= 0).
AXIAL_BOUND = ("I3 <= 2 I1 (any body of revolution: 2 I1 - I3 = 2 sum m z^2 >= 0)", lambda p: p["I3"] <= 2 * p["I1"])
