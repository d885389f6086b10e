"""Bodies rolling on a plane, as sympy expressions ready for heyoka.

>>> from models import get_model
>>> disk = get_model("disk")                 # derived equations
>>> printed = get_model("disk", "paper")     # the paper's Eq. 18 as printed
>>> from models.ring import parameter_set
>>> parameter_set("printed")                 # the paper's ring as printed (defaults: "annular")
{'I1': '0.4993', 'I3': '0.8727', 'h': '0.4344'}

See :mod:`models.symbols` for the conventions (3-1-3 Euler angles, paper Fig. 1).

The names (:data:`ALL_NAMES`, ...) and :mod:`models.catalogue` come without sympy; the models
themselves, and the submodules, are imported when first asked for (``get_model``,
``models.disk``, ``models.Model``), so that a command that only lists or checks names answers
at once.
"""
from __future__ import annotations

import importlib

from .catalogue import ALIASES, ALL_NAMES, BODY_PREFIX, COULOMB_NAMES, DISSIPATIVE_NAMES, MODEL_NAMES, STATE_NAMES

_EQUATIONS = {"disk": ("derived", "paper"), "ring": ("derived", "paper"), "hurricane": ("derived", "paper"),
              "sliding-disk": ("derived",), "gyroscope": ("derived", "paper"), "effective": ("derived",)}
_BUILDERS = {"disk": "disk", "ring": "ring", "hurricane": "hurricane", "sliding-disk": "sliding_disk",
             "gyroscope": "gyroscope", "effective": "effective"}


def _dissipative(name: str):
    from . import dissipative, ring_dissipation  # lazy: sympy (0.6 s) kept out of --help, which imports this package

    body, law = name.split("+", 1)
    return dissipative.dissipative_disk(law) if body == "disk" else ring_dissipation.dissipative_ring(law)


def sources(name: str) -> tuple:
    """The equation sources a model has ('derived', and 'paper' where transcribed)."""
    _check_name(name)
    return _EQUATIONS.get(name, ("derived",))


def get_model(name: str, equations: str = "derived"):
    """The model called ``name`` with equations from ``equations`` ('derived' or 'paper').

    ``name`` is one of :data:`MODEL_NAMES` (the paper's conservative bodies), of
    :data:`DISSIPATIVE_NAMES` (a body with an explicit dissipative term), ``body:NAME`` (a shipped body file) or
    ``body:NAME@HASH`` (any body file once loaded, :func:`models.bodies.register`).
    """
    _check_name(name)
    allowed = sources(name)
    if equations not in allowed:
        raise ValueError(f"equations={equations!r} for model {name!r}; allowed: {', '.join(allowed)}")
    if name.startswith(BODY_PREFIX):  # a body file: shipped (body:NAME) or registered (body:NAME@HASH), derived once
        from .bodies import model_of, resolve  # lazy: sympy (0.6 s) kept out of --help, which imports this package

        return model_of(resolve(name[len(BODY_PREFIX):]))
    if name in _BUILDERS:
        return importlib.import_module(f".{_BUILDERS[name]}", __name__).model(equations)
    return _dissipative(name)


def _check_name(name: str) -> None:
    if name.startswith(BODY_PREFIX):  # body:NAME (shipped) or body:NAME@HASH (a file loaded here or saved by another process)
        from .bodies import InvalidBody, resolve  # lazy: sympy (0.6 s) kept out of --help, which imports this package

        try:
            resolve(name[len(BODY_PREFIX):])
        except InvalidBody as err:
            raise ValueError(str(err)) from None
        return
    if name not in ALL_NAMES:
        hint = ""
        if name in ALIASES:
            model, params = ALIASES[name]
            hint = f" ({name!r} is the {model} with {', '.join(f'{k} = {v}' for k, v in params.items())})"
        raise ValueError(f"unknown model {name!r}{hint}; allowed: {', '.join(ALL_NAMES)}")


def __getattr__(attr: str):
    """``models.Model`` and the submodules (``models.disk``), imported when first used."""
    if attr == "Model":
        from .base import Model  # lazy: sympy (0.5 s) kept out of --help, which imports this package

        return Model
    if attr in ("body_of_revolution", "load_body"):  # a body of revolution from its profile (models.bodies)
        from . import bodies  # lazy: sympy (0.6 s) kept out of --help, which imports this package

        return bodies.body_of_revolution if attr == "body_of_revolution" else bodies.load
    try:
        return importlib.import_module(f".{attr}", __name__)
    except ModuleNotFoundError:
        raise AttributeError(f"module 'models' has no attribute {attr!r}") from None


__all__ = ["ALIASES", "ALL_NAMES", "COULOMB_NAMES", "DISSIPATIVE_NAMES", "Model", "MODEL_NAMES", "STATE_NAMES",
           "body_of_revolution", "get_model", "load_body", "sources"]
