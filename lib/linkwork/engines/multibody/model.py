"""A planar linkage with ideal and clearance revolute joints as a multibody system, generated from its description.

Formulation (the clearance paper's eqs. 1-3, for any linkage of ``linkage.Linkage``): bodies in (x, y, phi) at their
centres of mass; ideal revolutes and the driver are constraints, M q'' = g - Phi_q^T lambda,
Phi_q q'' = gamma - 2 alpha Phi' - beta^2 Phi (Baumgarte).  M is diagonal, so lambda comes from the small Schur
complement Phi_q M^-1 Phi_q^T.  The driver torque is -lambda of the driver row.

A clearance joint is not a constraint but a force element between a journal (on the joint's first body) and a
bearing (on its second).  Each clearance joint names its effects; the right-hand side is generated as source code
containing exactly those effects (no branch, no call for an effect left out), compiled by numba and cached on disk by
the hash of its source.  The source holds the topology only (which bodies each joint joins, which effects act
where); every dimension and property is data in the packed parameters (``pack``), so one compiled scene serves every
linkage of the same topology.  Each effect increments its own evaluation counter, so a
test can prove that an effect left out is never evaluated.

The dry contact's elastic law (ELASTIC_LAWS: the sphere law of eq. 9, or a conformal cylindrical law) is chosen
apart from its hysteresis damping (CONTACT_LAWS); both are data, not generated code: a scene compiled once serves
every law (the kernels branch on the law's number).

Sign conventions resolved here (the clearance paper's printed model differs):
* eccentricity e = journal centre - bearing centre, n = e/|e|; the dry contact force on the
  journal is -F_N n, i.e. it pushes the journal back into the bearing (eqs. 4/17 as printed push
  it outward);
* the wedge term uses omega_journal + omega_bearing - 2 gamma' in the fixed frame (eq. 22 speaks of
  "the relative angular velocity", but both elements rotate);
* the film force is capped at the eccentricity ratio eps_limit = 1 - e0/c: continuous and bounded
  up to and past eps = 1, where the dry contact takes over (eq. 23 as printed is infinite at e = c).
"""

from __future__ import annotations

import fcntl
import hashlib
import importlib.util
import os
import sys
from pathlib import Path

import numpy as np

from ... import compilecache
from .linkage import CONTACT_LAWS, ELASTIC_LAWS, JOINT_EFFECTS, Clearance, Driver, Linkage, LinkageError, oriented

EFFECTS = (*JOINT_EFFECTS, "gravity")
DIAG_FIXED = 4  # output body's angular acceleration, driver torque, energy, constraint drift
DIAG_PER_JOINT = 6  # e, delta, delta', dry normal force, film radial force, film tangential force
#: A clearance joint's packed values, in order (``pack``): its journal and bearing points, then its properties.
CLEARANCE_VALUES = (
    "jx", "jy", "bx", "by", "clearance", "r_journal", "r_bearing", "restitution", "friction", "v0", "v1", "film",
    "eps_limit", "floor", "elastic_law", "elastic_stiffness", "elastic_exponent", "contact_law",
)


def n_state(linkage: Linkage) -> int:
    """Length of a scene's state: q (3 nb), q' (3 nb) and the driver's work (1)."""
    return 2 * linkage.n_coordinates + 1


def check_effects(name: str, effects) -> None:
    """A clearance joint's effects: known ones, friction only with contact (it acts with the normal force)."""
    unknown = set(effects) - set(JOINT_EFFECTS)
    if unknown:
        raise LinkageError(
            f"joints.{name}.clearance.effects", f"unknown effect(s) {sorted(unknown)}; known: {JOINT_EFFECTS}"
        )
    if "friction" in effects and "contact" not in effects:
        raise LinkageError(
            f"joints.{name}.clearance.effects",
            "friction needs the contact effect (it acts with the normal contact force)",
        )


def _clearance_values(linkage: Linkage, joint) -> list[float]:
    """A clearance joint's packed values (CLEARANCE_VALUES); those of effects it does not name are NaN."""
    c: Clearance = joint.clearance
    nan = float("nan")
    fx = set(c.effects)
    v = dict.fromkeys(CLEARANCE_VALUES, nan)
    (v["jx"], v["jy"]), (v["bx"], v["by"]) = linkage.point(joint.journal), linkage.point(joint.bearing)
    v.update(clearance=c.clearance, r_journal=c.journal_radius, r_bearing=c.bearing_radius)
    if "contact" in fx:
        v.update(
            restitution=c.restitution, floor=c.impact_velocity_floor, elastic_law=float(ELASTIC_LAWS[c.elastic_law]),
            elastic_stiffness=c.elastic_stiffness, elastic_exponent=c.elastic_exponent,
            contact_law=float(CONTACT_LAWS[c.contact_law]),
        )
    if "friction" in fx:
        v.update(friction=c.friction, v0=c.v0, v1=c.v1)
    if "lubrication" in fx:
        v.update(film=c.film_coefficient, eps_limit=1.0 - c.e0 / c.clearance)
    return [float(v[k]) for k in CLEARANCE_VALUES]


def pack(linkage: Linkage) -> tuple[np.ndarray, dict[str, int]]:
    """The linkage's data as one float array for the compiled code, with the index of every block by name.  The
    layout depends on the topology only, so the generated source (which holds indices) does too."""
    d = linkage.driver
    values: dict[str, list[float]] = {
        "mass": [v for b in linkage.bodies for v in (b.mass, b.mass, b.inertia)],
        "gravity": [linkage.gravity], "alpha": [linkage.baumgarte], "beta": [linkage.baumgarte],
        "omega": [d.speed], "phi0": [d.start_angle], "series": [*d.cos, *d.sin],
    }
    for k, item in enumerate(linkage.constraint_order()):
        if isinstance(item, Driver):
            continue
        first, second = oriented(item)
        gx, gy = linkage.point(second) if second[0] == "ground" else (0.0, 0.0)
        s2 = (0.0, 0.0) if second[0] == "ground" else linkage.point(second)
        values[f"joint{k}"] = [*linkage.point(first), *s2, gx, gy]
    for k, joint in enumerate(linkage.clearance_joints):
        values[f"clearance{k}"] = _clearance_values(linkage, joint)
    for k, spring in enumerate(linkage.springs):
        values[f"spring{k}"] = [*linkage.point(spring.point), *spring.rest, *spring.stiffness, *spring.damping]
    index, flat = {}, []
    for key, vals in values.items():
        index[key] = len(flat)
        flat.extend(vals)
    return np.array(flat, dtype=float), index


def _constraint_lines(linkage: Linkage, idx) -> tuple[list[str], list[list[int]], int]:
    """Source lines of the constraint rows (the ideal joints and the driver, in ``constraint_order``), their Phi_q
    pattern and the driver's row."""
    lines, pattern, row, driver_row = [], [], 0, 0
    for k, item in enumerate(linkage.constraint_order()):
        if isinstance(item, Driver):
            b = linkage.body_index(item.body)
            if item.cos or item.rocking:
                n = len(item.cos)
                s = idx["series"]
                kernel = "driver_rocking" if item.rocking else "driver_series"
                lines.append(f"    {kernel}(q, qd, t, {b}, p[{idx['phi0']}], p[{idx['omega']}], p[{s}:{s + n}], "
                             f"p[{s + n}:{s + 2 * n}], {row}, phi, phiq, gamma, phidot)")
            else:
                lines.append(
                    f"    driver(q, qd, t, {b}, p[{idx['phi0']}], p[{idx['omega']}], {row}, phi, phiq, gamma, phidot)"
                )
            pattern.append([3 * b + 2])
            driver_row = row
            row += 1
            continue
        first, second = oriented(item)
        bi, bj = linkage.body_index(first[0]), linkage.body_index(second[0])
        six, siy, sjx, sjy, gx, gy = (f"p[{idx[f'joint{k}'] + m}]" for m in range(6))
        lines.append(
            f"    revolute(q, qd, cs, {bi}, {six}, {siy}, {bj}, {sjx}, {sjy}, {gx}, {gy}, {row}, phi, phiq, gamma,"
            " phidot)"
        )
        pattern += revolute_pattern(bi, bj)
        row += 2
    return lines, pattern, driver_row


def _clearance_lines(linkage: Linkage, idx) -> list[str]:
    """Source lines of the clearance joints' forces: exactly the effects each joint names."""
    L: list[str] = []
    a = L.append
    for k, joint in enumerate(linkage.clearance_joints):
        c = joint.clearance
        o = idx[f"clearance{k}"]
        P = {name: f"p[{o + m}]" for m, name in enumerate(CLEARANCE_VALUES)}
        bj, bb = linkage.body_index(joint.journal[0]), linkage.body_index(joint.bearing[0])
        jx, jy, bx, by = P["jx"], P["jy"], P["bx"], P["by"]
        d = DIAG_FIXED + DIAG_PER_JOINT * k
        a(f"    # clearance joint {joint.name}")
        a(
            f"    e, nx, ny, delta, ddot, vt, wj, wb, gd = clearance_state(q, qd, cs, {bj}, {jx}, {jy}, {bb}, {bx},"
            f" {by}, {P['clearance']}, {P['r_journal']}, {P['r_bearing']})"
        )
        a("    fn = 0.0")
        a("    ft = 0.0")
        a("    fr_film = 0.0")
        a("    ft_film = 0.0")
        if "contact" in c.effects:
            a("    if delta > 0.0:")
            a("        counts[0] += 1")
            a(f"        vimp = latched[{k}] if latched[{k}] > {P['floor']} else {P['floor']}")
            a(
                f"        fe, ue = elastic_contact(int({P['elastic_law']}), {P['elastic_stiffness']},"
                f" {P['elastic_exponent']}, delta)"
            )
            a(f"        fn = fe * hertz_damping_factor(int({P['contact_law']}), {P['restitution']}, ddot, vimp)")
            a("        potential += ue")
            if "friction" in c.effects:
                a("        counts[1] += 1")
                a(f"        ft = friction_coefficient(vt, {P['friction']}, {P['v0']}, {P['v1']}) * fn")
        if "lubrication" in c.effects:
            a("    counts[2] += 1")
            a(
                f"    fr_film, ft_film = film_forces(e / {P['clearance']}, ddot / {P['clearance']}, wj + wb, gd,"
                f" {P['film']}, {P['eps_limit']})"
            )
        a("    tx, ty = -ny, nx")
        a("    fx = (-fn + fr_film) * nx + (ft + ft_film) * tx")
        a("    fy = (-fn + fr_film) * ny + (ft + ft_film) * ty")
        a(f"    apply_force(q, cs, g, {bj}, {jx}, {jy}, fx, fy)")
        a(f"    apply_force(q, cs, g, {bb}, {bx}, {by}, -fx, -fy)")
        if "friction" in c.effects:
            a(f"    g[{3 * bj + 2}] += {P['r_journal']} * ft")
            a(f"    g[{3 * bb + 2}] -= {P['r_bearing']} * ft")
        for m, val in enumerate(("e", "delta", "ddot", "fn", "fr_film", "ft_film")):
            a(f"    diag[{d + m}] = {val}")
    return L


def _spring_lines(linkage: Linkage, idx) -> list[str]:
    """Source lines of the springs: each adds its force and its potential energy."""
    lines = []
    for k, spring in enumerate(linkage.springs):
        o = idx[f"spring{k}"]
        args = ", ".join(f"p[{o + m}]" for m in range(8))
        lines.append(
            f"    potential += ground_spring(q, qd, cs, g, {linkage.body_index(spring.point[0])}, {args})  # spring"
            f" {spring.name}"
        )
    return lines


def _check_topology(linkage: Linkage) -> None:
    for joint in linkage.clearance_joints:
        check_effects(joint.name, joint.clearance.effects)
        if joint.clearance.contact_law not in CONTACT_LAWS:
            raise LinkageError(f"joints.{joint.name}.clearance.contact_law",
                               f"unknown contact law {joint.clearance.contact_law!r}; known: {sorted(CONTACT_LAWS)}")
        if "ground" in (joint.journal[0], joint.bearing[0]):
            raise LinkageError(
                f"joints.{joint.name}",
                "a clearance joint with the ground is not supported yet (journal and bearing must be bodies)",
            )


#: The compiled kernels every generated scene calls (kernels.py, beside this file).
KERNELS = Path(__file__).with_name("kernels.py")


def kernels_fingerprint() -> str:
    """sha256 of kernels.py's text.  numba checks a cached function against its own file only, not against the files
    of the functions it calls, so a scene compiled before an edit of kernels.py would keep the old kernels: the
    generated source carries this fingerprint, and a new fingerprint is a new source, a new module and a new compile."""
    return hashlib.sha256(KERNELS.read_bytes()).hexdigest()


def generate_source(linkage: Linkage, gravity: bool) -> str:
    """Python source of the scene's right-hand side and integrators (numba): the linkage's topology, its clearance
    joints' effects and, if ``gravity``, gravity."""
    _check_topology(linkage)
    _, idx = pack(linkage)
    nb = len(linkage.bodies)
    nq = 3 * nb
    joints = linkage.clearance_joints
    constraint_lines, pattern, driver_row = _constraint_lines(linkage, idx)
    nc = len(pattern)
    out_b, drv_b = linkage.body_index(linkage.output), linkage.body_index(linkage.driver.body)
    L: list[str] = []
    a = L.append
    a(f"# compiled against kernels.py of sha256 {kernels_fingerprint()}")
    a("import numpy as np")
    a("from numba import njit")
    a("from linkwork.engines.multibody.kernels import (revolute, driver, driver_series, apply_force, clearance_state,")
    if linkage.springs or linkage.driver.rocking:
        a("    driver_rocking, ground_spring,")
    a("    hertz_damping_factor, friction_coefficient, film_forces, gauss_solve_into, elastic_contact, body_trig)")
    a(f"NB = {nb}")
    a(f"NQ = {nq}")
    a(f"NY = {2 * nq + 1}")
    a(f"NC = {nc}")
    a(f"N_DIAG = {DIAG_FIXED + DIAG_PER_JOINT * len(joints)}")
    a(f"JOINTS = {tuple(j.name for j in joints)}")
    scene_effects = [
        e for e in EFFECTS if any(e in j.clearance.effects for j in joints) or (e == "gravity" and gravity)
    ]
    a(f"EFFECTS = {tuple(scene_effects)}")
    a("")
    a(f"N_WORK = {5 * nb + nc * (6 + nq + nc)}")
    a("")
    a("@njit(cache=True)")
    a("def rhs(t, y, p, latched, counts, diag):")
    a("    \"\"\"dy/dt at (t, y), a new array; the diagnostics into ``diag`` (see rhs_into).\"\"\"")
    a("    out = np.empty(NY)")
    a("    rhs_into(t, y, p, latched, counts, diag, np.empty(N_WORK), out)")
    a("    return out")
    a("")
    a("@njit(cache=True)")
    a("def rhs_into(t, y, p, latched, counts, diag, w, out):")
    a("    \"\"\"dy/dt at (t, y) into ``out`` (NY), the diagnostics into ``diag``; ``w``: a work array of N_WORK,")
    a('    cleared here and cut into the pieces below (the integrators pass one, so that a call allocates nothing)."""')
    a("    q = y[0:NQ]")
    a("    qd = y[NQ : 2 * NQ]")
    a("    w[:] = 0.0")
    a(f"    cs = w[0:{2 * nb}]")
    a("    body_trig(q, cs)")
    a(f"    g = w[{2 * nb}:{5 * nb}]")
    o = 5 * nb
    for k, name in enumerate(("phi", "gamma", "phidot", "gamma_b", "schur_rhs", "lam")):
        a(f"    {name} = w[{o + k * nc} : {o + (k + 1) * nc}]")
    o += 6 * nc
    a(f"    phiq = w[{o} : {o + nq * nc}].reshape((NC, NQ))")
    a(f"    schur = w[{o + nq * nc} :].reshape((NC, NC))")
    a(f"    mass = p[{idx['mass']}:{idx['mass'] + nq}]")
    a("    potential = 0.0")
    if gravity:
        a("    counts[3] += 1")
        a("    for b in range(NB):")
        a(f"        g[3 * b + 1] -= mass[3 * b] * p[{idx['gravity']}]")
        a(f"        potential += mass[3 * b] * p[{idx['gravity']}] * q[3 * b + 1]")
    L.extend(_clearance_lines(linkage, idx))
    L.extend(_spring_lines(linkage, idx))
    L.extend(constraint_lines)
    a(f"    damping = 2.0 * p[{idx['alpha']}]")
    a(f"    stiffness = p[{idx['beta']}] ** 2")
    a("    for r in range(NC):")
    a("        gamma_b[r] = gamma[r] - damping * phidot[r] - stiffness * phi[r]")
    a("    out[0:NQ] = qd")
    a("    qdd = out[NQ : 2 * NQ]")
    L.extend(schur_source(pattern, nq))
    a(f"    torque = -lam[{driver_row}]")
    a(f"    out[{2 * nq}] = torque * qd[{3 * drv_b + 2}]")
    a("    kinetic = 0.0")
    a("    for k in range(NQ):")
    a("        kinetic += 0.5 * mass[k] * qd[k] * qd[k]")
    a(f"    diag[0] = qdd[{3 * out_b + 2}]")
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
    return [
        sorted(c for b in bodies for c in (3 * b, 3 * b + 2)),
        sorted(c for b in bodies for c in (3 * b + 1, 3 * b + 2)),
    ]


def schur_source(pattern: list[list[int]], nq: int) -> list[str]:
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
    for k in range(nq):
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
            y6 = y + hh * (a61 * k1 + a62 * k2 + a63 * k3 + a64 * k4 + a65 * k5)
            k6 = rhs(t + hh, y6, p, latched, counts, scratch)
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
        min_step = 10.0 * (np.nextafter(t, np.inf) - t)  # as scipy: ten units in the last place of t
        if h_abs < min_step:  # as scipy: a step below it (a cut's rounding-size remainder) is raised to it
            _ndf_change(D, order, min_step / h_abs)
            h_abs = min_step
            n_equal = 0
            inv_ok = False
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


def cache_dir() -> Path:
    """Where generated scene modules are written: <compile cache>/multibody (``linkwork.compilecache.root``)."""
    return compilecache.root() / "multibody"


def compile_scene(linkage: Linkage, gravity: bool):
    """The compiled module of a scene (rhs, integrators), cached on disk by the hash of its source.

    The source holds the topology and the effects only; dimensions, properties and the elastic law are data
    (``pack``), so one compiled module serves every linkage of the same topology and effects.
    """
    source = generate_source(linkage, gravity)
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


def compiled_for(module, method: str, args: tuple) -> None:
    """Compile ``module.<method>`` for the types of ``args`` (or load it from the cache), one process at a time.

    A process that finds another compiling the same function of the same scene module waits for it, then loads the
    result from the cache instead of compiling it again: two jobs of one scene type started together used to compile
    it twice.  Once compiled in this process, nothing is locked.  The call then runs what a lazy compile would have
    built: the same signature, the same machine code.
    """
    import numba

    dispatcher = getattr(module, method)
    signature = tuple(numba.typeof(a) for a in args)
    if signature in dispatcher.overloads:
        return
    with open(cache_dir() / f"{module.__name__}.{method}.lock", "a") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        try:
            dispatcher.compile(signature)
        finally:
            fcntl.flock(lock, fcntl.LOCK_UN)
