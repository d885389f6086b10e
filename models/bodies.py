"""Bodies of revolution from data: a TOML file (or its fields) to a rolling model.

A body file names a convex meridian profile (:mod:`models.profiles`), the moments of inertia about the
centre of mass and, optionally, a narrower domain of tilts::

    name = "rounded-coin"
    description = "a coin with torus-rounded rims"
    [profile]                  # lengths in units of the body's scale L; g is then g/L
    kind = "torus-rim"
    radius = "1"
    half_thickness = "0.05"
    tube_radius = "0.05"
    [inertia]                  # about the centre of mass, per unit mass, in L^2
    I1 = "301/1200"
    I3 = "1/2"
    [domain]                   # optional: theta_min, theta_max inside the profile's own domain
    theta_max = "pi/2"
    [start]                    # optional: the body's default start (unset components 0)
    theta = "1.2"
    phidot = "1"
    psidot = "10"

Numbers are strings read exactly (decimals and fractions; a domain end may be a multiple of pi).  The
equations are those of every body (:func:`models.rolling.derive`, paper Eqs. 5-8 and 73) with the
profile's contact vector; I1, I3 become the model's runtime parameters (defaults: the file's), with g.
Invariants: the energy, Chaplygin's two linear integrals (transported from the middle of the domain,
:mod:`verify.engine.chaplygin`), and for a sphere profile Jellett's L . r_P and Routh's
omega3 sqrt(I1 I3 + I1 r2^2 + I3 r3^2) in closed form (as for the hurricane balls, paper Sec. IV).

A bad body is refused in one line naming the value (:class:`models.profiles.InvalidBody`): an unknown kind
or field, a length that is not positive, moments of inertia no mass distribution has, a centre of mass
outside the body, a domain that lets the contact reach a corner of the profile.
"""
from __future__ import annotations

import hashlib
import json
import os
import pickle
import re
import threading
import tomllib
from dataclasses import dataclass, replace
from functools import lru_cache
from pathlib import Path

import sympy as sp

from .base import Domain, Parameter
from .build import invariant, rolling_model
from .catalogue import BODY_PREFIX
from .common import AXIAL_BOUND, GRAVITY, inertia_parameters
from .profile_curve import R2, R3, CurveError, read_expression, with_contact
from .profiles import EXPRESSIONS, FIELDS, RELATIONS, InvalidBody, check_domain, check_inertia, contact, vector
from .symbols import omega_body

#: The body files shipped with the suite (the paper's bodies from their profiles, and new ones).
DIRECTORY = Path(__file__).resolve().parent / "bodies"
_NUMBER = re.compile(r"^(?:[0-9eE.+\-*/() ]|pi)*$")
#: hex digits of the fingerprint in a model name body:NAME@HASH (48 bits: no accidental collision among files)
HASH_DIGITS = 12
_KEY = re.compile(rf"[a-z0-9][a-z0-9\-]*@[0-9a-f]{{{HASH_DIGITS}}}")
#: bodies registered in this process, by NAME@HASH (:func:`register`)
_REGISTERED: dict = {}


@dataclass(frozen=True)
class Body:
    """A body of revolution as data: its profile, exact inertia and domain (all sympy numbers)."""

    name: str
    description: str
    kind: str
    profile: tuple  # ((field, exact value), ...) in the kind's order
    I1: sp.Expr
    I3: sp.Expr
    theta_min: sp.Expr | None = None
    theta_max: sp.Expr | None = None
    start: tuple = ()  # ((state name, exact value), ...): the file's default start, or none

    @property
    def values(self) -> dict:
        return dict(self.profile)


def exact(text, what: str) -> sp.Expr:
    """A number of a body file, read exactly: a decimal, a fraction, or a rational multiple of pi."""
    if not isinstance(text, str):
        raise InvalidBody(f"{what} = {text!r}: give numbers as strings (\"0.05\", \"301/1200\", \"pi/2\"), read exactly")
    text = text.strip()
    # no powers and no exponent beyond 3 digits: '9**9**9**9' or '1e999999999' would hang sympy's exact arithmetic
    if not text or len(text) > 80 or "**" in text or re.search(r"[eE][+-]?\d{4,}", text) or not _NUMBER.match(text):
        raise InvalidBody(f"{what} = {text!r}: not a number (allowed: a decimal with an exponent of at most 3 digits, "
                          "a fraction such as 301/1200, or a rational multiple of pi such as pi/2; no powers)")
    try:  # the pattern lets through digits, operators, parentheses and pi only: nothing else to evaluate
        value = sp.sympify(text, locals={"pi": sp.pi}, rational=True)
    except (sp.SympifyError, SyntaxError, TypeError, ZeroDivisionError):
        raise InvalidBody(f"{what} = {text!r}: not a number") from None
    if value.free_symbols or not value.is_real or not value.is_finite:
        raise InvalidBody(f"{what} = {text!r}: not a finite real number")
    return value


def body_from_mapping(data: dict, source: str = "the body") -> Body:
    """A :class:`Body` from a body file's fields (a parsed TOML document)."""
    known = {"name", "description", "profile", "inertia", "domain", "start"}
    unknown = sorted(set(data) - known)
    if unknown:
        raise InvalidBody(f"{source}: unknown key {unknown[0]!r}; allowed: {', '.join(sorted(known))}")
    name = data.get("name")
    if not isinstance(name, str) or not re.fullmatch(r"[a-z0-9][a-z0-9\-]*", name or ""):
        raise InvalidBody(f"{source}: name = {name!r}; allowed: lower-case letters, digits and '-'")
    profile = data.get("profile")
    if not isinstance(profile, dict) or "kind" not in profile:
        raise InvalidBody(f"{source}: a [profile] table with a kind is needed")
    kind = profile["kind"]
    if not isinstance(kind, str):
        raise InvalidBody(f"{source}: profile.kind = {kind!r}; allowed: a string, one of the profile kinds")
    curve = EXPRESSIONS.get(kind, ())  # a curve's r and z: expressions of s through a whitelist (models.profile_curve)
    try:
        fields = {k: read_expression(v, f"profile.{k}") if k in curve else exact(v, f"profile.{k}")
                  for k, v in profile.items() if k != "kind"}
    except CurveError as err:
        raise InvalidBody(str(err)) from None
    inertia = data.get("inertia")
    if not isinstance(inertia, dict) or set(inertia) != {"I1", "I3"}:
        raise InvalidBody(f"{source}: an [inertia] table with exactly I1 and I3 is needed")
    I1, I3 = (exact(inertia[k], f"inertia.{k}") for k in ("I1", "I3"))
    domain = data.get("domain", {})
    if not isinstance(domain, dict) or set(domain) - {"theta_min", "theta_max"}:
        raise InvalidBody(f"{source}: [domain] takes theta_min and theta_max only")
    lo, hi = (exact(domain[k], f"domain.{k}") if k in domain else None for k in ("theta_min", "theta_max"))
    start = data.get("start", {})
    names = ("theta", "phi", "psi", "thetadot", "phidot", "psidot", "x", "y")
    if not isinstance(start, dict) or set(start) - set(names):
        raise InvalidBody(f"{source}: [start] takes the state's names only ({', '.join(names)})")
    body = Body(name, str(data.get("description", "")), kind,
                tuple((f, fields[f]) for f in FIELDS.get(kind, ()) if f in fields) + tuple(
                    (f, v) for f, v in fields.items() if f not in FIELDS.get(kind, ())), I1, I3, lo, hi,
                tuple((n, exact(start[n], f"start.{n}")) for n in names if n in start))
    check(body)
    return body


def check(body: Body) -> None:
    """Every rule of a body (:mod:`models.profiles`): the profile, the inertia, the domain, the start's tilt."""
    c = contact(body.kind, body.values)
    check_inertia(body.I1, body.I3)
    lo, hi = check_domain(c, body.theta_min, body.theta_max)
    tilt = dict(body.start).get("theta")
    if tilt is not None and not lo < tilt < hi:
        raise InvalidBody(f"start.theta = {tilt}: outside the body's domain ({lo}, {hi})")


def default_start(body: Body) -> tuple:
    """(state, words): the file's [start], or theta in the middle of the domain with phidot = 1, psidot = 10."""
    if body.start:
        return dict(body.start), f"the start in the [start] table of body {body.name}"
    c = contact(body.kind, body.values)
    lo, hi = check_domain(c, body.theta_min, body.theta_max)
    middle = sp.nsimplify((lo + hi) / 2)
    return ({"theta": middle, "phidot": sp.Integer(1), "psidot": sp.Integer(10)},
            f"the default start of body {body.name}: theta = {middle} (the middle of its domain), phidot = 1, psidot = 10")


def load(path) -> Body:
    """The body of the TOML file at ``path``, or of a name: a shipped body's ('rounded-coin'), or a model name's key
    'NAME@HASH' (:func:`resolve`: a body file registered in this process or saved in the cache)."""
    text = str(path)
    if text.startswith(BODY_PREFIX) and not Path(text).exists():  # a model name body:NAME or body:NAME@HASH
        return resolve(text[len(BODY_PREFIX):])
    if _KEY.fullmatch(text) and not Path(text).exists():
        return resolve(text)
    path = Path(path)
    if not path.suffix and not path.exists():
        path = DIRECTORY / f"{path.name}.toml"
    try:
        text = path.read_text()
    except UnicodeDecodeError:
        raise InvalidBody(f"body file {str(path)!r} is not UTF-8 text (a TOML body file is)") from None
    except OSError as err:
        raise InvalidBody(f"body file {str(path)!r}: {err.strerror or err}; shipped bodies: {', '.join(shipped())}") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise InvalidBody(f"body file {str(path)!r} is not TOML ({err})") from None
    return body_from_mapping(data, f"body file {path.name}")


# --- model names: body:NAME for a shipped body, body:NAME@HASH for any other file ----------------------------

def model_name(body: Body) -> str:
    """The model name of ``body``: ``body:NAME`` where it is the shipped body of that name (the same exact data), else
    ``body:NAME@HASH`` with HASH the first :data:`HASH_DIGITS` hex digits of its :func:`fingerprint`, so that the name
    can never resolve to a body with other equations (two files that differ only in description or [start] share it:
    their models are the same)."""
    if body.name in shipped() and fingerprint(_shipped(body.name)) == fingerprint(body):
        return BODY_PREFIX + body.name
    return f"{BODY_PREFIX}{body.name}@{fingerprint(body)[:HASH_DIGITS]}"


def register(body: Body) -> str:
    """Make ``body``'s model name (:func:`model_name`) resolve in this process (``get_model``, the friction engines) and
    in others on this machine: the body is kept in memory and its text (:func:`to_toml`) saved atomically as
    ``<cache>/registered/NAME@HASH.toml`` (:func:`cache_directory`), which another process reads back and checks
    against the hash (a sweep's or a report's workers).  A cache that cannot be written is skipped: there the name is
    refused loudly (:func:`resolve`).  Returns the model name."""
    name = model_name(body)
    key = name[len(BODY_PREFIX):]
    if "@" in key and key not in _REGISTERED:
        _REGISTERED[key] = body
        path = _registered_path(key)
        try:
            path.parent.mkdir(parents=True, exist_ok=True)
            tmp = path.with_suffix(f".{os.getpid()}.tmp")
            tmp.write_text(to_toml(body))
            os.replace(tmp, path)
        except OSError:
            pass
    return name


def resolve(key: str) -> Body:
    """The body of a model name's key: a shipped body's name, or 'NAME@HASH' registered (:func:`register`) in this
    process or saved in the cache by another; anything else is refused (:class:`InvalidBody`) naming what is allowed."""
    if "@" not in key:
        if key in shipped():
            return _shipped(key)
        raise InvalidBody(f"unknown body {BODY_PREFIX}{key}; shipped bodies: {', '.join(shipped())} "
                          "(a body file of your own: --body FILE.toml)")
    if not _KEY.fullmatch(key):
        raise InvalidBody(f"body name {BODY_PREFIX}{key!r}: allowed NAME or NAME@HASH ({HASH_DIGITS} hex digits)")
    if key in _REGISTERED:
        return _REGISTERED[key]
    path = _registered_path(key)
    try:
        text = path.read_text()
    except (OSError, UnicodeDecodeError):
        raise InvalidBody(f"{BODY_PREFIX}{key}: no body file with this name and fingerprint was loaded in this process "
                          f"or saved in {path.parent}; load its file first (--body FILE.toml, models.load_body(path))") from None
    try:
        body = body_from_mapping(tomllib.loads(text), f"registered body {path.name}")
    except (tomllib.TOMLDecodeError, InvalidBody) as err:
        raise InvalidBody(f"{BODY_PREFIX}{key}: the saved body {path} cannot be read ({err}); load its file again") from None
    if model_name(body) != BODY_PREFIX + key:
        raise InvalidBody(f"{BODY_PREFIX}{key}: the saved body {path} has the fingerprint "
                          f"{fingerprint(body)[:HASH_DIGITS]}, not the name's; load its file again")
    _REGISTERED[key] = body
    return body


def to_toml(body: Body) -> str:
    """The body as a body file's text, every number exact (read back by :func:`body_from_mapping` to the same
    :class:`Body`): what a run's file records and what :func:`register` saves."""
    def quoted(text) -> str:
        return json.dumps(str(text), ensure_ascii=False)  # a JSON string is a TOML basic string (escapes alike)

    lines = [f"name = {quoted(body.name)}", f"description = {quoted(body.description)}", "[profile]",
             f"kind = {quoted(body.kind)}"]
    lines += [f"{k} = {quoted(sp.sstr(v))}" for k, v in body.profile]
    lines += ["[inertia]", f"I1 = {quoted(sp.sstr(body.I1))}", f"I3 = {quoted(sp.sstr(body.I3))}"]
    domain = [(k, v) for k, v in (("theta_min", body.theta_min), ("theta_max", body.theta_max)) if v is not None]
    if domain:
        lines += ["[domain]"] + [f"{k} = {quoted(sp.sstr(v))}" for k, v in domain]
    if body.start:
        lines += ["[start]"] + [f"{k} = {quoted(sp.sstr(v))}" for k, v in body.start]
    return "\n".join(lines) + "\n"


def _registered_path(key: str) -> Path:
    return cache_directory() / "registered" / f"{key}.toml"


@lru_cache(maxsize=None)
def _shipped(name: str) -> Body:
    return load(DIRECTORY / f"{name}.toml")


def shipped() -> list:
    """Names of the body files shipped in ``models/bodies/``."""
    return sorted(p.stem for p in DIRECTORY.glob("*.toml"))


def body_of_revolution(kind: str, I1, I3, *, name: str = "body", description: str = "", theta_min=None,
                       theta_max=None, **profile):
    """The rolling model of a body of revolution given by its profile (Python's door to a body file).

    ``models.body_of_revolution("torus-rim", "301/1200", "1/2", radius="1", half_thickness="1/20",
    tube_radius="1/20")``; numbers as exact strings.  Returns a :class:`models.base.Model` that
    :func:`verify.solve` takes in place of a model name.
    """
    data = {"name": name, "description": description, "profile": {"kind": kind, **profile},
            "inertia": {"I1": str(I1), "I3": str(I3)}}
    domain = {k: str(v) for k, v in (("theta_min", theta_min), ("theta_max", theta_max)) if v is not None}
    if domain:
        data["domain"] = domain
    return model_of(body_from_mapping(data, f"body {name}"))


@lru_cache(maxsize=None)
def model_of(body: Body):
    """The rolling model of ``body``, named :func:`model_name` (registered: the name resolves, :func:`register`):
    derived once per body and kept on disk (:func:`cached_derivation`), so a second process pays nothing for sympy;
    in memory once per process."""
    model = cached_derivation(body)
    fixed, same = _fixed_and_shared(body)
    relations = tuple((text, _with(rule, fixed, same)) for text, rule in RELATIONS.get(body.kind, ()))
    return replace(model, name=register(body), relations=(AXIAL_BOUND,) + relations)


def cache_directory() -> Path:
    """Where derived bodies are kept: ``$HEYOKA_CACHE_DIR/bodies`` (the suite's cache folder), else
    ``~/.cache/rolling-verify/bodies``."""
    base = os.environ.get("HEYOKA_CACHE_DIR")
    return Path(base) / "bodies" if base else Path.home() / ".cache" / "rolling-verify" / "bodies"


def cached_derivation(body: Body):
    """The derived model of ``body`` without its relations (which hold functions, not data), from the disk cache
    when it holds one made by the same sources; keyed by the body's exact data (:func:`fingerprint`), the
    sources of the derivation and sympy's version (:func:`kept_on_disk`)."""
    key = hashlib.sha256((fingerprint(body) + _sources_hash() + sp.__version__).encode()).hexdigest()
    return kept_on_disk(body.name, key, lambda: _derive(body))


def kept_path(stem: str, key: str) -> Path:
    """The file :func:`kept_on_disk` keeps ``STEM`` under ``KEY`` in."""
    return cache_directory() / f"{stem}-{key[:24]}.pickle"


def kept_on_disk(stem: str, key: str, compute):
    """``compute()``, kept in :func:`cache_directory` as ``STEM-KEY.pickle``: read back if there and whole, else
    computed and written atomically (a temporary file renamed).  A cache that cannot be written is only skipped.

    The file holds the pickle's sha256 before the pickle: a damaged entry (a flipped byte can unpickle into another
    expression, or raise anything from TypeError to MemoryError) is never trusted, only computed again and
    rewritten.  A value computed here is returned as a later process will read it -- its pickle round trip --,
    not as computed: sympy rebuilds some trees otherwise (the thin disk's derived model is one: ``==`` tells the
    two apart), and the first run on an empty cache would compile other code, and so give other bits, than every
    run after it.
    """
    path = kept_path(stem, key)
    try:
        digest, data = path.read_bytes().split(b"\n", 1)
        if digest.decode() == hashlib.sha256(data).hexdigest():
            return pickle.loads(data)
    except Exception:  # missing, unreadable or damaged: a miss, whatever the damage raises
        pass
    data = pickle.dumps(compute())
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        tmp = path.with_suffix(f".{os.getpid()}.{threading.get_ident()}.tmp")
        tmp.write_bytes(hashlib.sha256(data).hexdigest().encode() + b"\n" + data)
        os.replace(tmp, path)
    except OSError:
        pass
    return pickle.loads(data)


@lru_cache(maxsize=None)
def _sources_hash() -> str:
    here = Path(__file__).resolve().parent
    h = hashlib.sha256()
    for name in ("base", "bodies", "build", "common", "profile_curve", "profiles", "rolling", "symbols"):
        h.update((here / f"{name}.py").read_bytes())
    return h.hexdigest()


def _fixed_and_shared(body: Body) -> tuple:
    _, symbols = _shape_parameters(body)
    fixed = {f: float(v) for f, v in symbols.items() if isinstance(v, sp.Integer)}
    same = {"tube_radius": "half_thickness"} if symbols.get("tube_radius") is symbols.get("half_thickness", 0) else {}
    return fixed, same


def _derive(body: Body):
    c = contact(body.kind, body.values)
    lo, hi = check_domain(c, body.theta_min, body.theta_max)
    below = c.below if lo == c.theta_min else "domain_min"
    above = c.above if hi == c.theta_max else "domain_max"
    p1, p3 = inertia_parameters(body.I1, body.I3, "M L^2", notes=("the body file's",) * 2)
    I1, I3 = p1.symbol, p3.symbol
    shape, symbols = _shape_parameters(body)
    r2, r3 = vector(body.kind, symbols)
    extra = _sphere_integrals(I1, I3, r2, r3) if body.kind == "sphere" else ()
    if body.kind == "curve":  # derived with r2, r3 as functions of theta, then put in (models.profile_curve)
        generic = rolling_model(f"body:{body.name}", body.description or f"curve body '{body.name}'",
                                (p1, p3, GRAVITY), I1, I3, R2, R3, Domain(lo, hi, below, above), unit="M L^2",
                                theta_ref=(lo + hi) / 2)
        return with_contact(generic, r2, r3)
    return rolling_model(f"body:{body.name}", body.description or f"{body.kind} body '{body.name}'",
                         (p1, p3, *shape, GRAVITY), I1, I3, r2, r3, Domain(lo, hi, below, above), unit="M L^2",
                         extra_invariants=extra, theta_ref=(lo + hi) / 2)


def contact_vector(body: Body) -> tuple:
    """(I1, I3, r2, r3) of ``body`` with the symbols of its model (:func:`model_of`): what the sliding phase of
    a Coulomb body (:func:`models.coulomb.body`) is derived from."""
    p1, p3 = inertia_parameters(body.I1, body.I3, "M L^2")
    _, symbols = _shape_parameters(body)
    return (p1.symbol, p3.symbol, *vector(body.kind, symbols))


def _with(rule, fixed: dict, same: dict):
    """A relation of the profile's numbers, given the run's parameters: the constants and shared symbols added."""
    def check(params):
        values = {**fixed, **params}
        values.update({a: values[b] for a, b in same.items()})
        return rule(values)
    return check


def _shape_parameters(body: Body) -> tuple:
    """(runtime parameters, the profile's values or symbols): an integer stays a constant (exact for heyoka, and
    the paper's bodies keep their own expressions: the disk's radius 1, the hurricane ball's centre at -1); any
    other number becomes a runtime parameter named by its field, the file's exact value its default.  A torus
    rim rounded all the way (tube_radius = half_thickness) keeps one symbol for both: it is what makes the body
    pass theta = pi/2 smoothly, so --param cannot split them."""
    params, symbols = [], {}
    if body.kind == "curve":  # a curve's numbers stay in its expressions: its checks hold for these values only
        return (), dict(body.profile)
    for field, value in body.profile:
        if body.kind == "torus-rim" and field == "tube_radius" and value == body.values["half_thickness"]:
            symbols[field] = symbols["half_thickness"]
            continue
        if value.is_integer:
            symbols[field] = value
            continue
        sym = sp.Symbol(field, real=True) if field == "centre_height" else sp.Symbol(field, positive=True)
        symbols[field] = sym
        params.append(Parameter(field, sym, value, f"{FIELD_WORDS[field]} in units of L (the body file's {value})",
                                lower=None if field == "centre_height" else 0.0))
    return tuple(params), symbols


#: What each profile field is, for a parameter's description.
FIELD_WORDS = {"radius": "the rim's (or sphere's) radius", "half_thickness": "the rims' distance from the mid-plane",
               "tube_radius": "the rims' rounding radius", "centre_height": "the profile's centre above the centre of mass",
               "a": "the equatorial semi-axis", "c": "the polar semi-axis"}


def _sphere_integrals(I1, I3, r2, r3) -> tuple:
    """Jellett's L_C . r_P and Routh's omega3 sqrt(I1 I3 + I1 r2^2 + I3 r3^2) of a sphere profile."""
    w = omega_body()
    return (invariant("jellett", I1 * w[1] * r2 + I3 * w[2] * r3,
                      "Jellett's integral L_C . r_P (angular momentum about C along CP)"),
            invariant("routh", w[2] * sp.sqrt(I1 * I3 + I1 * r2 ** 2 + I3 * r3 ** 2),
                      "Routh's integral omega3 sqrt(I1 I3 + I1 r2^2 + I3 r3^2)"))


def fingerprint(body: Body) -> str:
    """sha256 of the body's exact data: what a derivation cache is keyed on."""
    text = repr((body.kind, body.profile, body.I1, body.I3, body.theta_min, body.theta_max))
    return hashlib.sha256(text.encode()).hexdigest()


__all__ = ["Body", "DIRECTORY", "HASH_DIGITS", "InvalidBody", "body_from_mapping", "body_of_revolution", "check",
           "default_start", "exact", "fingerprint", "load", "model_name", "model_of", "register", "resolve", "shipped",
           "to_toml"]
