"""Equivalent stiffness of a crank-rocker treated as a frame (energy method).

Paper ``stiffness`` (Huang, Wu, Li 2022).  At each crank angle the linkage
O-A-B-O' is frozen into a rigid-jointed frame of three members (OA, AB, BO').

* **Linear stiffness** K_h = 1 / x_O': a unit horizontal force at O', the frame
  clamped at O (the load path of the paper's Table 1).
* **Rotational stiffness** K_c = 1 / phi_O': a unit moment at O', carried by
  vertical reactions M/l4 at O and O' (the load path of Table 2).

Every member carries a constant axial force N and a bending moment that is
linear along it, M(x) = m0 + m1 x (x from the member's first end).  The unit-load
(Castigliano) displacement is then exact:

    delta = sum_members [ N^2 l / (E A) + (m0^2 l + m0 m1 l^2 + m1^2 l^3 / 3) / (E I) ]

which is how this module computes it: from the internal forces, not from the
paper's printed eqs. (8)/(14).

Three *forms* are offered because the paper is not self-consistent:

``equilibrium``
    Internal forces from statics.  In AB the moment is F (l1 sin a + x sin g)
    and (M/l4)(l1 cos a + x cos g): continuous with OA at A and with BO' at B.
``tables``
    Tables 1-2 as printed: the l1 term in AB carries the opposite relative sign,
    F (l1 sin a - x sin g) and (M/l4)(x cos g - l1 cos a).  The moment is then
    discontinuous at the rigid joint B, which no loading can produce.
``printed``
    Eqs. (8) and (14) letter for letter.  Eq. (8) is Table 1 integrated
    correctly; eq. (14) additionally writes E2 I2 instead of E3 I3 in its
    l3^3 cos^2 b term.

Angles follow the paper: alpha is the crank direction, gamma the direction of
A->B, beta = pi - (direction of O'->B).  All quantities SI, angles in rad.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ...engines.kinematics import FourBar, four_bar

FloatArray = NDArray[np.float64]
Form = Literal["equilibrium", "tables", "printed"]
FORMS: tuple[Form, ...] = ("equilibrium", "tables", "printed")
MEMBERS = ("OA", "AB", "BO")  # BO stands for the rocker BO' (config keys use the same names)


@dataclass(frozen=True)
class Section:
    """Cross-section and material of one member.

    Attributes
    ----------
    youngs_modulus : float, Pa
    area : float, m^2
    second_moment : float, m^4 (about the bending axis)
    """

    youngs_modulus: float
    area: float
    second_moment: float

    def __post_init__(self) -> None:
        for name in ("youngs_modulus", "area", "second_moment"):
            value = getattr(self, name)
            if not np.isfinite(value) or value <= 0.0:
                raise ValueError(f"section {name} must be positive and finite, got {value!r}")


@dataclass(frozen=True)
class MemberForces:
    """Unit-load internal forces of one member: N, and M(x) = m0 + m1 x.

    Units per unit applied load: N in N/N (force case) or N/(N m) (moment case);
    m0 in m (force case) or 1 (moment case); m1 in 1 or 1/m.
    """

    axial: FloatArray
    m0: FloatArray
    m1: FloatArray


def paper_angles(linkage: FourBar, crank_angle: ArrayLike) -> tuple[FloatArray, FloatArray, FloatArray]:
    """(alpha, beta, gamma) of the paper, rad, from the four-bar solution.

    beta is wrapped to [0, 2 pi) and gamma to (-pi, pi].
    """
    motion = four_bar(linkage, crank_angle)
    beta = np.mod(np.pi - motion.rocker_angle, 2.0 * np.pi)
    return motion.crank_angle, beta, motion.coupler_angle


def _ab_sign(form: Form) -> float:
    if form == "equilibrium":
        return 1.0
    if form in ("tables", "printed"):
        return -1.0
    raise ValueError(f"unknown stiffness form {form!r}; expected one of {FORMS}")


def unit_force_internal_forces(
    crank: float, alpha: FloatArray, beta: FloatArray, gamma: FloatArray, form: Form = "equilibrium"
) -> tuple[MemberForces, MemberForces, MemberForces]:
    """Members' internal forces for a unit horizontal force at O' (paper's Table 1).

    x runs O->A on OA, A->B on AB and O'->B on BO'.
    """
    s = _ab_sign(form)
    zero = np.zeros_like(alpha)
    oa = MemberForces(np.cos(alpha), zero, np.sin(alpha))
    ab = MemberForces(np.cos(gamma), crank * np.sin(alpha), s * np.sin(gamma))
    bo = MemberForces(np.cos(beta), zero, np.sin(beta))
    return oa, ab, bo


def unit_moment_internal_forces(
    crank: float, ground: float, alpha: FloatArray, beta: FloatArray, gamma: FloatArray, form: Form = "equilibrium"
) -> tuple[MemberForces, MemberForces, MemberForces]:
    """Members' internal forces for a unit moment at O' (paper's Table 2)."""
    s = _ab_sign(form)
    v = 1.0 / ground  # vertical reactions at O and O' (N per N m)
    zero = np.zeros_like(alpha)
    oa = MemberForces(v * np.sin(alpha), zero, v * np.cos(alpha))
    ab = MemberForces(v * np.sin(gamma), s * v * crank * np.cos(alpha), v * np.cos(gamma))
    bo = MemberForces(v * np.sin(beta), -np.ones_like(alpha), v * np.cos(beta))
    return oa, ab, bo


def compliance_parts(
    lengths: tuple[float, float, float], sections: tuple[Section, Section, Section], forces: tuple[MemberForces, ...]
) -> tuple[FloatArray, FloatArray]:
    """(axial, bending) parts of the unit-load displacement.

    Exact integrals of N^2/(EA) and M^2/(EI) along each member with
    M(x) = m0 + m1 x, summed over members (m per N for a force, rad per N m
    for a moment).
    """
    axial, bending = 0.0, 0.0
    for length, sec, f in zip(lengths, sections, forces, strict=True):
        axial = axial + f.axial**2 * length / (sec.youngs_modulus * sec.area)
        bending = bending + (f.m0**2 * length + f.m0 * f.m1 * length**2 + f.m1**2 * length**3 / 3.0) / (
            sec.youngs_modulus * sec.second_moment
        )
    return np.asarray(axial, dtype=float), np.asarray(bending, dtype=float)


def axial_share(
    lengths: tuple[float, float, float], sections: tuple[Section, Section, Section], forces: tuple[MemberForces, ...]
) -> FloatArray:
    """Axial part of the unit-load displacement as a fraction of the whole (1)."""
    axial, bending = compliance_parts(lengths, sections, forces)
    return axial / (axial + bending)


def moment_jump_at_b(coupler: float, rocker: float, forces: tuple[MemberForces, ...]) -> FloatArray:
    """| |M_AB(B)| - |M_BO'(B)| |: the jump of the bending moment's magnitude at the rigid joint B.

    No external moment acts at B, so a frame in equilibrium has none (per unit load: N m per N for
    the force case, N m per N m for the moment case).  x runs A->B on AB and O'->B on BO'.
    """
    _, ab, bo = forces
    return np.abs(np.abs(ab.m0 + ab.m1 * coupler) - np.abs(bo.m0 + bo.m1 * rocker))


def unit_load_displacement(
    lengths: tuple[float, float, float], sections: tuple[Section, Section, Section], forces: tuple[MemberForces, ...]
) -> FloatArray:
    """Displacement under a unit load: axial plus bending compliance."""
    axial, bending = compliance_parts(lengths, sections, forces)
    return axial + bending


def printed_eq8(
    l1: float, l2: float, l3: float, sections: tuple[Section, Section, Section], alpha, beta, gamma
) -> FloatArray:
    """x_O' of the paper's eq. (8) exactly as printed, for F = 1 N (m)."""
    (e1, a1, i1), (e2, a2, i2), (e3, a3, i3) = ((s.youngs_modulus, s.area, s.second_moment) for s in sections)
    sa, sb, sg = np.sin(alpha), np.sin(beta), np.sin(gamma)
    ca, cb, cg = np.cos(alpha), np.cos(beta), np.cos(gamma)
    return (
        l1 * ca**2 / (e1 * a1)
        + l2 * cg**2 / (e2 * a2)
        + l3 * cb**2 / (e3 * a3)
        + l1**3 * sa**2 / (3 * e1 * i1)
        + l1**2 * l2 * sa**2 / (e2 * i2)
        - l1 * l2**2 * sa * sg / (e2 * i2)
        + l2**3 * sg**2 / (3 * e2 * i2)
        + l3**3 * sb**2 / (3 * e3 * i3)
    )


def printed_eq14(
    l1: float, l2: float, l3: float, l4: float, sections: tuple[Section, Section, Section], alpha, beta, gamma
) -> FloatArray:
    """phi_O' of the paper's eq. (14) exactly as printed, for M = 1 N m (rad).

    Note the printed E2 I2 in the l3^3 cos^2(beta) term.
    """
    (e1, a1, i1), (e2, a2, i2), (e3, a3, i3) = ((s.youngs_modulus, s.area, s.second_moment) for s in sections)
    sa, sb, sg = np.sin(alpha), np.sin(beta), np.sin(gamma)
    ca, cb, cg = np.cos(alpha), np.cos(beta), np.cos(gamma)
    return (
        l1 * sa**2 / (e1 * a1 * l4**2)
        + l2 * sg**2 / (e2 * a2 * l4**2)
        + l3 * sb**2 / (e3 * a3 * l4**2)
        + l1**3 * ca**2 / (3 * l4**2 * e1 * i1)
        + l2**3 * cg**2 / (3 * l4**2 * e2 * i2)
        - l1 * l2**2 * ca * cg / (l4**2 * e2 * i2)
        + l1**2 * l2 * ca**2 / (l4**2 * e2 * i2)
        + l3**3 * cb**2 / (3 * l4**2 * e2 * i2)
        - l3**2 * cb / (l4 * e3 * i3)
        + l3 / (e3 * i3)
    )


@dataclass(frozen=True)
class StiffnessCurves:
    """Equivalent stiffness over crank angle.

    alpha, beta, gamma in rad; linear (K_h) in N/m; rotational (K_c) in N m/rad.
    """

    alpha: FloatArray
    beta: FloatArray
    gamma: FloatArray
    linear: FloatArray
    rotational: FloatArray


def equivalent_stiffness(
    linkage: FourBar,
    sections: tuple[Section, Section, Section],
    crank_angle: ArrayLike,
    form: Form = "equilibrium",
) -> StiffnessCurves:
    """K_h and K_c of the frozen linkage at each crank angle (rad)."""
    alpha, beta, gamma = paper_angles(linkage, crank_angle)
    l1, l2, l3, l4 = linkage.lengths
    if form == "printed":
        x = printed_eq8(l1, l2, l3, sections, alpha, beta, gamma)
        phi = printed_eq14(l1, l2, l3, l4, sections, alpha, beta, gamma)
    else:
        members = (l1, l2, l3)
        x = unit_load_displacement(members, sections, unit_force_internal_forces(l1, alpha, beta, gamma, form))
        phi = unit_load_displacement(
            members, sections, unit_moment_internal_forces(l1, l4, alpha, beta, gamma, form)
        )
    return StiffnessCurves(alpha, beta, gamma, 1.0 / x, 1.0 / phi)


def trapezoid_displacement(
    lengths: tuple[float, float, float],
    sections: tuple[Section, Section, Section],
    forces: tuple[MemberForces, ...],
    panels: int,
) -> FloatArray:
    """The unit-load displacement by the composite trapezoid rule with ``panels`` panels per member.

    The quadrature route to ``unit_load_displacement``: its error falls as panels^-2.
    """
    total = 0.0
    for length, sec, f in zip(lengths, sections, forces, strict=True):
        x = np.linspace(0.0, length, panels + 1)
        m = np.asarray(f.m0)[..., None] + np.asarray(f.m1)[..., None] * x
        density = np.asarray(f.axial)[..., None] ** 2 / (sec.youngs_modulus * sec.area) + m**2 / (
            sec.youngs_modulus * sec.second_moment
        )
        total = total + np.trapezoid(density, x, axis=-1)
    return np.asarray(total, dtype=float)


# --- the real, pinned mechanism --------------------------------------------------------------------------
#: Parts of the pinned output's compliance, in the order ``pinned_output_compliance`` returns them.
PINNED_PARTS = ("coupler axial", "crank axial", "crank bending", "rocker axial", "rocker bending")


def _cross(u: FloatArray, v: FloatArray) -> FloatArray:
    return u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]


def pinned_output_compliance(
    linkage: FourBar, sections: tuple[Section, Section, Section], crank_angle: ArrayLike
) -> FloatArray:
    """Rotation of the rocker at O' per unit torque on it, for the pinned mechanism with the crank held, by part.

    The real linkage: the crank clamped at O (held by the drive), pins at A and B, the rocker pivoted on the
    frame at O'.  A torque T on the rocker is resisted by the coupler, a two-force member: its axial force is
    N = T / c with c = (B - O') x e_AB the lever of the line AB about O'.  N loads the crank's tip at A (axial
    and transverse components: a cantilever), and the rocker carries N's component along it and a bending
    moment falling linearly from T at O' to zero at the pin B.  Unit-load (Castigliano) compliance, exact:

        phi / T = [ l2/(E2 A2) + l1 (e_AB.e_OA)^2/(E1 A1) + l1^3 (e_OA x e_AB)^2/(3 E1 I1)
                    + l3 (e_AB.e_O'B)^2/(E3 A3) ] / c^2  +  l3 / (3 E3 I3)

    Returns an array (..., 5) in rad per N m, parts in the order of ``PINNED_PARTS``.
    """
    motion = four_bar(linkage, crank_angle)
    l1, l2, l3, _ = linkage.lengths
    a, b = np.asarray(motion.A, dtype=float), np.asarray(motion.B, dtype=float)
    pivot = np.asarray(linkage.rocker_pivot, dtype=float)
    e_oa = a / l1
    e_ab = (b - a) / l2
    e_rb = (b - pivot) / l3
    lever = l3 * _cross(e_rb, e_ab)  # c, m
    (crank, coupler, rocker) = sections
    parts = np.stack(
        [
            l2 / (coupler.youngs_modulus * coupler.area) / lever**2,
            l1 * np.sum(e_ab * e_oa, axis=-1) ** 2 / (crank.youngs_modulus * crank.area) / lever**2,
            l1**3 * _cross(e_oa, e_ab) ** 2 / (3.0 * crank.youngs_modulus * crank.second_moment) / lever**2,
            l3 * np.sum(e_ab * e_rb, axis=-1) ** 2 / (rocker.youngs_modulus * rocker.area) / lever**2,
            np.full_like(lever, l3 / (3.0 * rocker.youngs_modulus * rocker.second_moment)),
        ],
        axis=-1,
    )
    return parts


def pinned_output_stiffness(
    linkage: FourBar, sections: tuple[Section, Section, Section], crank_angle: ArrayLike
) -> FloatArray:
    """Rotational stiffness of the rocker at O' with the crank held, pinned mechanism (N m/rad)."""
    return 1.0 / pinned_output_compliance(linkage, sections, crank_angle).sum(axis=-1)


def planar_mobility(bodies: int, pins: int) -> int:
    """Grübler-Kutzbach mobility of a planar chain: 3 (bodies - 1) - 2 pins (the frame counts as a body).

    A body welded to the frame (the crank held by the drive) is part of the frame.
    """
    if bodies < 1 or pins < 0:
        raise ValueError(
            f"a chain needs at least the frame and no negative pin count, got {bodies} bodies, {pins} pins"
        )
    return 3 * (bodies - 1) - 2 * pins


#: The mechanisms whose mobility the report states: (description, bodies with the frame, pins).
MOBILITY_CASES = {
    "crank held, pins at A and B, O' free (a pinned K_h)": (3, 2),
    "crank held, pins at A and B, O' pivoted on the frame (the pinned output stiffness)": (3, 3),
    "running: crank on its pivot O, pins at A, B and O'": (4, 4),
}
