"""The formulation study of issue 24, first measurement: joint coordinates with the loop cut at the clearance joints,
against the engine's absolute coordinates with Baumgarte stabilisation, on two scenes (slender links: joint 2 dry,
and both joints dry; with both, the coupler is a free body (x3, y3, theta3) and the rocker turns about its pin).

With joint 2 in clearance the four-bar has no closed loop: the crank is driven, the coupler turns about the crank
pin (its angle theta3) and the rocker about its ground pin (theta4).  The state is (theta3, theta4, their rates, the
driver's work): five numbers where the engine has nineteen, no constraint to stabilise and no saddle-point solve.  The
right-hand side maps the joint coordinates to the bodies' absolute coordinates (positions, velocities and the
acceleration terms of the driven crank and the turning links), evaluates the same compiled contact and friction
kernels on them (``kernels.clearance_state`` and the rest, so the physics is the engine's), and projects the bodies'
equations onto the two angles by the velocity transformation (M_r = B^T M B, f_r = B^T (g - M gamma)); the crank
torque is the virtual work of the same equations along the crank angle.  The integrators are the engine's own
compiled DOP853 (the same source).

Method (time.perf_counter; one process, numba-compiled, compile excluded):
1. agreement: both formulations from the dead point with the journal centred, DOP853 at rtol 1e-11, sampled at 720
   points a turn over the first 0.02 turn (the first impacts): max |e_joint - e_engine| / c over the clearance joints,
   against the engine's own difference between rtol 1e-11 and 1e-12 (its floor); and the rocker acceleration and crank
   torque over the same window (max difference over the engine's range);
2. cost: each formulation from the same start, after --warm turns, --turns turns each timed alone at the pipeline's
   integrator setting and sampling (clearance.integrators.explicit, numerics.points_per_cycle): the median seconds and
   the steps a turn (the two runs part after the first impacts, as any two runs of this scene do, so their turns are
   different turns of the same state's kind, not the same turn).
Figures go to benchmarks/measured/formulation.json.
"""

from __future__ import annotations

import argparse
import hashlib
import importlib.util
import sys
from pathlib import Path

import numpy as np
import yaml

PROJECT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(PROJECT / "lib"))
sys.path.insert(0, str(Path(__file__).resolve().parent))
from _project import write_figures  # noqa: E402
from clearance_turns import timed_turns  # noqa: E402

from linkwork.engines.multibody import model  # noqa: E402
from linkwork.engines.multibody.simulate import Run  # noqa: E402
from linkwork.papers.clearance.fourbar import initial_state, start_angle  # noqa: E402
from linkwork.papers.clearance.fourbar import scene as scene_of  # noqa: E402
from linkwork.papers.clearance.adapter import parameters, scene_effects  # noqa: E402

N_REDUCED = 5  # theta3, theta4, their rates, the driver's work


#: The benchmark's own parameter layout (name, length): the four-bar's data the joint-coordinate sources read.
LAYOUT = (
    ("mass", 9), ("ground", 1), ("l", 3), ("omega", 1), ("phi0", 1), ("gravity", 1), ("clearance", 1), ("r_journal", 1),
    ("r_bearing", 1), ("restitution", 1), ("friction", 1), ("v0", 1), ("v1", 1), ("floor", 1), ("elastic_law", 1),
    ("elastic_stiffness", 1), ("elastic_exponent", 1),
)


def bench_pack(p) -> np.ndarray:
    """The four-bar's data in LAYOUT (SI, the start angle at the dead point)."""
    from linkwork.engines.multibody.linkage import ELASTIC_LAWS

    m, j = p.masses, p.inertias
    values = {
        "mass": [m[0], m[0], j[0], m[1], m[1], j[1], m[2], m[2], j[2]],
        "ground": [p.ground],
        "l": list(p.lengths),
        "omega": [p.crank_speed],
        "phi0": [start_angle(p)],
        "gravity": [p.gravity],
        "clearance": [p.clearance],
        "r_journal": [p.journal_radius],
        "r_bearing": [p.bearing_radius],
        "restitution": [p.restitution],
        "friction": [p.friction],
        "v0": [p.v0],
        "v1": [p.v1],
        "floor": [p.impact_velocity_floor],
        "elastic_law": [float(ELASTIC_LAWS[p.elastic_law])],
        "elastic_stiffness": [p.elastic_stiffness],
        "elastic_exponent": [p.elastic_exponent],
    }
    return np.array([v for name, _ in LAYOUT for v in values[name]], dtype=float)


def _names(lengths):
    """(P: a parameter's source expression by name, the contact law's code) in LAYOUT."""
    idx, at = {}, 0
    for name, n in LAYOUT:
        idx[name], at = at, at + n

    def P(name, k=0):
        return f"p[{idx[name] + k}]"

    return P, idx, model.CONTACT_LAWS["lankarani-nikravesh"]


def _head(joints: tuple[int, ...], n_state: int, P, idx) -> str:
    """Imports, constants, ``rhs`` and the start of ``rhs_into`` up to the bodies' absolute coordinates."""
    return f"""
import numpy as np
from numba import njit
from linkwork.engines.multibody.kernels import (clearance_state, hertz_damping_factor, friction_coefficient,
    elastic_contact, apply_force, body_trig)
NC = 0
N_DIAG = {model.DIAG_FIXED + model.DIAG_PER_JOINT * len(joints)}
JOINTS = {tuple(joints)}
N_WORK = 40


@njit(cache=True)
def rhs(t, y, p, latched, counts, diag):
    out = np.empty({n_state})
    rhs_into(t, y, p, latched, counts, diag, np.empty(N_WORK), out)
    return out


@njit(cache=True)
def rhs_into(t, y, p, latched, counts, diag, w, out):
    w[:] = 0.0
    q = w[0:9]
    qd = w[9:18]
    g = w[18:27]
    cs = w[27:33]
    l2, l3, l4 = {P('l')}, {P('l', 1)}, {P('l', 2)}
    om = {P('omega')}
    th2 = {P('phi0')} + om * t
    mass = p[{idx['mass']}:{idx['mass'] + 9}]
    potential = 0.0
"""


def _forces(P, law, contacts) -> str:
    """Gravity and each clearance joint's contact and friction (``contacts``: (k, journal body, its point's x, bearing
    body, its point's x)), into g, with the joints' diagnostics; after the bodies' q and qd are set."""
    out = f'''
    body_trig(q, cs)
    counts[3] += 1
    for b in range(3):
        g[3 * b + 1] -= mass[3 * b] * {P('gravity')}
        potential += mass[3 * b] * {P('gravity')} * q[3 * b + 1]
'''
    for k, bj, jx, bb, bx in contacts:
        o = model.DIAG_FIXED + model.DIAG_PER_JOINT * k
        out += f"""
    e, nx, ny, delta, ddot, vt, wj, wb, gd = clearance_state(q, qd, cs, {bj}, {jx}, 0.0, {bb}, {bx}, 0.0,
        {P('clearance')}, {P('r_journal')}, {P('r_bearing')})
    fn = 0.0
    ft = 0.0
    if delta > 0.0:
        counts[0] += 1
        vimp = latched[{k}] if latched[{k}] > {P('floor')} else {P('floor')}
        fe, ue = elastic_contact(int({P('elastic_law')}), {P('elastic_stiffness')}, {P('elastic_exponent')}, delta)
        fn = fe * hertz_damping_factor({law}, {P('restitution')}, ddot, vimp)
        potential += ue
        counts[1] += 1
        ft = friction_coefficient(vt, {P('friction')}, {P('v0')}, {P('v1')}) * fn
    fx = -fn * nx - ft * ny
    fy = -fn * ny + ft * nx
    apply_force(q, cs, g, {bj}, {jx}, 0.0, fx, fy)
    apply_force(q, cs, g, {bb}, {bx}, 0.0, -fx, -fy)
    g[{3 * bj + 2}] += {P('r_journal')} * ft
    g[{3 * bb + 2}] -= {P('r_bearing')} * ft
    diag[{o}] = e
    diag[{o + 1}] = delta
    diag[{o + 2}] = ddot
    diag[{o + 3}] = fn
    diag[{o + 4}] = 0.0
    diag[{o + 5}] = 0.0
"""
    return out


#: The tail of ``rhs_into``: energy and the fixed diagnostics (a4 and torque set before it).
_TAIL = '''
    kinetic = 0.0
    for k in range(9):
        kinetic += 0.5 * mass[k] * qd[k] * qd[k]
    diag[0] = a4
    diag[1] = torque
    diag[2] = kinetic + potential
    diag[3] = 0.0
'''


def joint_source(lengths) -> str:
    """Source of the joint-coordinate scene (joint 2 in clearance, contact, friction and gravity): rhs and rhs_into
    (which the engine's compiled integrators take), with the benchmark's parameter layout (LAYOUT)."""
    P, idx, law = _names(lengths)
    return (_head((2,), N_REDUCED, P, idx) + f'''
    th3, th4, w3, w4 = y[0], y[1], y[2], y[3]
    c2, s2, c3, s3, c4, s4 = np.cos(th2), np.sin(th2), np.cos(th3), np.sin(th3), np.cos(th4), np.sin(th4)
    # absolute coordinates of the three bodies (centres of mass at mid-link)
    q[0], q[1], q[2] = 0.5 * l2 * c2, 0.5 * l2 * s2, th2
    q[3], q[4], q[5] = l2 * c2 + 0.5 * l3 * c3, l2 * s2 + 0.5 * l3 * s3, th3
    q[6], q[7], q[8] = {P('ground')} + 0.5 * l4 * c4, 0.5 * l4 * s4, th4
    qd[0], qd[1], qd[2] = -0.5 * l2 * s2 * om, 0.5 * l2 * c2 * om, om
    qd[3], qd[4], qd[5] = -l2 * s2 * om - 0.5 * l3 * s3 * w3, l2 * c2 * om + 0.5 * l3 * c3 * w3, w3
    qd[6], qd[7], qd[8] = -0.5 * l4 * s4 * w4, 0.5 * l4 * c4 * w4, w4
''' + _forces(P, law, [(0, 1, "0.5 * l3", 2, "0.5 * l4")]) + '''
    # the bodies' accelerations at zero angular accelerations of theta3, theta4 (gamma), and their columns (B)
    gx1, gy1 = -0.5 * l2 * c2 * om * om, -0.5 * l2 * s2 * om * om
    gx2, gy2 = -l2 * c2 * om * om - 0.5 * l3 * c3 * w3 * w3, -l2 * s2 * om * om - 0.5 * l3 * s3 * w3 * w3
    gx3, gy3 = -0.5 * l4 * c4 * w4 * w4, -0.5 * l4 * s4 * w4 * w4
    b3x, b3y = -0.5 * l3 * s3, 0.5 * l3 * c3
    b4x, b4y = -0.5 * l4 * s4, 0.5 * l4 * c4
    m2, j2, m3, j3 = mass[3], mass[5], mass[6], mass[8]
    # theta3 moves only the coupler, theta4 only the rocker: B^T M B is diagonal
    a3 = ((g[3] - m2 * gx2) * b3x + (g[4] - m2 * gy2) * b3y + g[5]) / (m2 * (b3x * b3x + b3y * b3y) + j2)
    a4 = ((g[6] - m3 * gx3) * b4x + (g[7] - m3 * gy3) * b4y + g[8]) / (m3 * (b4x * b4x + b4y * b4y) + j3)
    # the crank torque: the virtual work of (M qdd - g) along the crank angle (theta3, theta4 held)
    ax2, ay2 = gx2 + b3x * a3, gy2 + b3y * a3
    torque = (mass[0] * gx1 - g[0]) * (-0.5 * l2 * s2) + (mass[1] * gy1 - g[1]) * (0.5 * l2 * c2) - g[2] \\
        + (m2 * ax2 - g[3]) * (-l2 * s2) + (m2 * ay2 - g[4]) * (l2 * c2)
    out[0], out[1], out[2], out[3] = w3, w4, a3, a4
    out[4] = torque * om
''' + _TAIL)


def joint_source_both(lengths) -> str:
    """Source of the joint-coordinate scene with both joints in clearance (contact, friction, gravity): the coupler is
    free (x3, y3, theta3), the rocker turns about its ground pin (theta4); state (x3, y3, theta3, theta4, their rates,
    the driver's work)."""
    P, idx, law = _names(lengths)
    return (_head((1, 2), 9, P, idx) + f'''
    th4, w4 = y[3], y[7]
    c2, s2, c4, s4 = np.cos(th2), np.sin(th2), np.cos(th4), np.sin(th4)
    q[0], q[1], q[2] = 0.5 * l2 * c2, 0.5 * l2 * s2, th2
    q[3], q[4], q[5] = y[0], y[1], y[2]
    q[6], q[7], q[8] = {P('ground')} + 0.5 * l4 * c4, 0.5 * l4 * s4, th4
    qd[0], qd[1], qd[2] = -0.5 * l2 * s2 * om, 0.5 * l2 * c2 * om, om
    qd[3], qd[4], qd[5] = y[4], y[5], y[6]
    qd[6], qd[7], qd[8] = -0.5 * l4 * s4 * w4, 0.5 * l4 * c4 * w4, w4
''' + _forces(P, law, [(0, 0, "0.5 * l2", 1, "-0.5 * l3"), (1, 1, "0.5 * l3", 2, "0.5 * l4")]) + '''
    gx1, gy1 = -0.5 * l2 * c2 * om * om, -0.5 * l2 * s2 * om * om
    gx3, gy3 = -0.5 * l4 * c4 * w4 * w4, -0.5 * l4 * s4 * w4 * w4
    b4x, b4y = -0.5 * l4 * s4, 0.5 * l4 * c4
    m3, j3 = mass[6], mass[8]
    a4 = ((g[6] - m3 * gx3) * b4x + (g[7] - m3 * gy3) * b4y + g[8]) / (m3 * (b4x * b4x + b4y * b4y) + j3)
    torque = (mass[0] * gx1 - g[0]) * (-0.5 * l2 * s2) + (mass[1] * gy1 - g[1]) * (0.5 * l2 * c2) - g[2]
    out[0], out[1], out[2], out[3] = y[4], y[5], y[6], w4
    out[4], out[5], out[6], out[7] = g[3] / mass[3], g[4] / mass[4], g[5] / mass[5], a4
    out[8] = torque * om
''' + _TAIL)


def compile_joint(lengths, both: bool = False):
    """The joint-coordinate scene module (cached like the engine's scenes): joint 2 in clearance, or both."""
    source = joint_source_both(lengths) if both else joint_source(lengths)
    name = "linkwork_joint_" + hashlib.sha256(source.encode()).hexdigest()[:16]
    folder = model.cache_dir()
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / f"{name}.py"
    if not path.exists() or path.read_text() != source:
        path.write_text(source)
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    spec.loader.exec_module(module)
    return module


class JointRun(Run):
    """A run of the joint-coordinate scene with the engine's Run interface (its state: the reduced one)."""

    def __init__(self, p, integrator, y_engine, joints=(2,)):
        super().__init__(*scene_of(p, joints, ("contact", "friction", "gravity")), integrator, y0=y_engine)
        both = tuple(joints) == (1, 2)
        self.module = compile_joint(p.lengths, both)
        self.params = bench_pack(p)
        self.y = reduced_both(y_engine) if both else reduced(y_engine)


def reduced(y_engine: np.ndarray) -> np.ndarray:
    """The joint-coordinate state of an engine state (joint 1 closed): theta3, theta4, their rates, the work."""
    return np.array([y_engine[5], y_engine[8], y_engine[14], y_engine[17], y_engine[18]])


def reduced_both(y_engine: np.ndarray) -> np.ndarray:
    """The state of the both-joints topology from an engine state: the coupler's (x, y, phi), theta4, their rates,
    the work."""
    return np.array([*y_engine[3:6], y_engine[8], *y_engine[12:15], y_engine[17], y_engine[18]])


def eccentricity(module_diags: np.ndarray) -> np.ndarray:
    """|e| (m) of joint 2 from a run's diagnostics."""
    return module_diags[:, 4]


def measure(section, scene: str, warm: int, turns: int) -> dict[str, object]:
    """Agreement over the first impacts and the cost of a turn, engine against joint coordinates, for one scene."""
    p = parameters(section, "slender", scene)
    joints, effects = scene_effects(section, scene)
    y0 = initial_state(p, joints)
    period = 2 * np.pi / p.crank_speed
    tight = {"method": "dop853", "rtol": 1e-11, "atol": 1e-14, "first_step_s": 1e-7, "max_step_s": 1e-3}
    tighter = {**tight, "rtol": 1e-12, "atol": 1e-15}
    t = np.linspace(0.0, 0.02 * period, int(0.02 * 720) + 1)
    _, d_engine = Run(*scene_of(p, joints, effects), tight, y0=y0).advance(t)
    _, d_engine2 = Run(*scene_of(p, joints, effects), tighter, y0=y0).advance(t)
    _, d_joint = JointRun(p, tight, y0, joints).advance(t)
    c = p.clearance
    ecc = [4 + model.DIAG_PER_JOINT * k for k in range(len(joints))]  # |e| of each clearance joint
    agreement = {
        "eccentricity_vs_engine_over_c": float(np.max(np.abs(d_joint[:, ecc] - d_engine[:, ecc])) / c),
        "engine_floor_over_c": float(np.max(np.abs(d_engine2[:, ecc] - d_engine[:, ecc])) / c),
        "rocker_acceleration_vs_engine": float(np.max(np.abs(d_joint[:, 0] - d_engine[:, 0])) / np.ptp(d_engine[:, 0])),
        "crank_torque_vs_engine": float(np.max(np.abs(d_joint[:, 1] - d_engine[:, 1])) / np.ptp(d_engine[:, 1])),
    }
    print(scene, agreement, flush=True)
    integ = section["integrators"]["explicit"]
    per = section["numerics"]["points_per_cycle"]
    cost = {}
    for name, run in (
        ("engine", Run(*scene_of(p, joints, effects), integ, y0=y0)),
        ("joint", JointRun(p, integ, y0, joints)),
    ):
        timed_turns(run, period, per, warm)
        cost[name] = timed_turns(run, period, per, turns)
        print(scene, name, cost[name], flush=True)
    cost["speedup"] = cost["engine"]["s_per_turn"] / cost["joint"]["s_per_turn"]
    return {
        "agreement": agreement,
        "cost": cost,
        "states": {"engine": 19, "joint": int(JointRun(p, integ, y0, joints).y.size)},
    }


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--warm", type=int, default=20)
    parser.add_argument("--turns", type=int, default=5)
    args = parser.parse_args()
    section = yaml.safe_load((PROJECT / "config" / "config.yaml").read_text())["clearance"]
    scenes = {f"slender/{s}": measure(section, s, args.warm, args.turns) for s in ("dry_2", "dry_both")}
    write_figures("formulation", {"scenes": scenes, "warm_turns": args.warm, "timed_turns": args.turns},
                  __doc__.split("Method", 1)[1].split("Figures go")[0])


if __name__ == "__main__":
    main()
