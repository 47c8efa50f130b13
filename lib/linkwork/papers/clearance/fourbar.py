"""The clearance paper's mechanism: a four-bar whose two moving joints may have a clearance, as an instance of the
multibody engine's linkage description (``engines.multibody.linkage``).

The paper's parameter set (``FourBarParameters``: the link lengths, the bodies, one set of joint materials and
effects for both joints, the crank at constant speed) is turned into a ``Linkage`` with joints O2 (crank at the
ground), A (crank pin in the coupler's bushing, the paper's joint 1), B (coupler pin in the rocker's bushing, joint 2)
and O4 (rocker at the ground); every body's centre of mass at mid-link.  The run starts at the paper's dead point
(crank and coupler extended), with the crank driven from that angle.  Everything else (assembly, kinematics, inverse
dynamics, the generated right-hand side) is the engine's, as for any linkage.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from ...engines.kinematics import FourBar, toggle_positions
from ...engines.multibody import assembly, simulate
from ...engines.multibody.linkage import Body, Clearance, Driver, Joint, Linkage
from ...units import STANDARD_GRAVITY

#: The paper's joint numbers and the description's joint names.
JOINT_NAMES = {1: "A", 2: "B"}
BODY_NAMES = ("crank", "coupler", "rocker")
#: Length of a run's state: the bodies' coordinates and their rates, and the driver's work (``model.n_state``).
N_STATE = 2 * 3 * len(BODY_NAMES) + 1


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
    elastic_law: str = "hertz-sphere"  # "pereira" reads joint_length
    fixed_impact_velocity: float = float("nan")  # m/s: NaN, the velocity latched at each impact; else memory-free

    def joint(self, effects=("contact", "friction", "lubrication")) -> Clearance:
        """The clearance of either joint with the given effects (the paper gives one set for both)."""
        return Clearance(
            self.journal_radius, self.bearing_radius, tuple(e for e in effects if e != "gravity"), self.youngs_modulus,
            self.poisson, self.restitution, self.contact_law, self.elastic_law, self.friction, self.v0, self.v1,
            self.viscosity, self.joint_length, self.e0, *self.impact_velocity_bounds,
        )

    @property
    def impact_velocity_bounds(self) -> tuple[float, float]:
        """(floor, ceiling) of the contact damping's impact velocity, m/s: the floor and no ceiling (the velocity
        latched at each impact, the paper's law), or both the fixed velocity (a memory-free damping)."""
        fixed = self.fixed_impact_velocity
        return (fixed, fixed) if np.isfinite(fixed) else (self.impact_velocity_floor, float("inf"))

    @property
    def clearance(self) -> float:
        return self.bearing_radius - self.journal_radius

    @property
    def hertz_stiffness(self) -> float:
        return self.joint().hertz_stiffness

    @property
    def effective_modulus(self) -> float:
        return self.joint().effective_modulus

    @property
    def elastic_exponent(self) -> float:
        return self.joint().elastic_exponent

    @property
    def elastic_stiffness(self) -> float:
        return self.joint().elastic_stiffness

    @property
    def film_coefficient(self) -> float:
        return self.joint().film_coefficient

    def four_bar(self) -> FourBar:
        l2, l3, l4 = self.lengths
        return FourBar(crank=l2, coupler=l3, rocker=l4, ground=self.ground, branch=self.branch)


def start_angle(p: FourBarParameters) -> float:
    """Crank angle (rad) with crank and coupler collinear (extended): the rocker's dead point, where runs start."""
    return float(toggle_positions(p.four_bar()).crank_angle[0])


def linkage(p: FourBarParameters, joints=(), effects=()) -> Linkage:
    """The four-bar as a linkage description; the joints in ``joints`` (1, 2) have a clearance with the scene's
    ``effects`` (gravity is the linkage's, not a joint's).  The bodies' guessed angles are the closed-form ones at the
    dead point (the branch ``p.branch``)."""
    l2, l3, l4 = p.lengths
    phi0 = start_angle(p)
    from ...engines.kinematics import four_bar

    m = four_bar(p.four_bar(), np.array([phi0]))
    guesses = (phi0, float(m.coupler_angle[0]), float(m.rocker_angle[0]))
    points = ({"O": (-l2 / 2, 0.0), "A": (l2 / 2, 0.0)}, {"A": (-l3 / 2, 0.0), "B": (l3 / 2, 0.0)},
              {"O": (-l4 / 2, 0.0), "B": (l4 / 2, 0.0)})
    bodies = tuple(Body(name, mass, inertia, pts, guess) for name, mass, inertia, pts, guess
                   in zip(BODY_NAMES, p.masses, p.inertias, points, guesses, strict=True))
    pins = {1: (("crank", "A"), ("coupler", "A")), 2: (("coupler", "B"), ("rocker", "B"))}
    order = [*joints, *[j for j in (1, 2) if j not in joints]]
    moving = tuple(Joint(JOINT_NAMES[j], *pins[j], p.joint(effects) if j in joints else None) for j in order)
    ground = (Joint("O2", ("crank", "O"), ("ground", "O2")), Joint("O4", ("rocker", "O"), ("ground", "O4")))
    return Linkage(
        bodies, {"O2": (0.0, 0.0), "O4": (p.ground, 0.0)}, (*ground, *moving), Driver("crank", p.crank_speed, phi0),
        output="rocker", gravity=p.gravity, baumgarte=p.baumgarte_alpha,
    )


def _ideal(p: FourBarParameters) -> Linkage:
    """The four-bar with both joints ideal; the Baumgarte constant is not read by the kinematics."""
    return linkage(p)


#: The ideal scene's responses already computed in this process, by the linkage's data and the times: a batch of
#: samples that move only joint inputs (the ideal joints do not read them) computes its ideal turn once.
_IDEAL: dict[tuple, dict[str, np.ndarray]] = {}


def inverse_dynamics(p: FourBarParameters, t: np.ndarray, gravity: bool) -> dict[str, np.ndarray]:
    """The ideal scene at the times t (s): rocker angular acceleration (rad/s^2), crank torque (N m), the reaction
    magnitudes at A and B (N) and the mechanical energy (J), by the engine's inverse dynamics."""
    t = np.asarray(t, dtype=float)
    key = (p.ground, p.lengths, p.masses, p.inertias, p.crank_speed, p.gravity, p.branch, bool(gravity), t.tobytes())
    if key not in _IDEAL:
        out = assembly.inverse_dynamics(_ideal(p), t, gravity)
        _IDEAL.clear()  # one entry: the batches repeat the last one
        _IDEAL[key] = {"rocker_acceleration": out["output_acceleration"], "crank_torque": out["driver_torque"],
                       "force_A": out["force_A"], "force_B": out["force_B"], "energy": out["energy"]}
    return {k: v.copy() for k, v in _IDEAL[key].items()}


def kinematic_state(p: FourBarParameters, crank_angle: np.ndarray):
    """Positions q, velocities q' and accelerations q'' (n, 9) each of the ideal four-bar at the crank angles (rad), by
    its closed-form kinematics (``engines.kinematics.four_bar``): the paper's start, and a second route for the
    engine's assembly (tests/test_clearance.py)."""
    from ...engines.kinematics import four_bar

    m = four_bar(p.four_bar(), crank_angle)
    w = p.crank_speed
    l2, l3, l4 = p.lengths
    ang = np.stack([m.crank_angle, m.coupler_angle, m.rocker_angle], axis=-1)
    rate = np.stack([np.ones_like(m.crank_angle), m.coupler_rate, m.rocker_rate], axis=-1) * w
    acc = np.stack([np.zeros_like(m.crank_angle), m.coupler_accel, m.rocker_accel], axis=-1) * w**2
    starts = [np.zeros_like(m.A), m.A, np.broadcast_to(p.four_bar().rocker_pivot, m.A.shape)]
    half = [l2 / 2, l3 / 2, l4 / 2]
    q = np.empty(ang.shape[:-1] + (9,))
    qd, qdd = np.empty_like(q), np.empty_like(q)
    for b in range(3):
        e = np.stack([np.cos(ang[..., b]), np.sin(ang[..., b])], axis=-1)
        perp = np.stack([-e[..., 1], e[..., 0]], axis=-1)
        start_vel = (
            np.zeros_like(e) if b != 1 else l2 * w * np.stack([-np.sin(ang[..., 0]), np.cos(ang[..., 0])], axis=-1)
        )
        start_acc = (
            np.zeros_like(e) if b != 1 else -l2 * w**2 * np.stack([np.cos(ang[..., 0]), np.sin(ang[..., 0])], axis=-1)
        )
        q[..., 3 * b : 3 * b + 2] = starts[b] + half[b] * e
        q[..., 3 * b + 2] = ang[..., b]
        qd[..., 3 * b : 3 * b + 2] = start_vel + half[b] * rate[..., b, None] * perp
        qd[..., 3 * b + 2] = rate[..., b]
        qdd[..., 3 * b : 3 * b + 2] = start_acc + half[b] * (acc[..., b, None] * perp - rate[..., b, None] ** 2 * e)
        qdd[..., 3 * b + 2] = acc[..., b]
    return q, qd, qdd


def initial_state(p: FourBarParameters, joints=(), offset: tuple[float, float] = (0.0, 0.0)) -> np.ndarray:
    """The paper's start: the dead point, journals centred, by the closed-form kinematics (the engine's assembly gives
    the same state to rounding, tests/test_clearance.py, but rounding decides which of coexisting states some dry
    scenes settle into, so the start is kept exactly as the results were made with); the coupler's centre then moved
    by ``offset`` (m).  ``joints``: the scene's clearance joints (the state's layout does not depend on them)."""
    q, qd, _ = kinematic_state(p, np.array([start_angle(p)]))
    y0 = np.zeros(N_STATE)
    y0[:9], y0[9:18] = q[0], qd[0]
    y0[3] += offset[0]
    y0[4] += offset[1]
    return y0


def offset_start(p: FourBarParameters, joints, eccentricity, rate, tol: float = 1e-15) -> np.ndarray:
    """The paper's off-centre start: at the dead point with every clearance joint's journal at ``eccentricity`` (m,
    (x, y)) and moving at ``rate`` (m/s) relative to its bearing, the ground pins, the drive and the ideal joints exact:
    positions by Newton's method on the nine position equations from the closed-form state, velocities from the same
    equations' rate form, both with the complex-step Jacobian (the engine's ``assembly.start_state`` gives the same
    state to rounding; the results were made with this one, see ``initial_state``).  Returns y0 (N_STATE,)."""
    phi0 = start_angle(p)
    q = kinematic_state(p, np.array([phi0]))[0][0].copy()
    for _ in range(20):
        r = _position_residual(p, q, phi0, joints, eccentricity)
        dq = np.linalg.solve(_residual_jacobian(p, q, phi0, joints, eccentricity), -r)
        q += dq
        if np.max(np.abs(dq)) < tol * max(1.0, np.max(np.abs(q))):
            break
    jac = _residual_jacobian(p, q, phi0, joints, eccentricity)
    rhs = np.zeros(9)
    rhs[2] = p.crank_speed
    rows = {1: slice(5, 7), 2: slice(7, 9)}
    for j in joints:
        rhs[rows[j]] = rate
    y0 = np.zeros(N_STATE)
    y0[:9], y0[9:18] = q, np.linalg.solve(jac, rhs)
    return y0


def _point(q: np.ndarray, body: int, local) -> np.ndarray:
    """World position (m) of a body's local point (m), q of shape (..., 9) (real or complex)."""
    phi = q[..., 3 * body + 2]
    c, s = np.cos(phi), np.sin(phi)
    return np.stack(
        [q[..., 3 * body] + c * local[0] - s * local[1], q[..., 3 * body + 1] + s * local[0] + c * local[1]], axis=-1
    )


def _position_residual(p: FourBarParameters, q: np.ndarray, phi0: float, joints, eccentricity) -> np.ndarray:
    """The nine position equations of a start: crank pinned to the ground at O2 and at angle phi0, rocker pinned at
    O4, each ideal joint closed, each clearance joint at its eccentricity (m)."""
    l2, _, l4 = p.lengths
    pts = joint_points(p)
    res = [_point(q, 0, (-l2 / 2, 0.0)), [q[2] - phi0], _point(q, 2, (-l4 / 2, 0.0)) - np.array([p.ground, 0.0])]
    for j in (1, 2):
        bj, sj, bb, sb = pts[j]
        gap = _point(q, bj, sj) - _point(q, bb, sb)
        res.append(gap - (np.asarray(eccentricity, dtype=float) if j in joints else 0.0))
    return np.concatenate([np.ravel(r) for r in res])


def _residual_jacobian(p: FourBarParameters, q: np.ndarray, phi0: float, joints, eccentricity) -> np.ndarray:
    """d(position equations)/dq by the complex step (exact to rounding: Im f(q + i h e_k) / h, h = 1e-30)."""
    jac = np.empty((9, 9))
    for k in range(9):
        dq = np.zeros(9, dtype=complex)
        dq[k] = 1e-30j
        jac[:, k] = _position_residual(p, q + dq, phi0, joints, eccentricity).imag / 1e-30
    return jac


def journal_offsets(p: FourBarParameters, joints, states: np.ndarray) -> np.ndarray:
    """(e_x, e_y, e_x', e_y') of each clearance joint (m, m/s) in the states: (..., joint, 4), joints in order."""
    return assembly.journal_offsets(linkage(p, joints, ("contact",)), np.asarray(states, dtype=float))


def scene(p: FourBarParameters, joints, effects) -> tuple[Linkage, bool]:
    """(the linkage, whether gravity acts) of a scene: its clearance joints and effects."""
    return linkage(p, joints, effects if joints else ()), "gravity" in effects


def run(
    p: FourBarParameters, joints, effects, integrator: Mapping[str, Any], y0=None, t0: float = 0.0, memory=None
) -> simulate.Run:
    """A continuable run of a scene (``simulate.Run``) from its centred start at the dead point, or
    ``y0``/``memory``."""
    lk, gravity = scene(p, joints, effects)
    y0 = initial_state(p, joints) if y0 is None and memory is None else y0
    return simulate.Run(lk, gravity, integrator, y0=y0, t0=t0, memory=memory)


def integrate(p: FourBarParameters, joints, effects, t_out, integrator: Mapping[str, Any], y0=None):
    """Run a scene from its centred start (or ``y0``) and sample it at ``t_out`` (s, from 0): (states, diagnostics,
    accepted steps, rejected steps, effect evaluation counts, the start angle (rad))."""
    r = run(p, joints, effects, integrator, y0=y0)
    ys, diags = r.advance(t_out)
    return ys, diags, r.steps, r.rejected, r.counts, start_angle(p)


def joint_points(p: FourBarParameters) -> dict[int, tuple[int, tuple[float, float], int, tuple[float, float]]]:
    """(journal body, its point, bearing body, its point) of joints 1 and 2, bodies by index, points in m."""
    lk = linkage(p)
    out = {}
    for j, name in JOINT_NAMES.items():
        joint = next(x for x in lk.joints if x.name == name)
        out[j] = (
            lk.body_index(joint.journal[0]), lk.point(joint.journal), lk.body_index(joint.bearing[0]),
            lk.point(joint.bearing),
        )
    return out


def _paper_names(run: dict) -> dict:
    """An engine run's output renamed for the paper: the output body is the rocker, the driven body the crank."""
    out = dict(run)
    out["rocker_acceleration"], out["crank_torque"] = out.pop("output_acceleration"), out.pop("driver_torque")
    return out


def exudyn_ideal(
    p: FourBarParameters, end_time: float, step: float, newton_tolerance: float, gravity: bool = True
) -> dict:
    """The ideal scene in Exudyn (``exudyn_route.ideal_run``) from the dead point: t, rocker acceleration, crank
    torque."""
    from ...engines.multibody.exudyn_route import ideal_run

    return _paper_names(ideal_run(linkage(p), end_time, step, newton_tolerance, gravity))


def exudyn_dry(
    p: FourBarParameters,
    joints,
    end_time: float,
    step: float,
    newton_tolerance: float,
    output_period: float,
    progress_s: float = 5.0,
) -> dict:
    """A dry scene (contact and friction at ``joints``, gravity) in Exudyn (``exudyn_route.run``) from the dead
    point."""
    from ...engines.multibody.exudyn_route import run as exudyn_run

    lk = linkage(p, joints, ("contact", "friction"))
    return _paper_names(exudyn_run(lk, end_time, step, newton_tolerance, output_period, True, progress_s))
