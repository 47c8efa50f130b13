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
linkage of the same topology.  No text of the description reaches the source: bodies, joints and springs are named by
their index (a name chosen in config is never code).  Each effect increments its own evaluation counter, so a
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

import hashlib
import os
import sys
import types
from pathlib import Path

import numpy as np

from ... import compilecache
from .integrators import DIAG_FIXED, DIAG_PER_JOINT
from .linkage import CONTACT_LAWS, ELASTIC_LAWS, JOINT_EFFECTS, Clearance, Driver, Linkage, LinkageError, oriented

EFFECTS = (*JOINT_EFFECTS, "gravity")
#: A clearance joint's packed values, in order (``pack``): its journal and bearing points, then its properties.
CLEARANCE_VALUES = (
    "jx", "jy", "bx", "by", "clearance", "r_journal", "r_bearing", "restitution", "friction", "v0", "v1", "film",
    "eps_limit", "floor", "ceiling", "elastic_law", "elastic_stiffness", "elastic_exponent", "contact_law",
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
            restitution=c.restitution, floor=c.impact_velocity_floor, ceiling=c.impact_velocity_ceiling,
            elastic_law=float(ELASTIC_LAWS[c.elastic_law]),
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
        a(f"    # clearance joint {k}")
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
            a(f"        vimp = vimp if vimp < {P['ceiling']} else {P['ceiling']}")
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
        body = linkage.body_index(spring.point[0])
        lines.append(f"    potential += ground_spring(q, qd, cs, g, {body}, {args})  # spring {k}")
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
    """Python source of the scene's right-hand side (numba; ``rhs_into``, which the compiled integrators of
    ``integrators`` take as their ``fun``, and ``rhs``, the same as a new array for callers in Python): the linkage's
    topology, its clearance joints' effects and, if ``gravity``, gravity."""
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
    return "\n".join(L) + "\n"


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


def cache_dir() -> Path:
    """Where generated scene modules are written: <compile cache>/multibody (``linkwork.compilecache.root``)."""
    return compilecache.root() / "multibody"


def compile_scene(linkage: Linkage, gravity: bool):
    """The compiled module of a scene (its right-hand side), cached on disk by the hash of its source.

    The source holds the topology and the effects only; dimensions, properties and the elastic law are data
    (``pack``), so one compiled module serves every linkage of the same topology and effects.  The module is run from
    the source generated here, never from what the cache holds: a file whose text does not match its key (the digest
    in its name) is written anew (``_keep_file``), and no bytecode file is read (``_run_module``).
    """
    source = generate_source(linkage, gravity)
    digest = hashlib.sha256(source.encode()).hexdigest()[:16]
    name = f"linkwork_scene_{digest}"
    if name in sys.modules:
        return sys.modules[name]
    folder = cache_dir()
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / f"{name}.py"
    _keep_file(path, source)
    return _run_module(name, path, source)


def _keep_file(path: Path, source: str) -> None:
    """Make the file ``path`` hold exactly ``source``: one that is missing, unreadable or holds other text (damaged,
    edited, or written by anything else) is written anew, atomically.  numba's cache stamps the compiled code with this
    file (its time and size), so a file written anew is compiled anew."""
    try:
        same = path.read_bytes() == source.encode()
    except OSError:
        same = False
    if not same:
        tmp = path.with_suffix(f".{os.getpid()}.tmp")
        tmp.write_bytes(source.encode())
        os.replace(tmp, path)


def _run_module(name: str, path: Path, source: str) -> types.ModuleType:
    """The module ``name`` run from the text ``source`` (filed under ``path``: numba's cache and tracebacks read it
    there), registered in ``sys.modules``.  Neither the file, which may have changed since it was checked, nor a
    bytecode file beside it is read: what runs is the source whose digest names the module."""
    module = types.ModuleType(name)
    module.__file__ = str(path)
    sys.modules[name] = module
    try:
        exec(compile(source, str(path), "exec"), module.__dict__)
    except BaseException:
        del sys.modules[name]
        raise
    return module
