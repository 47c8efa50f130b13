"""Planar dyads and four-bar linkages, vectorised over arrays of crank angles.

Conventions (SI units, radians):

* Points are arrays of shape ``(..., 2)``; angles are measured counter-clockwise
  from the global x axis.
* A four-bar has ground pivots O (crank pivot, at the origin) and O' (rocker
  pivot, at ``ground * (cos ground_angle, sin ground_angle)``), crank OA,
  coupler AB and rocker O'B.
* The **assembly branch** is the sign of the cross product
  ``(O' - A) x (B - A)``: ``+1`` puts B on the left of the directed line A->O',
  ``-1`` on its right.  The sign is chosen explicitly by the caller and kept for
  every crank angle.  Away from singular (collinear-dyad) positions the solution
  with a constant sign is the continuous one, so keeping the sign *is* keeping
  continuity; at a singular position both branches meet and the derivatives are
  undefined (returned as NaN and flagged in ``singular``).
* Velocities and accelerations are returned as derivatives with respect to the
  crank angle (``d theta / d alpha`` and ``d^2 theta / d alpha^2``); multiply by
  the crank speed (and its square) for a crank turning at constant speed.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

FloatArray = NDArray[np.float64]

#: Relative tolerance used to decide that a dyad is exactly stretched or folded
#: (discriminant clipped to zero instead of rejected).  Callers may override.
DEFAULT_ASSEMBLY_TOL = 1.0e-9


def _cross(u: FloatArray, v: FloatArray) -> FloatArray:
    return u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]


def _perp(u: FloatArray) -> FloatArray:
    """Rotate vectors by +90 degrees."""
    return np.stack([-u[..., 1], u[..., 0]], axis=-1)


@dataclass(frozen=True)
class DyadSolution:
    """Position of the joint R of an RRR dyad P-R-Q.

    Attributes
    ----------
    point : (..., 2) array, m
        The joint R.
    angle_p, angle_q : arrays, rad
        Directions of the links P->R and Q->R.
    singular : bool array
        True where the dyad is stretched or folded (P, R, Q collinear).
    """

    point: FloatArray
    angle_p: FloatArray
    angle_q: FloatArray
    singular: FloatArray


def dyad_position(
    p: ArrayLike,
    q: ArrayLike,
    length_p: float,
    length_q: float,
    branch: int,
    assembly_tol: float = DEFAULT_ASSEMBLY_TOL,
) -> tuple[DyadSolution, NDArray[np.bool_]]:
    """Close the RRR dyad: find R with |R-P| = length_p and |R-Q| = length_q.

    Parameters
    ----------
    p, q : (..., 2) arrays, m
        The two outer joints.
    length_p, length_q : float, m
        Link lengths from P and from Q to the middle joint R.
    branch : +1 or -1
        Sign of ``(Q - P) x (R - P)``: +1 puts R on the left of P->Q.
    assembly_tol : float
        Relative tolerance on the triangle inequality; a violation smaller than
        this (times the larger length) is treated as exactly stretched/folded.

    Returns
    -------
    solution : DyadSolution
        R and the link directions (NaN where the dyad cannot close).
    failed : bool array
        True where the dyad cannot be assembled.
    """
    if branch not in (1, -1):
        raise ValueError(f"branch must be +1 or -1, got {branch!r}")
    p = np.asarray(p, dtype=float)
    q = np.asarray(q, dtype=float)
    d_vec = q - p
    d = np.hypot(d_vec[..., 0], d_vec[..., 1])
    scale = max(length_p, length_q)
    # distance along P->Q to the foot of R, and the perpendicular offset squared
    with np.errstate(divide="ignore", invalid="ignore"):
        along = (d * d + length_p * length_p - length_q * length_q) / (2.0 * d)
    h2 = length_p * length_p - along * along
    slack = assembly_tol * scale * scale
    failed = ~np.isfinite(along) | (h2 < -slack)
    h = np.sqrt(np.clip(h2, 0.0, None))
    singular = h <= np.sqrt(slack)
    with np.errstate(divide="ignore", invalid="ignore"):
        unit = d_vec / d[..., None]
    r = p + along[..., None] * unit + branch * h[..., None] * _perp(unit)
    r = np.where(failed[..., None], np.nan, r)
    angle_p = np.arctan2(r[..., 1] - p[..., 1], r[..., 0] - p[..., 0])
    angle_q = np.arctan2(r[..., 1] - q[..., 1], r[..., 0] - q[..., 0])
    return DyadSolution(r, angle_p, angle_q, singular), failed


def dyad_rates(
    length_p: float,
    length_q: float,
    angle_p: FloatArray,
    angle_q: FloatArray,
    vel_p: FloatArray,
    vel_q: FloatArray,
    acc_p: FloatArray,
    acc_q: FloatArray,
) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """Angular rates of the two links of an RRR dyad from its end-point motion.

    The loop ``P + l_p e(angle_p) = Q + l_q e(angle_q)`` is differentiated once
    and twice with respect to the driving parameter; the 2x2 systems are solved
    in closed form (Cramer's rule), vectorised.

    Parameters
    ----------
    length_p, length_q : float, m
    angle_p, angle_q : arrays, rad
        Link directions P->R and Q->R.
    vel_p, vel_q, acc_p, acc_q : (..., 2) arrays
        First and second derivatives of P and Q (m per unit parameter).

    Returns
    -------
    omega_p, omega_q, alpha_p, alpha_q : arrays
        First and second derivatives of angle_p and angle_q (rad per unit
        parameter).  NaN where the dyad is singular (sin(angle_q - angle_p) = 0).
    """
    cp, sp = np.cos(angle_p), np.sin(angle_p)
    cq, sq = np.cos(angle_q), np.sin(angle_q)
    # columns: d/d(omega_p) -> l_p e_perp(p), d/d(omega_q) -> -l_q e_perp(q)
    a11, a21 = -length_p * sp, length_p * cp
    a12, a22 = length_q * sq, -length_q * cq
    det = a11 * a22 - a12 * a21  # = l_p l_q sin(angle_q - angle_p)
    with np.errstate(divide="ignore", invalid="ignore"):
        inv_det = np.where(det == 0.0, np.nan, 1.0 / det)
    rhs = vel_q - vel_p
    omega_p = (rhs[..., 0] * a22 - a12 * rhs[..., 1]) * inv_det
    omega_q = (a11 * rhs[..., 1] - a21 * rhs[..., 0]) * inv_det
    # second derivative: same matrix, centripetal terms moved to the right
    rhs2x = acc_q[..., 0] - acc_p[..., 0] + length_p * omega_p**2 * cp - length_q * omega_q**2 * cq
    rhs2y = acc_q[..., 1] - acc_p[..., 1] + length_p * omega_p**2 * sp - length_q * omega_q**2 * sq
    alpha_p = (rhs2x * a22 - a12 * rhs2y) * inv_det
    alpha_q = (a11 * rhs2y - a21 * rhs2x) * inv_det
    return omega_p, omega_q, alpha_p, alpha_q


@dataclass(frozen=True)
class Dyad:
    """An RRR dyad adding joint ``name`` between two already known points.

    ``length_p`` and ``length_q`` are the link lengths (m) from points ``p`` and
    ``q`` to the new joint; ``branch`` is the sign of ``(q - p) x (name - p)``.
    """

    name: str
    p: str
    q: str
    length_p: float
    length_q: float
    branch: int


@dataclass(frozen=True)
class Chain:
    """A single-degree-of-freedom planar linkage built as a crank plus a chain of dyads.

    Attributes
    ----------
    ground : mapping of point name -> (x, y) in m
        Fixed pivots.
    crank_pivot, crank_tip : str
        The crank turns about ``crank_pivot`` (a ground point); its tip is a new point.
    crank_length : float, m
    dyads : tuple of Dyad
        Solved in order; each joins two points known by then.
    assembly_tol : float
        Relative slack on the triangle inequality (see dyad_position).
    """

    ground: dict[str, tuple[float, float]]
    crank_pivot: str
    crank_tip: str
    crank_length: float
    dyads: tuple[Dyad, ...]
    assembly_tol: float = DEFAULT_ASSEMBLY_TOL

    def describe(self) -> str:
        parts = [f"crank {self.crank_pivot}{self.crank_tip}={self.crank_length:g} m"]
        parts += [f"{d.p}{d.name}={d.length_p:g} m, {d.q}{d.name}={d.length_q:g} m" for d in self.dyads]
        return "; ".join(parts)


@dataclass(frozen=True)
class PointMotion:
    """Position (m) and its first and second crank-angle derivatives (m/rad, m/rad^2)."""

    pos: FloatArray
    vel: FloatArray
    acc: FloatArray


@dataclass(frozen=True)
class LinkMotion:
    """Direction of a link (rad) and its first and second crank-angle derivatives."""

    angle: FloatArray
    rate: FloatArray
    accel: FloatArray


@dataclass(frozen=True)
class ChainMotion:
    """Every point and link of a chain over the crank angles.

    Links are keyed ``"P-R"`` for the direction P->R; a dyad adds ``"p-name"``
    and ``"q-name"``, the crank adds ``"pivot-tip"``.  ``singular`` marks crank
    angles at which some dyad is stretched or folded (rates there are NaN).
    """

    crank_angle: FloatArray
    points: dict[str, PointMotion]
    links: dict[str, LinkMotion]
    singular: NDArray[np.bool_]


def solve_chain(chain: Chain, crank_angle: ArrayLike) -> ChainMotion:
    """Positions, rates and accelerations of every point and link of a chain.

    Raises
    ------
    ValueError
        If a dyad cannot be assembled at some crank angle; the message names the
        dyad's lengths, the chain and the first such crank angle (in degrees).
    """
    alpha = np.asarray(crank_angle, dtype=float)
    shape = alpha.shape + (2,)
    zero = np.zeros(shape)
    points: dict[str, PointMotion] = {
        name: PointMotion(np.broadcast_to(np.asarray(xy, dtype=float), shape), zero, zero)
        for name, xy in chain.ground.items()
    }
    e = np.stack([np.cos(alpha), np.sin(alpha)], axis=-1)
    pivot = points[chain.crank_pivot].pos
    tip = pivot + chain.crank_length * e
    points[chain.crank_tip] = PointMotion(tip, chain.crank_length * _perp(e), -chain.crank_length * e)
    ones, zeros = np.ones_like(alpha), np.zeros_like(alpha)
    links = {f"{chain.crank_pivot}-{chain.crank_tip}": LinkMotion(alpha, ones, zeros)}
    singular = np.zeros(alpha.shape, dtype=bool)
    for d in chain.dyads:
        p, q = points[d.p], points[d.q]
        sol, failed = dyad_position(p.pos, q.pos, d.length_p, d.length_q, d.branch, chain.assembly_tol)
        if np.any(failed):
            bad = np.atleast_1d(alpha)[np.atleast_1d(failed)]
            raise ValueError(
                f"dyad {d.p}{d.name}{d.q} cannot be assembled ({d.p}{d.name}={d.length_p:g} m, "
                f"{d.q}{d.name}={d.length_q:g} m; chain: {chain.describe()}) at crank angle "
                f"{np.degrees(bad[0]):.6g} deg ({bad.size} of {np.size(alpha)} angles fail)"
            )
        wp, wq, ap, aq = dyad_rates(d.length_p, d.length_q, sol.angle_p, sol.angle_q, p.vel, q.vel, p.acc, q.acc)
        wp, wq, ap, aq = (np.where(sol.singular, np.nan, x) for x in (wp, wq, ap, aq))
        ep = np.stack([np.cos(sol.angle_p), np.sin(sol.angle_p)], axis=-1)
        vel = p.vel + d.length_p * wp[..., None] * _perp(ep)
        acc = p.acc + d.length_p * (ap[..., None] * _perp(ep) - (wp**2)[..., None] * ep)
        points[d.name] = PointMotion(sol.point, vel, acc)
        links[f"{d.p}-{d.name}"] = LinkMotion(sol.angle_p, wp, ap)
        links[f"{d.q}-{d.name}"] = LinkMotion(sol.angle_q, wq, aq)
        singular = singular | sol.singular
    return ChainMotion(alpha, points, links, singular)


GrashofClass = Literal["grashof", "change-point", "non-grashof"]


@dataclass(frozen=True)
class FourBar:
    """A planar four-bar O-A-B-O' (lengths in m, angles in rad).

    Attributes
    ----------
    crank : float
        OA, the driven link.
    coupler : float
        AB.
    rocker : float
        O'B, the output link.
    ground : float
        OO', the frame.
    branch : +1 or -1
        Assembly branch, see the module docstring.
    ground_angle : float
        Direction of O->O' (rad); 0 puts O' on the positive x axis.
    assembly_tol : float
        Relative tolerance for positions at the edge of assembly.
    """

    crank: float
    coupler: float
    rocker: float
    ground: float
    branch: int = 1
    ground_angle: float = 0.0
    assembly_tol: float = DEFAULT_ASSEMBLY_TOL

    def __post_init__(self) -> None:
        for name in ("crank", "coupler", "rocker", "ground"):
            value = getattr(self, name)
            if not np.isfinite(value) or value <= 0.0:
                raise ValueError(f"four-bar {name} length must be positive and finite, got {value!r}")
        if self.branch not in (1, -1):
            raise ValueError(f"four-bar branch must be +1 or -1, got {self.branch!r}")

    @property
    def lengths(self) -> tuple[float, float, float, float]:
        return (self.crank, self.coupler, self.rocker, self.ground)

    @property
    def rocker_pivot(self) -> FloatArray:
        """O' (m)."""
        return self.ground * np.array([np.cos(self.ground_angle), np.sin(self.ground_angle)])


@dataclass(frozen=True)
class FourBarMotion:
    """Four-bar positions and rates over an array of crank angles.

    All angle derivatives are with respect to the crank angle alpha.
    Angles are in rad, points in m.
    """

    crank_angle: FloatArray
    A: FloatArray
    B: FloatArray
    coupler_angle: FloatArray  #: direction of A->B
    rocker_angle: FloatArray  #: direction of O'->B
    coupler_rate: FloatArray  #: d(coupler_angle)/d(alpha)
    rocker_rate: FloatArray  #: d(rocker_angle)/d(alpha)
    coupler_accel: FloatArray  #: d2(coupler_angle)/d(alpha)2
    rocker_accel: FloatArray  #: d2(rocker_angle)/d(alpha)2
    transmission_angle: FloatArray  #: angle between B->A and B->O', in [0, pi]
    singular: NDArray[np.bool_]  #: coupler and rocker collinear (rates undefined)


def four_bar_chain(linkage: FourBar) -> Chain:
    """The four-bar as a chain: crank O->A, then the dyad A-B-O'."""
    o2 = linkage.rocker_pivot
    return Chain(
        ground={"O": (0.0, 0.0), "O'": (float(o2[0]), float(o2[1]))},
        crank_pivot="O",
        crank_tip="A",
        crank_length=linkage.crank,
        dyads=(Dyad("B", "A", "O'", linkage.coupler, linkage.rocker, linkage.branch),),
        assembly_tol=linkage.assembly_tol,
    )


def four_bar(linkage: FourBar, crank_angle: ArrayLike) -> FourBarMotion:
    """Solve a four-bar over an array of crank angles (rad).

    Raises
    ------
    ValueError
        If the linkage cannot be assembled at some crank angle; the message
        names the lengths and the first such angle (in degrees).
    """
    try:
        m = solve_chain(four_bar_chain(linkage), crank_angle)
    except ValueError as exc:
        l1, l2, l3, l4 = linkage.lengths
        raise ValueError(
            f"four-bar cannot be assembled: crank={l1:g} m, coupler={l2:g} m, rocker={l3:g} m, ground={l4:g} m "
            + str(exc)[str(exc).index("at crank angle") :]
        ) from None
    coupler, rocker = m.links["A-B"], m.links["O'-B"]
    # angle between B->A and B->O' equals the angle between A->B and O'->B
    mu = np.abs(np.angle(np.exp(1j * (rocker.angle - coupler.angle))))
    return FourBarMotion(
        m.crank_angle,
        m.points["A"].pos,
        m.points["B"].pos,
        coupler.angle,
        rocker.angle,
        coupler.rate,
        rocker.rate,
        coupler.accel,
        rocker.accel,
        mu,
        m.singular,
    )


def loop_closure_residual(linkage: FourBar, motion: FourBarMotion) -> FloatArray:
    """|OA + AB - OO' - O'B| at every crank angle (m), from the solved angles."""
    e = lambda t: np.stack([np.cos(t), np.sin(t)], axis=-1)  # noqa: E731
    loop = (
        linkage.crank * e(motion.crank_angle)
        + linkage.coupler * e(motion.coupler_angle)
        - linkage.rocker_pivot
        - linkage.rocker * e(motion.rocker_angle)
    )
    return np.hypot(loop[..., 0], loop[..., 1])


def grashof_class(lengths: tuple[float, float, float, float], rel_tol: float = 1.0e-12) -> GrashofClass:
    """Grashof classification of four link lengths (any order).

    ``s + l < p + q`` is Grashof (some link turns fully), equality within
    ``rel_tol`` (relative to the sum of lengths) is a change-point linkage,
    otherwise non-Grashof (triple rocker).
    """
    s = sorted(float(x) for x in lengths)
    lhs, rhs = s[0] + s[3], s[1] + s[2]
    if abs(lhs - rhs) <= rel_tol * sum(s):
        return "change-point"
    return "grashof" if lhs < rhs else "non-grashof"


#: Four link lengths whose Grashof sums differ by less than this fraction of their total are refused as a change-point
#: linkage (config checks): each turn passes a configuration where two links lie nearly in line and the motion is
#: nearly singular (the stiffness study's pinned share, a clearance run's constraint matrix).
CHANGE_POINT_MARGIN = 1.0e-3


def change_point_distance(lengths: tuple[float, float, float, float]) -> float:
    """|(p + q) - (s + l)| / (s + l + p + q) of four link lengths (any order): 0 for a change-point linkage."""
    s = sorted(float(x) for x in lengths)
    return abs((s[1] + s[2]) - (s[0] + s[3])) / sum(s)


def inversion(linkage: FourBar, rel_tol: float = 1.0e-12) -> str:
    """Name of the Grashof inversion: which link is shortest decides the motion.

    Returns one of ``crank-rocker``, ``double-crank``, ``double-rocker``,
    ``rocker-crank`` (Grashof), ``triple-rocker`` (non-Grashof) or
    ``change-point``.
    """
    cls = grashof_class(linkage.lengths, rel_tol)
    if cls != "grashof":
        return "triple-rocker" if cls == "non-grashof" else "change-point"
    names = ["crank-rocker", "double-rocker", "rocker-crank", "double-crank"]
    return names[int(np.argmin(linkage.lengths))]


@dataclass(frozen=True)
class ToggleSolution:
    """Crank--coupler toggle (dead-centre) positions, where the rocker reverses.

    ``kind`` is ``extended`` (O, A, B collinear with A between O and B) or
    ``folded`` (A beyond B as seen from O); angles in rad; an entry is NaN when
    that toggle does not exist for the linkage.
    """

    kind: tuple[str, str]
    crank_angle: FloatArray
    rocker_angle: FloatArray


def toggle_positions(linkage: FourBar) -> ToggleSolution:
    """Crank angles at which crank and coupler are collinear (rocker dead centres).

    At such a position |OB| = coupler + crank (extended) or coupler - crank
    (folded); B follows from the triangle O, O', B on the linkage's branch.
    """
    l1, l2, l3, _ = linkage.lengths
    o = np.zeros(2)
    o2 = linkage.rocker_pivot
    crank_angles, rocker_angles = [], []
    for kind, reach in (("extended", l2 + l1), ("folded", abs(l2 - l1))):
        found = (np.nan, np.nan)
        for side in (1, -1):
            sol, failed = dyad_position(o, o2, reach, l3, side, linkage.assembly_tol)
            if failed:
                continue
            b_dir = float(sol.angle_p)
            alpha = b_dir if (kind == "extended" or l2 < l1) else b_dir + np.pi
            alpha = float(np.mod(alpha, 2 * np.pi))
            try:
                m = four_bar(linkage, np.array([alpha]))
            except ValueError:
                continue
            if np.allclose(m.B[0], sol.point, atol=1e-9 * max(linkage.lengths)):
                found = (alpha, float(m.rocker_angle[0]))
                break
        crank_angles.append(found[0])
        rocker_angles.append(found[1])
    return ToggleSolution(("extended", "folded"), np.array(crank_angles), np.array(rocker_angles))
