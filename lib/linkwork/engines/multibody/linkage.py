"""A planar linkage as data: bodies, ground points, revolute joints (ideal or with a clearance), a driver.

This is the description the multibody engine assembles a scene from (``model.generate_source`` writes its
right-hand side from the topology; ``assembly`` finds its configurations).  Everything inside is SI and radians;
``from_config`` reads the config form (degrees for angles, named keys with units) and names the key of any
problem (``LinkageError``).

Conventions:
* a body's frame has its origin at the centre of mass; its named points are given in that frame (m), and its
  angle is the rotation of that frame (rad);
* a joint joins a point of its first body (the journal's side) to a point of its second (the bearing's side, or
  ``ground``); an ideal joint is two constraint rows, a clearance joint a force element between journal and bearing;
* the driver turns a grounded body: theta(t) = theta0 + omega t + sum_k (a_k cos(k omega t) + b_k sin(k omega t)), or
  rocks it (``rocking``): the same without the mean turning omega t (a cam-driven lever);
* a spring pulls a body point towards a fixed rest point, with stiffness and damping per axis (a warp, a guide).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

from ...units import STANDARD_GRAVITY

GROUND = "ground"
#: Physical effects a clearance joint can name (gravity is the linkage's, not a joint's).
JOINT_EFFECTS = ("contact", "friction", "lubrication")
#: Hysteresis damping laws of the dry contact, by the code the compiled kernel reads (kernels.hertz_damping_factor).
CONTACT_LAWS = {"lankarani-nikravesh": 0, "hunt-crossley": 1, "flores": 2}
#: Elastic (force-penetration) laws of the dry contact: eq. (9)'s sphere law, or the conformal cylinder law of
#: Pereira, Ramalho and Ambrosio (2011); data in the packed parameters, not code.
ELASTIC_LAWS = {"hertz-sphere": 0, "pereira": 1}


class LinkageError(ValueError):
    """A linkage description that cannot be assembled or simulated; ``key`` is the config key at fault."""

    def __init__(self, key: str, message: str):
        super().__init__(f"{key}: {message}")
        self.key = key


# --- the conformal cylindrical law of Pereira, Ramalho and Ambrosio (2011) ---------------------------
# C. M. Pereira, A. L. Ramalho, J. A. Ambrosio, "A critical overview of internal and external cylinder contact
# force models", Nonlinear Dynamics 63 (2011) 681-697: for a journal in a bushing (internal contact) of radial
# clearance dR and length L, F = (a dR + b) L E* / dR * delta^n with n = Y dR^-0.005, a and b and Y fitted to
# finite-element results, everything in mm, N and N/mm^2 (MPa).  Coefficients as implemented in the public
# DyS code (github.com/ladisk/DyS @ 5e6a54d, MBD_system/contact_model/contact_model_cylinder.py); the two branches
# of Y meet at the break clearance only with dR in mm in both (our check, tests/test_contact_laws.py).
PEREIRA_A = 0.965  # -, internal contact
PEREIRA_B = 0.0965  # mm, internal contact
PEREIRA_Y_BREAK_MM = 0.34954  # mm: Y's logarithmic branch below, linear branch above
PEREIRA_CLEARANCE_RANGE_M = (0.005e-3, 10.0e-3)  # radial clearances over which Y is given (the fit's range), m
_MM_PER_M = 1e3
_MPA_PER_PA = 1e-6


def _unknown_elastic_law(law: str) -> ValueError:
    return ValueError(f"unknown elastic law {law!r}; known: {sorted(ELASTIC_LAWS)}")


#: Pereira's exponent is undefined at or below this radial clearance (m): ln(1000 dR) <= 0 with dR in mm.
PEREIRA_MIN_CLEARANCE = 1e-6


def pereira_exponent(clearance: float) -> float:
    """Pereira's exponent n = Y dR^-0.005 (-) of the radial clearance ``clearance`` (m; dR in mm in the fit).

    Y = 1.51 [ln(1000 dR)]^-0.151 up to the break clearance (the logarithm of dR in micrometres), Y = 0.0151 dR + 1.151
    above it.  Outside the fitted range the nearer branch is extrapolated (the clearance paper states each law's range);
    below
    1 um the logarithm is not positive and the law is undefined (ValueError).
    """
    dr = clearance * _MM_PER_M
    if clearance <= PEREIRA_MIN_CLEARANCE:
        raise ValueError(f"Pereira's exponent is undefined at a radial clearance of {clearance:g} m (ln(1000 dR) <= 0)")
    y = 1.51 * np.log(1000.0 * dr) ** -0.151 if dr <= PEREIRA_Y_BREAK_MM else 0.0151 * dr + 1.151
    return float(y * dr**-0.005)


def pereira_stiffness(clearance: float, length: float, effective_modulus: float) -> float:
    """K of Pereira's internal-contact law F = K delta^n in SI, N/m^n.

    clearance: radial clearance dR (m); length: joint length L (m); effective_modulus: E* (Pa).  The fit gives
    (a dR + b) L E* / dR in N/mm^n with dR, L in mm and E* in N/mm^2; delta in m is 1000 delta in mm, so
    K_SI = K_mm * 1000^n.
    """
    dr, n = clearance * _MM_PER_M, pereira_exponent(clearance)
    k_mm = (PEREIRA_A * dr + PEREIRA_B) * (length * _MM_PER_M) * (effective_modulus * _MPA_PER_PA) / dr
    return float(k_mm * _MM_PER_M**n)


_NAN = float("nan")


@dataclass(frozen=True)
class Clearance:
    """A revolute joint's clearance and the physical effects that act in it (SI).  A value only a left-out effect
    would read is NaN and never read (the generated right-hand side holds no code for it)."""

    journal_radius: float
    bearing_radius: float
    effects: tuple[str, ...]
    youngs_modulus: tuple[float, float] = (_NAN, _NAN)  # journal, bearing
    poisson: tuple[float, float] = (_NAN, _NAN)
    restitution: float = _NAN
    contact_law: str = "lankarani-nikravesh"
    elastic_law: str = "hertz-sphere"
    friction: float = _NAN
    v0: float = _NAN  # m/s: no friction below this slip (Ambrosio's modified Coulomb)
    v1: float = _NAN  # m/s: full Coulomb above this slip
    viscosity: float = _NAN  # Pa s
    length: float = _NAN  # m, the bearing's length (lubrication; Pereira's law)
    e0: float = _NAN  # m: film/dry transition tolerance on the eccentricity
    impact_velocity_floor: float = _NAN  # m/s
    #: m/s: the damping's impact velocity is the latched one clamped to [floor, ceiling]; floor = ceiling makes the
    #: damping memory-free (the same at every impact), infinite keeps the latched velocity (Lankarani-Nikravesh's law)
    impact_velocity_ceiling: float = float("inf")

    @property
    def clearance(self) -> float:
        """Radial clearance c = R_bearing - R_journal, m."""
        return self.bearing_radius - self.journal_radius

    @property
    def effective_modulus(self) -> float:
        """E* = 1 / sum((1 - nu^2) / E) of the journal and bearing materials, Pa."""
        return 1.0 / sum((1 - nu**2) / e for nu, e in zip(self.poisson, self.youngs_modulus, strict=True))

    @property
    def hertz_stiffness(self) -> float:
        """K of eq. (9): 4 / (3 (sigma_i + sigma_j)) sqrt(R_i R_j / |R_j - R_i|), N/m^1.5."""
        sig = sum((1 - nu**2) / e for nu, e in zip(self.poisson, self.youngs_modulus, strict=True))
        return 4.0 / (3.0 * sig) * np.sqrt(self.journal_radius * self.bearing_radius / self.clearance)

    @property
    def elastic_exponent(self) -> float:
        """Exponent n (-) of the elastic law F = K delta^n: 1.5 for the sphere law, Pereira's n(c) for the conformal."""
        if self.elastic_law == "hertz-sphere":
            return 1.5
        if self.elastic_law == "pereira":
            return pereira_exponent(self.clearance)
        raise _unknown_elastic_law(self.elastic_law)

    @property
    def elastic_stiffness(self) -> float:
        """K of the elastic law F = K delta^n, N/m^n: eq. (9)'s K, or Pereira's K(c, L, E*)."""
        if self.elastic_law == "hertz-sphere":
            return self.hertz_stiffness
        if self.elastic_law == "pereira":
            return pereira_stiffness(self.clearance, self.length, self.effective_modulus)
        raise _unknown_elastic_law(self.elastic_law)

    @property
    def film_coefficient(self) -> float:
        """12 pi mu L R^3 / c^2 (N s): the long-bearing film force scale per unit eccentricity-ratio rate."""
        return 12 * np.pi * self.viscosity * self.length * self.journal_radius**3 / self.clearance**2


@dataclass(frozen=True)
class Body:
    """A rigid body: mass (kg), inertia about the centre of mass (kg m^2), named points in its frame (m), and the
    angle (rad) its assembly starts from (it picks the branch)."""

    name: str
    mass: float
    inertia: float
    points: Mapping[str, tuple[float, float]]
    angle_guess: float = 0.0


@dataclass(frozen=True)
class Joint:
    """A revolute joint between ``journal`` and ``bearing``, each (body, point); the body may be ``ground``."""

    name: str
    journal: tuple[str, str]
    bearing: tuple[str, str]
    clearance: Clearance | None = None


@dataclass(frozen=True)
class Driver:
    """The driven body's angle theta0 + omega t + sum_k (cos[k-1] cos(k omega t) + sin[k-1] sin(k omega t)), rad."""

    body: str
    speed: float  # rad/s, the mean speed omega (negative: the body turns towards decreasing angles)
    start_angle: float  # rad, theta0
    cos: tuple[float, ...] = ()
    sin: tuple[float, ...] = ()
    rocking: bool = False  # True: no mean turning; omega is the frequency of the series only

    @property
    def period(self) -> float:
        """Duration of one driven turn (or one rocking cycle), s (the speed's sign is the sense of turning)."""
        return 2 * np.pi / abs(self.speed)

    @property
    def drift(self) -> float:
        """The mean turning speed, rad/s: omega, or 0 for a rocking driver."""
        return 0.0 if self.rocking else self.speed

    def angle(self, t):
        """theta(t), rad, and its first and second time derivatives (rad/s, rad/s^2), at the times t (s)."""
        t = np.asarray(t, dtype=float)
        w = self.speed
        th, thd, thdd = self.start_angle + self.drift * t, np.full_like(t, self.drift), np.zeros_like(t)
        for k, (a, b) in enumerate(zip(self.cos, self.sin, strict=True), start=1):
            c, s = np.cos(k * w * t), np.sin(k * w * t)
            th = th + a * c + b * s
            thd = thd + k * w * (b * c - a * s)
            thdd = thdd - (k * w) ** 2 * (a * c + b * s)
        return th, thd, thdd


@dataclass(frozen=True)
class Spring:
    """A linear spring-damper pulling the point ``point`` (body, point) towards the fixed ``rest`` (m), per axis:
    F = -(k_x dx, k_y dy) - (c_x v_x, c_y v_y) with (dx, dy) the point's displacement from rest (m) and (v_x, v_y)
    its velocity (m/s); stiffness in N/m, damping in N s/m (a zero leaves that axis free)."""

    name: str
    point: tuple[str, str]
    rest: tuple[float, float]
    stiffness: tuple[float, float]
    damping: tuple[float, float] = (0.0, 0.0)


@dataclass(frozen=True)
class Linkage:
    """A planar linkage: bodies, ground points (m), joints, one driver, gravity (m/s^2, along -y, acting when the
    scene names it), the body whose angular acceleration is reported (``output``) and the Baumgarte constants
    (1/s) that stabilise its closed loops."""

    bodies: tuple[Body, ...]
    ground: Mapping[str, tuple[float, float]]
    joints: tuple[Joint, ...]
    driver: Driver
    output: str
    gravity: float = STANDARD_GRAVITY
    baumgarte: float = 250.0
    names: Mapping[str, str] = field(default_factory=dict)  # config key of each part, for messages
    springs: tuple[Spring, ...] = ()

    def body_index(self, name: str) -> int:
        """Index of a body (-1 for the ground)."""
        if name == GROUND:
            return -1
        return [b.name for b in self.bodies].index(name)

    def point(self, ref: tuple[str, str]) -> tuple[float, float]:
        """Coordinates (m) of a (body, point) reference: in the body's frame, or fixed for the ground."""
        body, name = ref
        if body == GROUND:
            return tuple(self.ground[name])
        return tuple(self.bodies[self.body_index(body)].points[name])

    @property
    def clearance_joints(self) -> tuple[Joint, ...]:
        return tuple(j for j in self.joints if j.clearance is not None)

    @property
    def ideal_joints(self) -> tuple[Joint, ...]:
        return tuple(j for j in self.joints if j.clearance is None)

    @property
    def n_coordinates(self) -> int:
        return 3 * len(self.bodies)

    def constraint_order(self) -> tuple[Joint | Driver, ...]:
        """The constraint rows' order: the driven body's ground joint, the driver, the other ground joints, then the
        joints between bodies (each group in the description's order).  Each joint is two rows, the driver one."""
        ideal = self.ideal_joints
        grounded = [j for j in ideal if GROUND in (j.journal[0], j.bearing[0])]
        first = [j for j in grounded if self.driver.body in (j.journal[0], j.bearing[0])]
        rest = [j for j in grounded if j not in first]
        return (*first, self.driver, *rest, *[j for j in ideal if j not in grounded])

    def with_clearance(self, updates: Mapping[str, Clearance | None]) -> Linkage:
        """The same linkage with the named joints' clearances replaced (None: the joint made ideal)."""
        joints = tuple(Joint(j.name, j.journal, j.bearing, updates.get(j.name, j.clearance)) for j in self.joints)
        return Linkage(
            self.bodies, self.ground, joints, self.driver, self.output, self.gravity, self.baumgarte, self.names,
            self.springs,
        )


def oriented(joint: Joint) -> tuple[tuple[str, str], tuple[str, str]]:
    """(first, second) of an ideal joint with the ground, if any, second (the row is first minus second)."""
    if joint.journal[0] == GROUND:
        return joint.bearing, joint.journal
    return joint.journal, joint.bearing
