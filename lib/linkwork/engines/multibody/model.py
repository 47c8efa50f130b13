"""A four-bar with clearance joints as a planar multibody system, assembled from the scene's effects.

Formulation (the paper's eqs. 1-3): bodies crank (0), coupler (1), rocker (2) in (x, y, phi) at
their centres of mass; ideal revolutes and the constant-speed crank driver are constraints,
M q'' = g - Phi_q^T lambda, Phi_q q'' = gamma - 2 alpha Phi' - beta^2 Phi (Baumgarte).  M is
diagonal, so lambda comes from the small Schur complement Phi_q M^-1 Phi_q^T.  The crank torque
is -lambda of the driver row.

A clearance joint is not a constraint but a force element between a journal (on the first body)
and a bearing (on the second).  The scene names its effects; the right-hand side is generated
as source code containing exactly those effects (no branch, no call for an effect left out),
compiled by numba and cached on disk by the hash of its source.  Each effect increments its own
evaluation counter, so a test can prove that an effect left out is never evaluated.

The dry contact's elastic law (ELASTIC_LAWS: the sphere law of eq. 9, or a conformal cylindrical law)
is chosen apart from its hysteresis damping (CONTACT_LAWS); it is data in the packed parameters, not
generated code, so one compiled scene serves every elastic law.

Sign conventions resolved here (the printed model differs):
* eccentricity e = journal centre - bearing centre, n = e/|e|; the dry contact force on the
  journal is -F_N n, i.e. it pushes the journal back into the bearing (eqs. 4/17 as printed push
  it outward);
* the wedge term uses omega_journal + omega_bearing - 2 gamma' in the fixed frame (eq. 22 speaks of
  "the relative angular velocity", but both elements rotate);
* the film force is capped at the eccentricity ratio eps_limit = 1 - e0/c: continuous and bounded
  up to and past eps = 1, where the dry contact takes over (eq. 23 as printed is infinite at e = c).
"""

from __future__ import annotations

import hashlib
import importlib.util
import os
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ...units import STANDARD_GRAVITY
from ..kinematics import FourBar, four_bar, toggle_positions

CONTACT_LAWS = {"lankarani-nikravesh": 0, "hunt-crossley": 1, "flores": 2}
#: Elastic (force-penetration) laws of the dry contact, orthogonal to the hysteresis damping of CONTACT_LAWS:
#: the sphere law of eq. (9) and the conformal cylindrical law of Pereira, Ramalho and Ambrosio (2011).
ELASTIC_LAWS = {"hertz-sphere": 0, "pereira": 1}
EFFECTS = ("contact", "friction", "lubrication", "gravity")
N_STATE = 19  # q (9), q' (9), driver work (1)
DIAG_FIXED = 4  # rocker angular acceleration, crank torque, energy, constraint drift
DIAG_PER_JOINT = 6  # e, delta, delta', dry normal force, film radial force, film tangential force


@dataclass(frozen=True)
class FourBarParameters:
    """Physical data of the four-bar with clearance joints (SI)."""

    ground: float
    lengths: tuple[float, float, float]  # crank, coupler, rocker
    masses: tuple[float, float, float]
    inertias: tuple[float, float, float]  # about the centres of mass (kg m^2)
    crank_speed: float  # rad/s
    journal_radius: float
    bearing_radius: float
    youngs_modulus: tuple[float, float]  # journal, bearing
    poisson: tuple[float, float]
    joint_length: float  # L of the bearing (lubrication)
    restitution: float
    friction: float
    v0: float
    v1: float
    viscosity: float  # Pa s
    e0: float  # film/dry transition tolerance on the eccentricity, m
    impact_velocity_floor: float  # m/s
    baumgarte_alpha: float
    baumgarte_beta: float
    gravity: float = STANDARD_GRAVITY
    contact_law: str = "lankarani-nikravesh"
    branch: int = 1
    elastic_law: str = "hertz-sphere"  # a key of ELASTIC_LAWS; "pereira" reads joint_length

    @property
    def clearance(self) -> float:
        return self.bearing_radius - self.journal_radius

    @property
    def hertz_stiffness(self) -> float:
        """K of eq. (9): 4 / (3 (sigma_i + sigma_j)) sqrt(R_i R_j / |R_j - R_i|), N/m^1.5."""
        sig = sum((1 - nu**2) / e for nu, e in zip(self.poisson, self.youngs_modulus, strict=True))
        return 4.0 / (3.0 * sig) * np.sqrt(self.journal_radius * self.bearing_radius / self.clearance)

    @property
    def effective_modulus(self) -> float:
        """E* = 1 / sum((1 - nu^2) / E) of the journal and bearing materials, Pa."""
        return 1.0 / sum((1 - nu**2) / e for nu, e in zip(self.poisson, self.youngs_modulus, strict=True))

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
            return pereira_stiffness(self.clearance, self.joint_length, self.effective_modulus)
        raise _unknown_elastic_law(self.elastic_law)

    @property
    def film_coefficient(self) -> float:
        """12 pi mu L R^3 / c^2 (N s/m per unit eccentricity-ratio rate... times 1/s)."""
        return 12 * np.pi * self.viscosity * self.joint_length * self.journal_radius**3 / self.clearance**2

    def linkage(self) -> FourBar:
        l2, l3, l4 = self.lengths
        return FourBar(crank=l2, coupler=l3, rocker=l4, ground=self.ground, branch=self.branch)


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


def pereira_exponent(clearance: float) -> float:
    """Pereira's exponent n = Y dR^-0.005 (-) of the radial clearance ``clearance`` (m; dR in mm in the fit).

    Y = 1.51 [ln(1000 dR)]^-0.151 up to the break clearance (the logarithm of dR in micrometres), Y = 0.0151 dR + 1.151
    above it.  Outside the fitted range the nearer branch is extrapolated (the clearance paper states each law's range); below
    1 um the logarithm is not positive and the law is undefined (ValueError).
    """
    dr = clearance * _MM_PER_M
    if dr <= 1e-3:
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


# joint geometry: (journal body, journal point, bearing body, bearing point) as functions of the lengths
def joint_points(lengths):
    l2, l3, l4 = lengths
    return {
        1: (0, (l2 / 2, 0.0), 1, (-l3 / 2, 0.0)),  # crank pin A in the coupler's bushing
        2: (1, (l3 / 2, 0.0), 2, (l4 / 2, 0.0)),  # coupler pin B in the rocker's bushing
    }


def pack(p: FourBarParameters, phi0: float) -> tuple[np.ndarray, dict[str, int]]:
    """Parameters as one float array for the compiled code, with the index of every name."""
    l2, l3, l4 = p.lengths
    m, inertia = p.masses, p.inertias
    values = {
        "mass": [m[0], m[0], inertia[0], m[1], m[1], inertia[1], m[2], m[2], inertia[2]],
        "ground": [p.ground],
        "l": [l2, l3, l4],
        "omega": [p.crank_speed],
        "phi0": [phi0],
        "alpha": [p.baumgarte_alpha],
        "beta": [p.baumgarte_beta],
        "gravity": [p.gravity],
        "clearance": [p.clearance],
        "r_journal": [p.journal_radius],
        "r_bearing": [p.bearing_radius],
        "hertz": [p.hertz_stiffness],
        "restitution": [p.restitution],
        "friction": [p.friction],
        "v0": [p.v0],
        "v1": [p.v1],
        "film": [p.film_coefficient],
        "eps_limit": [1.0 - p.e0 / p.clearance],
        "floor": [p.impact_velocity_floor],
        # appended last so that every earlier index (and so the generated source) keeps its place
        "elastic_law": [float(ELASTIC_LAWS[p.elastic_law])],
        "elastic_stiffness": [p.elastic_stiffness],
        "elastic_exponent": [p.elastic_exponent],
    }
    index, flat = {}, []
    for key, vals in values.items():
        index[key] = len(flat)
        flat.extend(vals)
    return np.array(flat, dtype=float), index


def generate_source(clearance_joints: tuple[int, ...], effects: tuple[str, ...], contact_law: str, lengths) -> str:
    """Python source of the scene's right-hand side and integrators (numba)."""
    unknown = set(effects) - set(EFFECTS)
    if unknown:
        raise ValueError(f"unknown effect(s) {sorted(unknown)}; known: {EFFECTS}")
    if any(j not in (1, 2) for j in clearance_joints):
        raise ValueError(f"clearance joints must be 1 and/or 2, got {clearance_joints}")
    if "friction" in effects and "contact" not in effects:
        raise ValueError("friction needs the contact effect (it acts with the normal contact force)")
    law = CONTACT_LAWS[contact_law]
    _, idx = pack(_dummy_parameters(lengths), 0.0)
    l2, l3, l4 = (f"p[{idx['l'] + k}]" for k in range(3))
    pts = {1: (0, f"0.5 * {l2}", "0.0", 1, f"-0.5 * {l3}", "0.0"), 2: (1, f"0.5 * {l3}", "0.0", 2, f"0.5 * {l4}", "0.0")}
    ideal = [j for j in (1, 2) if j not in clearance_joints]
    nc = 2 + 1 + 2 + 2 * len(ideal)
    n_diag = DIAG_FIXED + DIAG_PER_JOINT * len(clearance_joints)
    P = lambda name, k=0: f"p[{idx[name] + k}]"  # noqa: E731
    L = []
    a = L.append
    a("import numpy as np")
    a("from numba import njit")
    a("from linkwork.engines.multibody.kernels import (revolute, driver, apply_force, clearance_state, hertz_damping_factor,")
    a("    friction_coefficient, film_forces, gauss_solve_into, elastic_contact, body_trig)")
    a(f"NC = {nc}")
    a(f"N_DIAG = {n_diag}")
    a(f"JOINTS = {tuple(clearance_joints)}")
    a(f"EFFECTS = {tuple(effects)}")
    a("")
    a(f"N_WORK = {15 + nc * (15 + nc)}")
    a("")
    a("@njit(cache=True)")
    a("def rhs(t, y, p, latched, counts, diag):")
    a("    \"\"\"dy/dt at (t, y), a new array; the diagnostics into ``diag`` (see rhs_into).\"\"\"")
    a("    out = np.empty(19)")
    a("    rhs_into(t, y, p, latched, counts, diag, np.empty(N_WORK), out)")
    a("    return out")
    a("")
    a("@njit(cache=True)")
    a("def rhs_into(t, y, p, latched, counts, diag, w, out):")
    a("    \"\"\"dy/dt at (t, y) into ``out`` (19), the diagnostics into ``diag``; ``w``: a work array of N_WORK,")
    a("    cleared here and cut into the pieces below (the integrators pass one, so that a call allocates nothing).\"\"\"")
    a("    q = y[0:9]")
    a("    qd = y[9:18]")
    a("    w[:] = 0.0")
    a("    cs = w[0:6]")
    a("    body_trig(q, cs)")
    a("    g = w[6:15]")
    a("    phi = w[15 : 15 + NC]")
    a("    gamma = w[15 + NC : 15 + 2 * NC]")
    a("    phidot = w[15 + 2 * NC : 15 + 3 * NC]")
    a("    gamma_b = w[15 + 3 * NC : 15 + 4 * NC]")
    a("    schur_rhs = w[15 + 4 * NC : 15 + 5 * NC]")
    a("    lam = w[15 + 5 * NC : 15 + 6 * NC]")
    a("    phiq = w[15 + 6 * NC : 15 + 15 * NC].reshape((NC, 9))")
    a("    schur = w[15 + 15 * NC :].reshape((NC, NC))")
    a(f"    mass = p[{idx['mass']}:{idx['mass'] + 9}]")
    a("    potential = 0.0")
    if "gravity" in effects:
        a("    counts[3] += 1")
        a("    for b in range(3):")
        a(f"        g[3 * b + 1] -= mass[3 * b] * {P('gravity')}")
        a(f"        potential += mass[3 * b] * {P('gravity')} * q[3 * b + 1]")
    for k, j in enumerate(clearance_joints):
        bj, jx, jy, bb, bx, by = pts[j]
        o = DIAG_FIXED + DIAG_PER_JOINT * k
        a(f"    # clearance joint {j}")
        a(f"    e, nx, ny, delta, ddot, vt, wj, wb, gd = clearance_state(q, qd, cs, {bj}, {jx}, {jy}, {bb}, {bx}, {by}, "
          f"{P('clearance')}, {P('r_journal')}, {P('r_bearing')})")
        a("    fn = 0.0")
        a("    ft = 0.0")
        a("    fr_film = 0.0")
        a("    ft_film = 0.0")
        if "contact" in effects:
            a("    if delta > 0.0:")
            a("        counts[0] += 1")
            a(f"        vimp = latched[{k}] if latched[{k}] > {P('floor')} else {P('floor')}")
            law_k_n = f"int({P('elastic_law')}), {P('elastic_stiffness')}, {P('elastic_exponent')}"
            a(f"        fe, ue = elastic_contact({law_k_n}, delta)")
            a(f"        fn = fe * hertz_damping_factor({law}, {P('restitution')}, ddot, vimp)")
            a("        potential += ue")
            if "friction" in effects:
                a("        counts[1] += 1")
                a(f"        ft = friction_coefficient(vt, {P('friction')}, {P('v0')}, {P('v1')}) * fn")
        if "lubrication" in effects:
            a("    counts[2] += 1")
            a(f"    fr_film, ft_film = film_forces(e / {P('clearance')}, ddot / {P('clearance')}, wj + wb, gd, {P('film')}, {P('eps_limit')})")
        a("    tx, ty = -ny, nx")
        a("    fx = (-fn + fr_film) * nx + (ft + ft_film) * tx")
        a("    fy = (-fn + fr_film) * ny + (ft + ft_film) * ty")
        a(f"    apply_force(q, cs, g, {bj}, {jx}, {jy}, fx, fy)")
        a(f"    apply_force(q, cs, g, {bb}, {bx}, {by}, -fx, -fy)")
        if "friction" in effects:
            a(f"    g[{3 * bj + 2}] += {P('r_journal')} * ft")
            a(f"    g[{3 * bb + 2}] -= {P('r_bearing')} * ft")
        for m_, val in enumerate(("e", "delta", "ddot", "fn", "fr_film", "ft_film")):
            a(f"    diag[{o + m_}] = {val}")
    a(f"    revolute(q, qd, cs, 0, -0.5 * {l2}, 0.0, -1, 0.0, 0.0, 0.0, 0.0, 0, phi, phiq, gamma, phidot)")
    a(f"    driver(q, qd, t, 0, {P('phi0')}, {P('omega')}, 2, phi, phiq, gamma, phidot)")
    a(f"    revolute(q, qd, cs, 2, -0.5 * {l4}, 0.0, -1, 0.0, 0.0, {P('ground')}, 0.0, 3, phi, phiq, gamma, phidot)")
    pattern = [*revolute_pattern(0, -1), [2], *revolute_pattern(2, -1)]  # Phi_q's nonzero columns per row
    row = 5
    for j in ideal:
        bj, jx, jy, bb, bx, by = pts[j]
        a(f"    revolute(q, qd, cs, {bj}, {jx}, {jy}, {bb}, {bx}, {by}, 0.0, 0.0, {row}, phi, phiq, gamma, phidot)")
        pattern += revolute_pattern(bj, bb)
        row += 2
    a(f"    damping = 2.0 * {P('alpha')}")
    a(f"    stiffness = {P('beta')} ** 2")
    a("    for r in range(NC):")
    a("        gamma_b[r] = gamma[r] - damping * phidot[r] - stiffness * phi[r]")
    a("    out[0:9] = qd")
    a("    qdd = out[9:18]")
    L.extend(schur_source(pattern))
    a("    torque = -lam[2]")
    a("    out[18] = torque * qd[2]")
    a("    kinetic = 0.0")
    a("    for k in range(9):")
    a("        kinetic += 0.5 * mass[k] * qd[k] * qd[k]")
    a("    diag[0] = qdd[8]")
    a("    diag[1] = torque")
    a("    diag[2] = kinetic + potential")
    a("    drift = 0.0")
    a("    for r in range(NC):")
    a("        drift += phi[r] * phi[r]")
    a("    diag[3] = np.sqrt(drift)")
    a("")
    a(dop853_coefficients_source())
    a(INTEGRATORS)
    return "\n".join(L)


def revolute_pattern(bi: int, bj: int) -> list[list[int]]:
    """The columns of Phi_q a revolute between bodies bi and bj (bj < 0: the ground) fills, in its x and y rows."""
    bodies = [b for b in (bi, bj) if b >= 0]
    return [sorted(c for b in bodies for c in (3 * b, 3 * b + 2)), sorted(c for b in bodies for c in (3 * b + 1, 3 * b + 2))]


def schur_source(pattern: list[list[int]]) -> list[str]:
    """Source lines that solve M q'' = g - Phi_q^T lam, Phi_q q'' = gamma_b (M diagonal) by the Schur complement
    Phi_q M^-1 Phi_q^T lam = Phi_q M^-1 g - gamma_b, summing only the products of Phi_q's nonzero entries
    (``pattern``: the nonzero columns of each row).  The sums run over the columns in increasing order, as a full
    loop would, and the terms left out are exact zeros, so the result is the full loop's to the bit; the complement
    is symmetric and each pair is summed once."""
    lines = []
    for a, cols_a in enumerate(pattern):
        for b in range(a, len(pattern)):
            common = sorted(set(cols_a) & set(pattern[b]))
            terms = "".join(f" + phiq[{a}, {k}] * phiq[{b}, {k}] / mass[{k}]" for k in common)
            lines.append(f"    schur[{a}, {b}] = 0.0{terms}")
            if b != a:
                lines.append(f"    schur[{b}, {a}] = schur[{a}, {b}]")
        terms = "".join(f" + phiq[{a}, {k}] * (g[{k}] / mass[{k}])" for k in cols_a)
        lines.append(f"    schur_rhs[{a}] = (0.0{terms}) - gamma_b[{a}]")
    lines.append("    gauss_solve_into(schur, schur_rhs, lam)")
    for k in range(9):
        terms = "".join(f" - phiq[{a}, {k}] * lam[{a}]" for a, cols in enumerate(pattern) if k in cols)
        lines.append(f"    qdd[{k}] = (g[{k}]{terms}) / mass[{k}]")
    return lines


def dop853_coefficients_source() -> str:
    """The DOP853 tableau (Hairer, Norsett and Wanner; as tabulated in scipy.integrate) as module constants of a
    generated scene: stages A, C, weights B, error weights E3, E5, dense-output weights D (extra stages 13-15), from
    ``dop853_tableau`` (no import of scipy.integrate)."""
    from . import dop853_tableau as c

    def arr(x) -> str:
        return "np.array(" + repr(np.asarray(x, dtype=float).tolist()) + ")"

    return "\n".join([f"D853_A = {arr(c.A)}", f"D853_B = {arr(c.B)}", f"D853_C = {arr(c.C)}", f"D853_E3 = {arr(c.E3)}",
                      f"D853_E5 = {arr(c.E5)}", f"D853_D = {arr(c.D)}", ""])


INTEGRATORS = '''
@njit(cache=True)
def _latch(diag, latched, was_in_contact):
    for k in range(len(JOINTS)):
        delta = diag[4 + 6 * k + 1]
        ddot = diag[4 + 6 * k + 2]
        now = delta > 0.0
        if now and not was_in_contact[k]:
            latched[k] = abs(ddot)
        was_in_contact[k] = now


@njit(cache=True)
def _start(y0, t0, n_out, p, latched, counts, was):
    """Output buffers, work arrays and the first right-hand side (latching its contact state; ``was`` holds
    which joints were in contact before t0, so that a continued run latches no impact that is not one)."""
    ys = np.empty((n_out, y0.size))
    diags = np.empty((n_out, N_DIAG))
    diag = np.zeros(N_DIAG)
    scratch = np.zeros(N_DIAG)
    y = y0.copy()
    k1 = rhs(t0, y, p, latched, counts, diag)
    _latch(diag, latched, was)
    return ys, diags, diag, scratch, was, y, k1


@njit(cache=True)
def jacobian(t, y, p, latched, counts, scratch):
    """d rhs / d y by forward differences (step sqrt(eps) max(|y_j|, 1)), compiled: for the implicit integrators."""
    n = y.size
    work = np.empty(N_WORK)
    f0 = np.empty(n)
    f1 = np.empty(n)
    rhs_into(t, y, p, latched, counts, scratch, work, f0)
    jac = np.empty((n, n))
    yy = y.copy()
    for j in range(n):
        h = 1.4901161193847656e-08 * max(abs(y[j]), 1.0)
        yy[j] = y[j] + h
        rhs_into(t, yy, p, latched, counts, scratch, work, f1)
        for i in range(n):
            jac[i, j] = (f1[i] - f0[i]) / h
        yy[j] = y[j]
    return jac


@njit(cache=True)
def rk4(y0, t0, h, t_out, p, latched, counts, was):
    """Fixed-step RK4; steps are shortened only to land on the output times."""
    n_out = t_out.size
    ys, diags, diag, scratch, was, y, k1 = _start(y0, t0, n_out, p, latched, counts, was)
    t = t0
    steps = 0
    for i in range(n_out):
        while t < t_out[i] - 1e-15:
            hh = min(h, t_out[i] - t)
            k2 = rhs(t + 0.5 * hh, y + 0.5 * hh * k1, p, latched, counts, scratch)
            k3 = rhs(t + 0.5 * hh, y + 0.5 * hh * k2, p, latched, counts, scratch)
            k4 = rhs(t + hh, y + hh * k3, p, latched, counts, scratch)
            y = y + hh / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
            t = t + hh
            k1 = rhs(t, y, p, latched, counts, diag)
            _latch(diag, latched, was)
            steps += 1
        ys[i] = y
        diags[i] = diag
    return ys, diags, steps, 0, h


@njit(cache=True)
def dopri5(y0, t0, t_out, p, latched, counts, rtol, atol, h0, h_max, was):
    """Adaptive Dormand-Prince 5(4) with FSAL; steps land on the output times; latching at accepted steps."""
    c2, c3, c4, c5 = 1.0 / 5, 3.0 / 10, 4.0 / 5, 8.0 / 9
    a21 = 1.0 / 5
    a31, a32 = 3.0 / 40, 9.0 / 40
    a41, a42, a43 = 44.0 / 45, -56.0 / 15, 32.0 / 9
    a51, a52, a53, a54 = 19372.0 / 6561, -25360.0 / 2187, 64448.0 / 6561, -212.0 / 729
    a61, a62, a63, a64, a65 = 9017.0 / 3168, -355.0 / 33, 46732.0 / 5247, 49.0 / 176, -5103.0 / 18656
    b1, b3, b4, b5, b6 = 35.0 / 384, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784, 11.0 / 84
    e1, e3, e4, e5, e6, e7 = 71.0 / 57600, -71.0 / 16695, 71.0 / 1920, -17253.0 / 339200, 22.0 / 525, -1.0 / 40
    n_out = t_out.size
    ys, diags, diag, scratch, was, y, k1 = _start(y0, t0, n_out, p, latched, counts, was)
    t = t0
    h = h0
    accepted = 0
    rejected = 0
    for i in range(n_out):
        while t < t_out[i] - 1e-15:
            hh = min(h, h_max, t_out[i] - t)
            k2 = rhs(t + c2 * hh, y + hh * a21 * k1, p, latched, counts, scratch)
            k3 = rhs(t + c3 * hh, y + hh * (a31 * k1 + a32 * k2), p, latched, counts, scratch)
            k4 = rhs(t + c4 * hh, y + hh * (a41 * k1 + a42 * k2 + a43 * k3), p, latched, counts, scratch)
            k5 = rhs(t + c5 * hh, y + hh * (a51 * k1 + a52 * k2 + a53 * k3 + a54 * k4), p, latched, counts, scratch)
            k6 = rhs(t + hh, y + hh * (a61 * k1 + a62 * k2 + a63 * k3 + a64 * k4 + a65 * k5), p, latched, counts, scratch)
            y_new = y + hh * (b1 * k1 + b3 * k3 + b4 * k4 + b5 * k5 + b6 * k6)
            k7 = rhs(t + hh, y_new, p, latched, counts, scratch)
            err_vec = hh * (e1 * k1 + e3 * k3 + e4 * k4 + e5 * k5 + e6 * k6 + e7 * k7)
            sc = atol + rtol * np.maximum(np.abs(y), np.abs(y_new))
            err = np.sqrt(np.mean((err_vec / sc) ** 2))
            if err <= 1.0:
                t = t + hh
                y = y_new
                k1 = k7  # first same as last: its diagnostics are in scratch
                diag[:] = scratch
                _latch(diag, latched, was)
                accepted += 1
                fac = 5.0 if err == 0.0 else min(5.0, max(0.2, 0.9 * err ** -0.2))
                if hh == t_out[i] - (t - hh) and hh < h:
                    fac = max(fac, 1.0)
                h = hh * fac
            else:
                rejected += 1
                h = hh * max(0.2, 0.9 * err ** -0.25)
                if h < 1e-14:
                    raise RuntimeError("dopri5: step size underflow")
        ys[i] = y
        diags[i] = diag
    return ys, diags, accepted, rejected, h


@njit(cache=True)
def _rms(x):
    return np.sqrt(np.mean(x * x))


@njit(cache=True)
def _ndf_R(order, factor):
    """The matrix that re-expresses the differences array for a step size changed by ``factor``."""
    m = np.zeros((order + 1, order + 1))
    m[0, :] = 1.0
    for i in range(1, order + 1):
        for j in range(1, order + 1):
            m[i, j] = (i - 1 - factor * j) / i
    for i in range(1, order + 1):
        for j in range(order + 1):
            m[i, j] *= m[i - 1, j]
    return m


@njit(cache=True)
def _ndf_change(D, order, factor):
    ru = _ndf_R(order, factor) @ _ndf_R(order, 1.0)
    D[: order + 1] = ru.T @ D[: order + 1].copy()


@njit(cache=True)
def ndf(y0, t0, t_out, p, latched, counts, rtol, atol, h0, h_max, was):
    """Variable-order (1-5) implicit NDF/BDF, compiled: the algorithm of scipy.integrate.BDF (quasi-constant step,
    numerical differentiation formulas, Newton with a reused Jacobian), with the compiled finite-difference
    Jacobian; outputs at t_out by the method's own interpolating polynomial; latching at accepted steps."""
    n_out = t_out.size
    ys, diags, diag, scratch, was, y, f = _start(y0, t0, n_out, p, latched, counts, was)
    n = y.size
    kappa = np.array([0.0, -0.1850, -1.0 / 9.0, -0.0823, -0.0415, 0.0])
    gamma = np.zeros(6)
    for k in range(1, 6):
        gamma[k] = gamma[k - 1] + 1.0 / k
    alpha = (1.0 - kappa) * gamma
    error_const = kappa * gamma + 1.0 / np.arange(1, 7)
    newton_tol = max(10.0 * 2.220446049250313e-16 / rtol, min(0.03, rtol ** 0.5))
    D = np.zeros((8, n))
    D[0] = y
    D[1] = f * h0
    order = 1
    n_equal = 0
    h_abs = h0
    J = jacobian(t0, y, p, latched, counts, scratch)
    current_jac = True
    work = np.empty(N_WORK)
    fk = np.empty(n)
    eye = np.eye(n)
    minv = np.empty((n, n))
    inv_ok = False
    t = t0
    i = 0
    while i < n_out and t_out[i] <= t + 1e-15:
        ys[i] = y
        diags[i] = diag
        i += 1
    accepted = 0
    rejected = 0
    t_bound = t_out[-1]
    while i < n_out:
        if h_abs > h_max:
            _ndf_change(D, order, h_max / h_abs)
            h_abs = h_max
            n_equal = 0
            inv_ok = False
        min_step = 10.0 * 2.220446049250313e-16 * abs(t)  # as scipy: ten units in the last place of t
        while True:
            if h_abs < min_step:
                raise RuntimeError("ndf: step size underflow")
            t_new = t + h_abs
            if t_new > t_bound:
                t_new = t_bound
                _ndf_change(D, order, (t_new - t) / h_abs)
                n_equal = 0
                inv_ok = False
            h = t_new - t
            h_abs = h
            y_predict = np.zeros(n)
            for k in range(order + 1):
                y_predict += D[k]
            scale = atol + rtol * np.abs(y_predict)
            psi = np.zeros(n)
            for k in range(1, order + 1):
                psi += D[k] * gamma[k]
            psi /= alpha[order]
            c = h / alpha[order]
            converged = False
            n_iter = 0
            y_new = y_predict.copy()
            d = np.zeros(n)
            while True:
                if not inv_ok:
                    minv = np.ascontiguousarray(np.linalg.inv(eye - c * J))
                    inv_ok = True
                # Newton iterations on the BDF system
                y_new = y_predict.copy()
                d = np.zeros(n)
                converged = False
                dy_norm_old = -1.0
                for k in range(4):
                    n_iter = k + 1
                    rhs_into(t_new, y_new, p, latched, counts, scratch, work, fk)
                    if not np.all(np.isfinite(fk)):
                        break
                    dy = minv @ (c * fk - psi - d)
                    dy_norm = _rms(dy / scale)
                    rate = -1.0 if dy_norm_old < 0 else dy_norm / dy_norm_old
                    if rate >= 0 and (rate >= 1 or rate ** (4 - k) / (1 - rate) * dy_norm > newton_tol):
                        break
                    y_new += dy
                    d += dy
                    if dy_norm == 0 or (rate >= 0 and rate / (1 - rate) * dy_norm < newton_tol):
                        converged = True
                        break
                    dy_norm_old = dy_norm
                if converged or current_jac:
                    break
                J = jacobian(t_new, y_predict, p, latched, counts, scratch)
                current_jac = True
                inv_ok = False
            if not converged:
                h_abs *= 0.5
                _ndf_change(D, order, 0.5)
                n_equal = 0
                inv_ok = False
                rejected += 1
                continue
            safety = 0.9 * 9.0 / (8.0 + n_iter)
            scale = atol + rtol * np.abs(y_new)
            error_norm = _rms(error_const[order] * d / scale)
            if error_norm > 1.0:
                factor = max(0.2, safety * error_norm ** (-1.0 / (order + 1)))
                h_abs *= factor
                _ndf_change(D, order, factor)
                n_equal = 0
                inv_ok = False
                rejected += 1
                continue
            break
        accepted += 1
        n_equal += 1
        t = t_new
        y = y_new
        current_jac = False
        D[order + 2] = d - D[order + 1]
        D[order + 1] = d
        for k in range(order, -1, -1):
            D[k] += D[k + 1]
        rhs_into(t, y, p, latched, counts, diag, work, fk)
        _latch(diag, latched, was)
        while i < n_out and t_out[i] <= t + 1e-15:  # the step's interpolating polynomial, into ys[i] in place
            yi = ys[i]
            for m in range(n):
                yi[m] = D[0, m]
            prod = 1.0
            for k in range(1, order + 1):
                prod *= (t_out[i] - (t - h * (k - 1))) / (h * k)
                for m in range(n):
                    yi[m] += D[k, m] * prod
            rhs_into(t_out[i], yi, p, latched, counts, diags[i], work, fk)
            i += 1
        if n_equal < order + 1:
            continue
        em = _rms(error_const[order - 1] * D[order] / scale) if order > 1 else np.inf
        ep = _rms(error_const[order + 1] * D[order + 2] / scale) if order < 5 else np.inf
        norms = np.array([em, error_norm, ep])
        best, delta = -1.0, 0
        for k in range(3):
            fac = np.inf if norms[k] == 0 else norms[k] ** (-1.0 / (order + k))
            if fac > best:
                best, delta = fac, k - 1
        order += delta
        factor = min(10.0, safety * best)
        h_abs *= factor
        _ndf_change(D, order, factor)
        n_equal = 0
        inv_ok = False
    return ys, diags, accepted, rejected, h_abs

@njit(cache=True)
def _d853_stage(y, K, row, s, h, out):
    """out = y + h * sum_j<s A[row, j] K[j]."""
    for m in range(y.size):
        acc = 0.0
        for j in range(s):
            acc += D853_A[row, j] * K[j, m]
        out[m] = y[m] + h * acc


@njit(cache=True)
def dop853(y0, t0, t_out, p, latched, counts, rtol, atol, h0, h_max, was):
    """Adaptive Dormand-Prince 8(5,3) (DOP853: scipy's step-size control and error norm), compiled; outputs at t_out
    by its 7th-order dense output (three extra stages in a step that holds an output), the diagnostics evaluated
    there; steps land only on t_out[-1]; latching at accepted steps."""
    n_out = t_out.size
    ys, diags, diag, scratch, was, y, f = _start(y0, t0, n_out, p, latched, counts, was)
    n = y.size
    K = np.empty((16, n))
    F = np.empty((7, n))
    yy = np.empty(n)
    y_new = np.empty(n)
    diag_new = np.zeros(N_DIAG)
    work = np.empty(N_WORK)
    f_out = np.empty(n)
    t = t0
    h = h0
    t_end = t_out[-1]
    accepted = 0
    rejected = 0
    i = 0
    while i < n_out and t_out[i] <= t + 1e-15:
        ys[i] = y
        diags[i] = diag
        i += 1
    while t < t_end - 1e-15:
        step_rejected = False
        while True:
            hh = min(h, h_max)
            t_new = t + hh
            if t_new >= t_end - 1e-15:
                t_new = t_end
                hh = t_end - t
            K[0] = f
            for s in range(1, 12):
                _d853_stage(y, K, s, s, hh, yy)
                rhs_into(t + D853_C[s] * hh, yy, p, latched, counts, scratch, work, K[s])
            for m in range(n):
                acc = 0.0
                for j in range(12):
                    acc += D853_B[j] * K[j, m]
                y_new[m] = y[m] + hh * acc
            rhs_into(t_new, y_new, p, latched, counts, diag_new, work, K[12])
            e5 = 0.0
            e3 = 0.0
            for m in range(n):
                sc = atol + rtol * max(abs(y[m]), abs(y_new[m]))
                a5 = 0.0
                a3 = 0.0
                for j in range(13):
                    a5 += D853_E5[j] * K[j, m]
                    a3 += D853_E3[j] * K[j, m]
                e5 += (a5 / sc) ** 2
                e3 += (a3 / sc) ** 2
            err = 0.0 if e5 == 0.0 and e3 == 0.0 else hh * e5 / np.sqrt((e5 + 0.01 * e3) * n)
            if err < 1.0:
                break
            rejected += 1
            step_rejected = True
            h = hh * max(0.2, 0.9 * err ** (-1.0 / 8.0))
            if h < 1e-14:
                raise RuntimeError("dop853: step size underflow")
        factor = 10.0 if err == 0.0 else min(10.0, 0.9 * err ** (-1.0 / 8.0))
        if step_rejected:
            factor = min(1.0, factor)
        if i < n_out and t_out[i] < t_new - 1e-15:
            for s in range(13, 16):
                _d853_stage(y, K, s, s, hh, yy)
                rhs_into(t + D853_C[s] * hh, yy, p, latched, counts, scratch, work, K[s])
            for m in range(n):
                dy = y_new[m] - y[m]
                F[0, m] = dy
                F[1, m] = hh * f[m] - dy
                F[2, m] = 2.0 * dy - hh * (f[m] + K[12, m])
                for r in range(4):
                    acc = 0.0
                    for j in range(16):
                        acc += D853_D[r, j] * K[j, m]
                    F[3 + r, m] = hh * acc
            while i < n_out and t_out[i] < t_new - 1e-15:
                x = (t_out[i] - t) / hh
                for m in range(n):
                    v = 0.0
                    for r in range(7):
                        v += F[6 - r, m]
                        v *= x if r % 2 == 0 else 1.0 - x
                    yy[m] = y[m] + v
                ys[i] = yy
                rhs_into(t_out[i], yy, p, latched, counts, diags[i], work, f_out)
                i += 1
        t = t_new
        y[:] = y_new
        f[:] = K[12]
        diag[:] = diag_new
        _latch(diag, latched, was)
        accepted += 1
        while i < n_out and t_out[i] <= t + 1e-15:
            ys[i] = y
            diags[i] = diag
            i += 1
        if t_new != t_end or hh >= h:
            h = hh * factor
    return ys, diags, accepted, rejected, h

'''


def _dummy_parameters(lengths) -> FourBarParameters:
    return FourBarParameters(1.0, tuple(lengths), (1.0,) * 3, (1.0,) * 3, 1.0, 0.0099, 0.01, (1.0, 1.0), (0.3, 0.3),
                             0.01, 0.9, 0.0, 1e-4, 1e-3, 0.0, 1e-7, 1e-3, 1.0, 1.0)


def cache_dir() -> Path:
    """Where generated scene modules are written (LINKWORK_CACHE, else ~/.cache/linkwork)."""
    return Path(os.environ.get("LINKWORK_CACHE", Path.home() / ".cache" / "linkwork")) / "multibody"


def compile_scene(clearance_joints: tuple[int, ...], effects: tuple[str, ...], contact_law: str = "lankarani-nikravesh"):
    """The compiled module of a scene (rhs, rk4, dopri5), cached on disk by the hash of its source.

    The elastic law is data, not code: ``pack`` gives its code, K and n, and the one compiled module serves every
    elastic law (the dispatch is in ``kernels.elastic_contact``), so it needs no place in the key.
    """
    source = generate_source(tuple(clearance_joints), tuple(effects), contact_law, (1.0, 1.0, 1.0))
    digest = hashlib.sha256(source.encode()).hexdigest()[:16]
    name = f"linkwork_scene_{digest}"
    if name in sys.modules:
        return sys.modules[name]
    folder = cache_dir()
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / f"{name}.py"
    if not path.exists() or path.read_text() != source:
        tmp = path.with_suffix(f".{os.getpid()}.tmp")
        tmp.write_text(source)
        os.replace(tmp, path)
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    spec.loader.exec_module(module)
    return module


# --- initial state and the ideal (kinematic) scene -------------------------------------------------


def start_angle(p: FourBarParameters) -> float:
    """Crank angle with crank and coupler collinear (extended): the rocker's dead point."""
    return float(toggle_positions(p.linkage()).crank_angle[0])


def kinematic_state(p: FourBarParameters, crank_angle: np.ndarray):
    """Body positions q, velocities q' and accelerations q'' of the ideal linkage (n, 9) each."""
    m = four_bar(p.linkage(), crank_angle)
    w = p.crank_speed
    l2, l3, l4 = p.lengths
    ang = np.stack([m.crank_angle, m.coupler_angle, m.rocker_angle], axis=-1)
    rate = np.stack([np.ones_like(m.crank_angle), m.coupler_rate, m.rocker_rate], axis=-1) * w
    acc = np.stack([np.zeros_like(m.crank_angle), m.coupler_accel, m.rocker_accel], axis=-1) * w**2
    starts = [np.zeros_like(m.A), m.A, np.broadcast_to(p.linkage().rocker_pivot, m.A.shape)]
    half = [l2 / 2, l3 / 2, l4 / 2]
    q = np.empty(ang.shape[:-1] + (9,))
    qd, qdd = np.empty_like(q), np.empty_like(q)
    for b in range(3):
        e = np.stack([np.cos(ang[..., b]), np.sin(ang[..., b])], axis=-1)
        perp = np.stack([-e[..., 1], e[..., 0]], axis=-1)
        start_vel = np.zeros_like(e) if b != 1 else l2 * w * np.stack([-np.sin(ang[..., 0]), np.cos(ang[..., 0])], axis=-1)
        start_acc = np.zeros_like(e) if b != 1 else -l2 * w**2 * np.stack([np.cos(ang[..., 0]), np.sin(ang[..., 0])], axis=-1)
        q[..., 3 * b : 3 * b + 2] = starts[b] + half[b] * e
        q[..., 3 * b + 2] = ang[..., b]
        qd[..., 3 * b : 3 * b + 2] = start_vel + half[b] * rate[..., b, None] * perp
        qd[..., 3 * b + 2] = rate[..., b]
        qdd[..., 3 * b : 3 * b + 2] = start_acc + half[b] * (acc[..., b, None] * perp - rate[..., b, None] ** 2 * e)
        qdd[..., 3 * b + 2] = acc[..., b]
    return q, qd, qdd


def inverse_dynamics(p: FourBarParameters, t: np.ndarray, gravity: bool) -> dict[str, np.ndarray]:
    """The ideal scene: kinematics, then Phi_q^T lambda = g - M q'' (no time integration).

    Returns rocker angular acceleration, crank torque, joint reaction magnitudes at A and B and the
    mechanical energy, at the times t (s).  The constraint Jacobians are assembled by the compiled kernels in one
    compiled loop (``kernels.ideal_jacobians``) and the systems solved as one stack (the same numbers as a loop of single
    solves: tests/test_clearance.py).
    """
    from .kernels import ideal_jacobians

    module = compile_scene((), ("gravity",) if gravity else ())
    phi0 = start_angle(p)
    t = np.asarray(t, dtype=float)
    theta = phi0 + p.crank_speed * t
    q, qd, qdd = kinematic_state(p, theta)
    params, idx = pack(p, phi0)
    mass = params[idx["mass"] : idx["mass"] + 9]
    l2, l3, l4 = p.lengths
    phiq = ideal_jacobians(q, qd, t, module.NC, phi0, p.crank_speed, float(l2), float(l3), float(l4), float(p.ground))
    g = np.zeros(9)
    if gravity:
        g[1::3] -= mass[0::3] * p.gravity
    lam = np.linalg.solve(np.swapaxes(phiq, 1, 2), (g - mass * qdd)[..., None])[..., 0]
    energy = 0.5 * np.sum(mass * qd**2, axis=-1)
    if gravity:
        energy = energy + np.sum(mass[0::3] * p.gravity * q[:, 1::3], axis=-1)
    return {"rocker_acceleration": qdd[:, 8], "crank_torque": -lam[:, 2], "force_A": np.hypot(lam[:, 5], lam[:, 6]),
            "force_B": np.hypot(lam[:, 7], lam[:, 8]), "energy": energy}


def initial_state(p: FourBarParameters, offset: tuple[float, float] = (0.0, 0.0), joint: int = 0) -> tuple[np.ndarray, float]:
    """Consistent initial state at the dead point (journals centred), optionally displacing the coupler
    by ``offset`` (m) to start a journal off-centre.  Returns (y0, phi0)."""
    phi0 = start_angle(p)
    q, qd, _ = kinematic_state(p, np.array([phi0]))
    y0 = np.zeros(N_STATE)
    y0[:9], y0[9:18] = q[0], qd[0]
    if joint:
        y0[3] += offset[0]
        y0[4] += offset[1]
    return y0, phi0


def _point(q: np.ndarray, body: int, local) -> np.ndarray:
    """World position (m) of a body's local point (m), q of shape (..., 9)."""
    phi = q[..., 3 * body + 2]
    c, s = np.cos(phi), np.sin(phi)
    return np.stack([q[..., 3 * body] + c * local[0] - s * local[1], q[..., 3 * body + 1] + s * local[0] + c * local[1]], axis=-1)


def _point_velocity(q: np.ndarray, qd: np.ndarray, body: int, local) -> np.ndarray:
    """World velocity (m/s) of a body's local point."""
    phi, w = q[..., 3 * body + 2], qd[..., 3 * body + 2]
    c, s = np.cos(phi), np.sin(phi)
    rx, ry = c * local[0] - s * local[1], s * local[0] + c * local[1]
    return np.stack([qd[..., 3 * body] - w * ry, qd[..., 3 * body + 1] + w * rx], axis=-1)


def journal_offsets(p: FourBarParameters, clearance_joints, states: np.ndarray) -> np.ndarray:
    """Eccentricity e = journal centre - bearing centre (m) and its rate (m/s) of each clearance joint in the states
    (..., >= 18): shape (..., joint, 4) as (e_x, e_y, e_x', e_y') in the fixed frame."""
    q, qd = states[..., :9], states[..., 9:18]
    pts = joint_points(p.lengths)
    out = []
    for j in clearance_joints:
        bj, sj, bb, sb = pts[j]
        e = _point(q, bj, sj) - _point(q, bb, sb)
        v = _point_velocity(q, qd, bj, sj) - _point_velocity(q, qd, bb, sb)
        out.append(np.concatenate([e, v], axis=-1))
    return np.stack(out, axis=-2)


def _position_residual(p: FourBarParameters, q: np.ndarray, phi0: float, clearance_joints, eccentricity) -> np.ndarray:
    """The nine position equations of a start: crank pinned to the ground at O2 and at angle phi0, rocker pinned at
    O4, each ideal joint closed, each clearance joint at its eccentricity (m)."""
    l2, l3, l4 = p.lengths
    pts = joint_points(p.lengths)
    res = [_point(q, 0, (-l2 / 2, 0.0)), [q[2] - phi0], _point(q, 2, (-l4 / 2, 0.0)) - np.array([p.ground, 0.0])]
    for j in (1, 2):
        bj, sj, bb, sb = pts[j]
        gap = _point(q, bj, sj) - _point(q, bb, sb)
        res.append(gap - (np.asarray(eccentricity, dtype=float) if j in clearance_joints else 0.0))
    return np.concatenate([np.ravel(r) for r in res])


def offset_start(p: FourBarParameters, clearance_joints, eccentricity, rate, tol: float = 1e-15) -> np.ndarray:
    """A start at the dead point with every clearance joint's journal at ``eccentricity`` (m, (x, y)) and moving
    at ``rate`` (m/s) relative to its bearing, the ground pins, the drive and the ideal joints exact: positions by
    Newton's method on the nine position equations, velocities from the same equations'
    rate form (crank at the drive speed), both with the complex-step Jacobian.  Returns y0 (N_STATE,)."""
    phi0 = start_angle(p)
    q = kinematic_state(p, np.array([phi0]))[0][0].copy()
    for _ in range(20):
        r = _position_residual(p, q, phi0, clearance_joints, eccentricity)
        jac = _residual_jacobian(p, q, phi0, clearance_joints, eccentricity)
        dq = np.linalg.solve(jac, -r)
        q += dq
        if np.max(np.abs(dq)) < tol * max(1.0, np.max(np.abs(q))):
            break
    jac = _residual_jacobian(p, q, phi0, clearance_joints, eccentricity)
    rhs = np.zeros(9)
    rhs[2] = p.crank_speed
    rows = {1: slice(5, 7), 2: slice(7, 9)}
    for j in clearance_joints:
        rhs[rows[j]] = rate
    y0 = np.zeros(N_STATE)
    y0[:9], y0[9:18] = q, np.linalg.solve(jac, rhs)
    return y0


def _residual_jacobian(p: FourBarParameters, q: np.ndarray, phi0: float, clearance_joints, eccentricity) -> np.ndarray:
    """d(position equations)/dq by the complex step (exact to rounding: Im f(q + i h e_k) / h, h = 1e-30)."""
    jac = np.empty((9, 9))
    for k in range(9):
        dq = np.zeros(9, dtype=complex)
        dq[k] = 1e-30j
        jac[:, k] = _position_residual(p, q + dq, phi0, clearance_joints, eccentricity).imag / 1e-30
    return jac
