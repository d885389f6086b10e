"""What the models are, as plain data: names, parameters, domains, invariants and units.

Listing the models (``python -m verify models``), checking a name on the command line and labelling
a run's columns with units need none of the derivation: this module imports nothing heavy (no
sympy), so those answer at once.  Every entry is what :func:`models.get_model` derives, written
out; ``tests/test_catalogue.py`` compares each field with the derived model, so the two cannot
drift apart.

Units: time in s, lengths in the body's length unit L (the radius R of the disk and ring, the ball
radius a of the hurricane balls), g/L = 980 s^-2 by default (g = 980 cm s^-2 with L = 1 cm); in SI,
``--param g=9.81`` with L = 1 m.  Inertia in the model's ``inertia_unit`` (m R^2, or 2 m a^2 for the
two balls of mass m each), so an energy is in ``inertia_unit``/s^2.
"""
from __future__ import annotations

from dataclasses import dataclass

#: The state of every model, in this order (models.symbols: 3-1-3 Euler angles phi, theta, psi).
STATE_NAMES = ("theta", "phi", "psi", "thetadot", "phidot", "psidot", "x", "y")


@dataclass(frozen=True)
class ModelEntry:
    """One model as data.

    ``parameters`` are (name, exact default, allowed range, description); ``domain`` is (theta_min,
    theta_max, event below, event above) as text; ``inertia_unit`` the unit of moments of inertia
    (energies are in it per s^2).
    """

    name: str
    title: str
    equations: tuple
    parameters: tuple
    domain: tuple
    invariants: tuple
    inertia_unit: str
    normal_force: bool
    friction_required: bool

    @property
    def length_unit(self) -> str:
        """'R' (disk, ring), 'a' (the hurricane balls' ball radius) or 'L' (a body file's own scale)."""
        return "a" if self.inertia_unit.endswith("a^2") else "L" if self.inertia_unit.endswith("L^2") else "R"

    @property
    def parameter_names(self) -> tuple:
        return tuple(p[0] for p in self.parameters)


ENTRIES = (
    ModelEntry(
        'disk', 'thin disk or hoop rolling without slipping', ('derived', 'paper'),
        parameters=(
        ('k', '1/4', '(0, 0.5]', 'I1/(m R^2) with I3 = 2 I1; 1/4 disk, 1/2 hoop; at most 1/2 (all mass on the rim)'),
        ('g', '980', '(0, +inf)', 'g/L in s^-2, L = R (disk, ring) or a (hurricane balls); 980 is g with L = 1 cm'),
        ),
        domain=('0', 'pi', 'lies_flat', 'lies_flat'),
        invariants=('energy', 'chaplygin_1', 'chaplygin_2'), inertia_unit='m R^2',
        normal_force=True, friction_required=True),
    ModelEntry(
        'ring', 'thick ring or coin rolling on one rim', ('derived', 'paper'),
        parameters=(
        ('I1', '16720/33489', '(0, +inf)', 'transverse moment of inertia about C in units of m R^2 (default 0.4992684...: the exact annular cylinder R = 3.66 cm, h = 1.59 cm, w = 0.5 cm; the paper prints 0.4993: models.ring.PRINTED)'),
        ('I3', '58453/66978', '(0, +inf)', 'axial moment of inertia about C in units of m R^2 (default 0.8727194...: the exact annular cylinder R = 3.66 cm, h = 1.59 cm, w = 0.5 cm; the paper prints 0.8727: models.ring.PRINTED)'),
        ('h', '53/122', '[0, +inf)', 'half-thickness of the ring in units of R (default 0.4344262...: the exact annular cylinder R = 3.66 cm, h = 1.59 cm, w = 0.5 cm; the paper prints 0.4344: models.ring.PRINTED)'),
        ('g', '980', '(0, +inf)', 'g/L in s^-2, L = R (disk, ring) or a (hurricane balls); 980 is g with L = 1 cm'),
        ),
        domain=('0', 'pi/2', 'lies_flat', 'rim_switch'),
        invariants=('energy', 'chaplygin_1', 'chaplygin_2'), inertia_unit='m R^2',
        normal_force=True, friction_required=True),
    ModelEntry(
        'hurricane', 'hurricane balls rolling without slipping', ('derived', 'paper'),
        parameters=(
        ('I1', '7/5', '(0, +inf)', 'transverse moment of inertia about C in units of 2 m a^2'),
        ('I3', '2/5', '(0, +inf)', 'axial moment of inertia about C in units of 2 m a^2'),
        ('g', '980', '(0, +inf)', 'g/L in s^-2, L = R (disk, ring) or a (hurricane balls); 980 is g with L = 1 cm'),
        ),
        domain=('0', 'pi/2', 'upright', 'upper_ball_contact'),
        invariants=('energy', 'jellett', 'routh'), inertia_unit='2 m a^2',
        normal_force=True, friction_required=True),
    ModelEntry(
        'sliding-disk', 'thin disk on a frictionless plane', ('derived',),
        parameters=(
        ('k', '1/4', '(0, 0.5]', 'I1/(m R^2) with I3 = 2 I1; 1/4 disk, 1/2 hoop'),
        ('g', '980', '(0, +inf)', 'g/L in s^-2, L = R (disk, ring) or a (hurricane balls); 980 is g with L = 1 cm'),
        ),
        domain=('0', 'pi', 'lies_flat', 'lies_flat'),
        invariants=('energy', 'p_phi', 'p_psi'), inertia_unit='m R^2',
        normal_force=True, friction_required=False),
    ModelEntry(
        'gyroscope', 'hurricane-ball gyroscope about a fixed pivot', ('derived', 'paper'),
        parameters=(
        ('I1', '7/5', '(0, +inf)', 'transverse moment of inertia about C in units of 2 m a^2'),
        ('I3', '2/5', '(0, +inf)', 'axial moment of inertia about C in units of 2 m a^2'),
        ('g', '980', '(0, +inf)', 'g/L in s^-2, L = R (disk, ring) or a (hurricane balls); 980 is g with L = 1 cm'),
        ),
        domain=('0', 'pi', 'upright', 'hanging'),
        invariants=('energy', 'p_phi', 'p_psi'), inertia_unit='2 m a^2',
        normal_force=False, friction_required=False),
    ModelEntry(
        'effective', "hurricane balls, the paper's effective Lagrangian (psi = phi)", ('derived',),
        parameters=(
        ('I1', '7/5', '(0, +inf)', 'transverse moment of inertia about C in units of 2 m a^2'),
        ('I3', '2/5', '(0, +inf)', 'axial moment of inertia about C in units of 2 m a^2'),
        ('g', '980', '(0, +inf)', 'g/L in s^-2, L = R (disk, ring) or a (hurricane balls); 980 is g with L = 1 cm'),
        ),
        domain=('0', 'pi/2', 'upright', 'upper_ball_contact'),
        invariants=('energy', 'p_phi'), inertia_unit='2 m a^2',
        normal_force=False, friction_required=False),
    ModelEntry(
        'disk+moffatt', 'thin disk rolling without slipping, damped by the moffatt couple (n = 3)', ('derived',),
        parameters=(
        ('k', '1/4', '(0, 0.5]', 'I1/(m R^2) with I3 = 2 I1; 1/4 disk, 1/2 hoop; at most 1/2 (all mass on the rim)'),
        ('g', '980', '(0, +inf)', 'g/L in s^-2, L = R (disk, ring) or a (hurricane balls); 980 is g with L = 1 cm'),
        ('c', '9*pi/500000', '[0, +inf)', 'dissipation coefficient of the moffatt couple in s^-1 (c = pi mu a / (2 m); default: air (mu = 1.8e-5 Pa s), a = 1 cm, m = 5 g)'),
        ),
        domain=('0', 'pi', 'lies_flat', 'lies_flat'),
        invariants=('energy',), inertia_unit='m R^2',
        normal_force=True, friction_required=True),
    ModelEntry(
        'disk+contact-rate', 'thin disk rolling without slipping, damped by the contact-rate couple (n = 2)', ('derived',),
        parameters=(
        ('k', '1/4', '(0, 0.5]', 'I1/(m R^2) with I3 = 2 I1; 1/4 disk, 1/2 hoop; at most 1/2 (all mass on the rim)'),
        ('g', '980', '(0, +inf)', 'g/L in s^-2, L = R (disk, ring) or a (hurricane balls); 980 is g with L = 1 cm'),
        ('c', '9*pi/50000', '[0, +inf)', 'dissipation coefficient of the contact-rate couple in s^-1 (P = -c Omega^2 on the steady family; default 10 x the Moffatt default (equal loss at sin(theta) = 1/10))'),
        ),
        domain=('0', 'pi', 'lies_flat', 'lies_flat'),
        invariants=('energy',), inertia_unit='m R^2',
        normal_force=True, friction_required=True),
    ModelEntry(
        'ring+air-drag', 'thick ring or coin rolling on one rim, with air-drag', ('derived',),
        parameters=(
        ('I1', '16720/33489', '(0, +inf)', 'transverse moment of inertia about C in units of m R^2 (default 0.4992684...: the exact annular cylinder R = 3.66 cm, h = 1.59 cm, w = 0.5 cm; the paper prints 0.4993: models.ring.PRINTED)'),
        ('I3', '58453/66978', '(0, +inf)', 'axial moment of inertia about C in units of m R^2 (default 0.8727194...: the exact annular cylinder R = 3.66 cm, h = 1.59 cm, w = 0.5 cm; the paper prints 0.8727: models.ring.PRINTED)'),
        ('h', '53/122', '[0, +inf)', 'half-thickness of the ring in units of R (default 0.4344262...: the exact annular cylinder R = 3.66 cm, h = 1.59 cm, w = 0.5 cm; the paper prints 0.4344: models.ring.PRINTED)'),
        ('g', '980', '(0, +inf)', 'g/L in s^-2, L = R (disk, ring) or a (hurricane balls); 980 is g with L = 1 cm'),
        ('w', '25/183', '(0, 1]', 'wall of the ring in units of R (inner radius R(1 - w)); 1 is a solid disk'),
        ('c', '1/1000', '[0, +inf)', 'coefficient of the air-drag couple (tau = -c A(w) |omega_perp| omega_perp, A(w) = 1 - (1 - w)^5 (quadratic rotational air drag))'),
        ),
        domain=('0', 'pi/2', 'lies_flat', 'rim_switch'),
        invariants=('energy',), inertia_unit='m R^2',
        normal_force=True, friction_required=True),
    ModelEntry(
        'ring+rolling-friction', 'thick ring or coin rolling on one rim, with rolling-friction', ('derived',),
        parameters=(
        ('I1', '16720/33489', '(0, +inf)', 'transverse moment of inertia about C in units of m R^2 (default 0.4992684...: the exact annular cylinder R = 3.66 cm, h = 1.59 cm, w = 0.5 cm; the paper prints 0.4993: models.ring.PRINTED)'),
        ('I3', '58453/66978', '(0, +inf)', 'axial moment of inertia about C in units of m R^2 (default 0.8727194...: the exact annular cylinder R = 3.66 cm, h = 1.59 cm, w = 0.5 cm; the paper prints 0.8727: models.ring.PRINTED)'),
        ('h', '53/122', '[0, +inf)', 'half-thickness of the ring in units of R (default 0.4344262...: the exact annular cylinder R = 3.66 cm, h = 1.59 cm, w = 0.5 cm; the paper prints 0.4344: models.ring.PRINTED)'),
        ('g', '980', '(0, +inf)', 'g/L in s^-2, L = R (disk, ring) or a (hurricane balls); 980 is g with L = 1 cm'),
        ('c', '1/10', '[0, +inf)', 'coefficient of the rolling-friction couple (tau = -c (omega - (omega . Z) Z) (viscous rolling friction, no pivoting friction))'),
        ),
        domain=('0', 'pi/2', 'lies_flat', 'rim_switch'),
        invariants=('energy',), inertia_unit='m R^2',
        normal_force=True, friction_required=True),
)

#: The models by name (``get_model`` builds each from its derivation).
CATALOGUE = {e.name: e for e in ENTRIES}
MODEL_NAMES = ("disk", "ring", "hurricane", "sliding-disk", "gyroscope", "effective")
#: Models with an explicit dissipative term (derived equations only; energy + work is conserved).
DISSIPATIVE_NAMES = ("disk+moffatt", "disk+contact-rate", "ring+air-drag", "ring+rolling-friction")
ALL_NAMES = MODEL_NAMES + DISSIPATIVE_NAMES
#: Bodies that roll or slide with Coulomb friction: a rolling model plus the sliding phase of
#: :mod:`models.coulomb`, run by :mod:`verify.engine.hybrid` (not a single :class:`Model`).
COULOMB_NAMES = ("disk+coulomb", "ring+coulomb")
#: Other names for a model with some parameters set: name -> (model, parameters).
ALIASES = {"hoop": ("disk", {"k": "0.5"})}


def entry(name: str) -> ModelEntry:
    """The catalogue entry of a model name or alias (a Coulomb body: its rolling model's)."""
    name = ALIASES.get(name, (name,))[0]
    if name in COULOMB_NAMES:
        name = name.split("+")[0]
    if name.startswith(BODY_PREFIX):  # a body file's model (models.bodies): its units are the file's scale L
        body = name[len(BODY_PREFIX):].split("+")[0]  # body:NAME@HASH+coulomb: the rolling model's entry
        name = BODY_PREFIX + body
        return ModelEntry(name, f"the body {body.split('@')[0]} (a body file)", ("derived",), parameters=(),
                          domain=(), invariants=(), inertia_unit="M L^2", normal_force=True, friction_required=True)
    return CATALOGUE[name]


#: The name of a body file's model is this prefix and the file's ``name`` (models.bodies).
BODY_PREFIX = "body:"
