"""Configurations of a linkage from its description: assembly on a branch, the check over the driven turn, the
ideal linkage's kinematics and inverse dynamics (numpy, vectorised over time; SI units, radians).

The constraints are those of the compiled scenes (``kernels.revolute``, ``kernels.driver``) written again in numpy
over a stack of configurations: every ideal joint (and, for assembly, every clearance joint with its journal at a
given eccentricity) closes, and the driver sets its body's angle.  With as many equations as coordinates (a driven
linkage of zero mobility), positions follow by Newton's method, velocities from Phi_q q' = nu and accelerations from
Phi_q q'' = gamma, the multipliers from Phi_q^T lambda = g - M q''.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .linkage import GROUND, Driver, Joint, Linkage, LinkageError, oriented


@dataclass(frozen=True)
class AssemblySettings:
    """Newton's method and the turn check: a step below ``tolerance`` (m and rad) ends the iteration, at most
    ``max_iterations``; the turn is followed in ``steps_per_turn`` steps, and a configuration whose Jacobian's
    condition number exceeds ``condition_limit`` is a lock-up (a change point or a dead centre of the driver)."""

    tolerance: float = 1e-13
    max_iterations: int = 50
    steps_per_turn: int = 720
    condition_limit: float = 1e8


def _rows(linkage: Linkage, closed: tuple[Joint, ...]) -> list[tuple[str, object]]:
    """The constraint blocks in the engine's row order, with the clearance joints in ``closed`` appended (closed at a
    prescribed eccentricity)."""
    blocks = [("driver", c) if isinstance(c, Driver) else ("joint", c) for c in linkage.constraint_order()]
    return blocks + [("clearance", j) for j in closed]


def _rot(phi):
    c, s = np.cos(phi), np.sin(phi)
    return c, s


def constraints(linkage: Linkage, q: np.ndarray, t: np.ndarray, closed: tuple[Joint, ...] = (), offsets=None):
    """Phi (n, m), Phi_q (n, m, 3 nb) and the acceleration right-hand side gamma (n, m) without velocity terms' sign
    change (gamma = Phi_q q'' exactly for a motion that keeps Phi = 0), and the velocity right-hand side nu (n, m),
    at the configurations q (n, 3 nb) and times t (n,).  ``offsets``: the eccentricity (m, (2,)) of each joint in
    ``closed`` (journal centre minus bearing centre), zero if None.  gamma needs q' and is filled by ``gamma_of``."""
    n, nq = q.shape
    blocks = _rows(linkage, closed)
    m = sum(1 if kind == "driver" else 2 for kind, _ in blocks)
    phi, jac, nu = np.zeros((n, m)), np.zeros((n, m, nq)), np.zeros((n, m))
    row = 0
    for kind, item in blocks:
        if kind == "driver":
            b = linkage.body_index(item.body)
            th, thd, _ = item.angle(t)
            phi[:, row] = q[:, 3 * b + 2] - th
            jac[:, row, 3 * b + 2] = 1.0
            nu[:, row] = thd
            row += 1
            continue
        first, second = oriented(item) if kind == "joint" else (item.journal, item.bearing)
        for sign, ref in ((1.0, first), (-1.0, second)):
            b = linkage.body_index(ref[0])
            sx, sy = linkage.point(ref)
            if b < 0:
                phi[:, row] += sign * sx
                phi[:, row + 1] += sign * sy
                continue
            c, s = _rot(q[:, 3 * b + 2])
            phi[:, row] += sign * (q[:, 3 * b] + c * sx - s * sy)
            phi[:, row + 1] += sign * (q[:, 3 * b + 1] + s * sx + c * sy)
            jac[:, row, 3 * b] = sign
            jac[:, row + 1, 3 * b + 1] = sign
            jac[:, row, 3 * b + 2] = sign * (-s * sx - c * sy)
            jac[:, row + 1, 3 * b + 2] = sign * (c * sx - s * sy)
        if kind == "clearance" and offsets is not None:
            phi[:, row : row + 2] -= np.asarray(offsets[item.name], dtype=float)
        row += 2
    return phi, jac, nu


def gamma_of(linkage: Linkage, q: np.ndarray, qd: np.ndarray, t: np.ndarray, closed: tuple[Joint, ...] = ()):
    """gamma (n, m): Phi_q q'' = gamma for every motion that keeps the constraints (the quadratic velocity terms and
    the driver's angular acceleration)."""
    n = q.shape[0]
    blocks = _rows(linkage, closed)
    m = sum(1 if kind == "driver" else 2 for kind, _ in blocks)
    gamma = np.zeros((n, m))
    row = 0
    for kind, item in blocks:
        if kind == "driver":
            gamma[:, row] = item.angle(t)[2]
            row += 1
            continue
        first, second = oriented(item) if kind == "joint" else (item.journal, item.bearing)
        for sign, ref in ((1.0, first), (-1.0, second)):
            b = linkage.body_index(ref[0])
            if b < 0:
                continue
            sx, sy = linkage.point(ref)
            c, s = _rot(q[:, 3 * b + 2])
            w2 = qd[:, 3 * b + 2] ** 2
            gamma[:, row] += sign * (c * sx - s * sy) * w2
            gamma[:, row + 1] += sign * (s * sx + c * sy) * w2
        row += 2
    return gamma


#: Stacks at least this tall are solved by the compiled kernel (faster than numpy's batched LAPACK call there); smaller
#: ones by numpy, so that checking a description (validation, in Snakemake's own process) loads no compiled code.
COMPILED_STACK = 2048


def _solve(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """x with a[i] x[i] = b[i] over a stack (Gaussian elimination with partial pivoting); LinAlgError on a singular or
    non-finite system."""
    if a.shape[0] < COMPILED_STACK:
        x = np.linalg.solve(a, b[..., None])[..., 0]
    else:
        from .kernels import solve_stack

        x = solve_stack(np.ascontiguousarray(a, dtype=float), np.ascontiguousarray(b, dtype=float))
    if not np.isfinite(x).all():
        raise np.linalg.LinAlgError("singular constraint Jacobian")
    return x


def _newton(linkage, q, t, closed, offsets, settings: AssemblySettings):
    """Newton's method on Phi(q, t) = 0 for every row of q at once; returns (q, converged (n,))."""
    q = q.copy()
    done = np.zeros(q.shape[0], dtype=bool)
    for _ in range(settings.max_iterations):
        phi, jac, _ = constraints(linkage, q, t, closed, offsets)
        try:
            dq = _solve(jac, -phi)
        except np.linalg.LinAlgError:
            return q, done
        dq[done] = 0.0
        q += dq
        step = np.max(np.abs(dq), axis=1)
        done |= step < settings.tolerance * np.maximum(1.0, np.max(np.abs(q), axis=1))
        if done.all():
            break
    return q, done


def tree_guess(linkage: Linkage) -> np.ndarray:
    """A configuration to start Newton's method from: every body at its guessed angle, placed along a spanning tree
    from the ground so that each tree joint's two points coincide (m, rad; (3 nb,))."""
    q = np.full(linkage.n_coordinates, np.nan)
    placed = {GROUND}
    for b in linkage.bodies:
        q[3 * linkage.body_index(b.name) + 2] = b.angle_guess
    progress = True
    while progress:
        progress = False
        for j in linkage.joints:
            for known, new in ((j.journal, j.bearing), (j.bearing, j.journal)):
                if known[0] in placed and new[0] not in placed:
                    x, y = _world(linkage, q, known)
                    b = linkage.body_index(new[0])
                    sx, sy = linkage.point(new)
                    c, s = np.cos(q[3 * b + 2]), np.sin(q[3 * b + 2])
                    q[3 * b], q[3 * b + 1] = x - (c * sx - s * sy), y - (s * sx + c * sy)
                    placed.add(new[0])
                    progress = True
    return q


def _world(linkage: Linkage, q: np.ndarray, ref: tuple[str, str]) -> tuple[float, float]:
    b = linkage.body_index(ref[0])
    sx, sy = linkage.point(ref)
    if b < 0:
        return sx, sy
    c, s = np.cos(q[3 * b + 2]), np.sin(q[3 * b + 2])
    return q[3 * b] + c * sx - s * sy, q[3 * b + 1] + s * sx + c * sy


def assemble(
    linkage: Linkage, t: float = 0.0, settings: AssemblySettings = AssemblySettings(), guess=None
) -> np.ndarray:
    """The configuration q (3 nb,) at time t (s) on the branch nearest the guessed body angles, every clearance
    journal centred in its bearing.  LinkageError (key ``driver``) if Newton's method does not converge."""
    closed = linkage.clearance_joints
    q0 = tree_guess(linkage) if guess is None else np.asarray(guess, dtype=float)
    tt = np.array([t])
    q, ok = _newton(linkage, q0[None], tt, closed, None, settings)
    if not ok[0]:  # far from the guess: least squares (Levenberg-Marquardt) first, then Newton's method from there
        from scipy.optimize import least_squares

        fit = least_squares(
            lambda x: constraints(linkage, x[None], tt, closed)[0][0], q0, method="lm",
            jac=lambda x: constraints(linkage, x[None], tt, closed)[1][0], xtol=1e-15, ftol=1e-15, gtol=1e-15,
        )
        q, ok = _newton(linkage, fit.x[None], tt, closed, None, settings)
    if not ok[0] or np.max(np.abs(constraints(linkage, q, tt, closed)[0])) > 1e3 * settings.tolerance * max(
        1.0, np.max(np.abs(q))
    ):
        theta = np.degrees(linkage.driver.angle(tt)[0][0])
        raise LinkageError(
            linkage.names.get("driver", "driver"),
            f"the linkage does not assemble at the driver angle {theta:.6g} deg from the guessed body angles "
            "(no configuration closes every joint near them: check the dimensions and the angle guesses)",
        )
    return q[0]


@dataclass(frozen=True)
class Turn:
    """The ideal linkage over one driven turn: times (s), configurations (n, 3 nb), their rates (n, 3 nb) and each body
    angle's gain over the turn (rad, a multiple of 2 pi: 2 pi for a body that turns round, 0 for one that rocks)."""

    t: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    gain: np.ndarray


def follow_turn(linkage: Linkage, settings: AssemblySettings = AssemblySettings()) -> Turn:
    """Follow the assembled linkage through one driven turn (2 pi / omega) at ``settings.steps_per_turn`` steps.

    The turn is first followed in a few coarse steps (each from the last two configurations' extrapolation), then
    refined by halving the step, every new configuration from the interpolation of its neighbours, all of a level at
    once, down to the set step.  LinkageError where it locks up: Newton's method fails, the Jacobian's condition
    number exceeds the limit, or its determinant changes sign (a change point passed, the branch changed)."""
    closed = linkage.clearance_joints
    period = linkage.driver.period
    n, key = settings.steps_per_turn, linkage.names.get("linkage", "linkage")
    levels = 0
    while n % 2 == 0 and n // 2 >= 16 and levels < 4:
        n, levels = n // 2, levels + 1
    t = np.arange(n + 1) * period / n
    qs = np.empty((n + 1, linkage.n_coordinates))
    qs[0] = assemble(linkage, 0.0, settings)
    for i in range(1, n + 1):
        guess = 2 * qs[i - 1] - qs[i - 2] if i > 1 else qs[i - 1]
        q, ok = _newton(linkage, guess[None], t[i : i + 1], closed, None, settings)
        if not ok[0]:
            _no_closure(linkage, key, t[i - 1], t[i])
        qs[i] = q[0]
    for _ in range(levels):
        mid_t = 0.5 * (t[:-1] + t[1:])
        q, ok = _newton(linkage, 0.5 * (qs[:-1] + qs[1:]), mid_t, closed, None, settings)
        if not ok.all():
            k = int(np.argmin(ok))
            _no_closure(linkage, key, t[k], mid_t[k])
        t = np.insert(t, np.arange(1, t.size), mid_t)
        qs = np.insert(qs, np.arange(1, qs.shape[0]), q, axis=0)
        n *= 2
    _check_turn(linkage, key, t, qs, settings)
    gain = np.zeros(linkage.n_coordinates)
    gain[2::3] = 2 * np.pi * np.round((qs[-1, 2::3] - qs[0, 2::3]) / (2 * np.pi))
    if np.max(np.abs(qs[-1] - gain - qs[0])) > 1e3 * settings.tolerance * max(1.0, np.max(np.abs(qs[0]))):
        raise LinkageError(key, "does not return to its start after one driven turn (it ends on another branch)")
    _, jac, nu = constraints(linkage, qs, t, closed)
    return Turn(t, qs, _solve(jac, nu), gain)


def _no_closure(linkage: Linkage, key: str, good: float, bad: float):
    a, b = np.degrees(linkage.driver.angle(np.array([good, bad]))[0])
    raise LinkageError(
        key,
        f"locks up between the driver angles {a:.6g} and {b:.6g} deg (no configuration near the last "
        "one closes every joint: a dyad cannot reach, the driven body cannot turn through)",
    )


def _lock_up(linkage: Linkage, key: str, t: float, i: int, n: int, cond: float, settings: AssemblySettings):
    theta = np.degrees(linkage.driver.angle(np.array([t]))[0][0])
    raise LinkageError(key, f"locks up at the driver angle {theta:.6g} deg ({i} of {n} steps into the turn; "
                            f"Jacobian condition number {cond:.3g}, limit {settings.condition_limit:g})")


def _check_turn(linkage: Linkage, key: str, t: np.ndarray, qs: np.ndarray, settings: AssemblySettings) -> None:
    """Every configuration of the turn well conditioned, and the Jacobian's determinant of one sign throughout."""
    jac = constraints(linkage, qs, t, linkage.clearance_joints)[1]
    cond = np.linalg.cond(jac)
    bad = ~(cond < settings.condition_limit)
    if bad.any():
        k = int(np.argmax(bad))
        _lock_up(linkage, key, t[k], k, t.size - 1, cond[k], settings)
    sign = np.sign(np.linalg.det(jac))
    if (sign != sign[0]).any():
        k = int(np.argmax(sign != sign[0]))
        theta = np.degrees(linkage.driver.angle(t[k : k + 1])[0][0])
        raise LinkageError(key, f"passes a change point before the driver angle {theta:.6g} deg (the constraint "
                                "Jacobian's determinant changes sign: the linkage changes branch)")


def positions(
    linkage: Linkage, t: np.ndarray, turn: Turn, settings: AssemblySettings = AssemblySettings()
) -> np.ndarray:
    """Configurations q (n, 3 nb) at the times t (s): the turn's configuration at the same phase (linear
    interpolation, plus the turns' angle gains), polished by Newton's method, all at once."""
    t = np.asarray(t, dtype=float)
    period = turn.t[-1]
    k = np.floor(t / period)
    phase = t - k * period
    i = np.clip(np.searchsorted(turn.t, phase, side="right") - 1, 0, turn.t.size - 2)
    h = turn.t[i + 1] - turn.t[i]
    s = ((phase - turn.t[i]) / h)[:, None]
    h = h[:, None]
    # cubic Hermite interpolation of positions and rates: an error of order h^4, so Newton's method starts close
    guess = ((2 * s**3 - 3 * s**2 + 1) * turn.q[i] + (s**3 - 2 * s**2 + s) * h * turn.qd[i]
             + (-2 * s**3 + 3 * s**2) * turn.q[i + 1] + (s**3 - s**2) * h * turn.qd[i + 1]) + k[:, None] * turn.gain
    q, ok = _newton(linkage, guess, t, linkage.clearance_joints, None, settings)
    if not ok.all():
        raise LinkageError(linkage.names.get("linkage", "linkage"),
                           f"Newton's method did not converge at {np.count_nonzero(~ok)} of {t.size} times")
    return q


def kinematics(
    linkage: Linkage, t: np.ndarray, settings: AssemblySettings = AssemblySettings(), turn: Turn | None = None
):
    """Positions, velocities and accelerations (n, 3 nb) each of the ideal linkage (every joint closed) at t (s)."""
    turn = follow_turn(linkage, settings) if turn is None else turn
    t = np.asarray(t, dtype=float)
    closed = linkage.clearance_joints
    q = positions(linkage, t, turn, settings)
    _, jac, nu = constraints(linkage, q, t, closed)
    qd = _solve(jac, nu)
    gamma = gamma_of(linkage, q, qd, t, closed)
    qdd = _solve(jac, gamma)
    return q, qd, qdd


def mass_vector(linkage: Linkage) -> np.ndarray:
    """The diagonal of the mass matrix (3 nb,): m, m, J per body."""
    return np.array([v for b in linkage.bodies for v in (b.mass, b.mass, b.inertia)], dtype=float)


def applied_forces(
    linkage: Linkage, q: np.ndarray, gravity: bool, qd: np.ndarray | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """Generalised applied forces g (n, 3 nb) and their potential energy (n,), J: gravity along -y at every centre
    of mass, if it acts, and the springs (their dampers read the velocities ``qd``, zero if None)."""
    g, potential = np.zeros_like(q), np.zeros(q.shape[0])
    if gravity:
        g[:, 1::3] -= mass_vector(linkage)[0::3] * linkage.gravity
        potential += np.sum(mass_vector(linkage)[0::3] * linkage.gravity * q[:, 1::3], axis=-1)
    qd = np.zeros_like(q) if qd is None else qd
    for spring in linkage.springs:
        b = linkage.body_index(spring.point[0])
        pos, vel = _world_stack(linkage, q, qd, spring.point)
        d = pos - np.asarray(spring.rest)
        f = -np.asarray(spring.stiffness) * d - np.asarray(spring.damping) * vel
        arm = pos - q[:, 3 * b : 3 * b + 2]
        g[:, 3 * b : 3 * b + 2] += f
        g[:, 3 * b + 2] += arm[:, 0] * f[:, 1] - arm[:, 1] * f[:, 0]
        potential += 0.5 * np.sum(np.asarray(spring.stiffness) * d**2, axis=-1)
    return g, potential


def inverse_dynamics(linkage: Linkage, t: np.ndarray, gravity: bool, settings: AssemblySettings = AssemblySettings(),
                     turn: Turn | None = None) -> dict[str, np.ndarray]:
    """The ideal linkage driven through the times t (s): Phi_q^T lambda = g - M q'' (every joint closed).

    Returns the output body's angular acceleration (rad/s^2), the driver torque (N m, what the driver applies), the
    reaction force of every joint (N, by name): its magnitude ``force_<joint>`` and its components ``reaction_<joint>``
    (..., 2) in the ground frame, the force the bearing's body exerts on the journal's (the journal's constraint
    p_journal - p_bearing = 0 enters M q'' = g - Phi_q^T lambda with -lambda on the journal's body); the mechanical
    energy (J) and the configurations."""
    q, qd, qdd = kinematics(linkage, t, settings, turn)
    mass = mass_vector(linkage)
    closed = linkage.clearance_joints
    jac = constraints(linkage, q, np.asarray(t, dtype=float), closed)[1]
    g, potential = applied_forces(linkage, q, gravity, qd)
    lam = _solve(np.swapaxes(jac, 1, 2), g - mass * qdd)
    energy = 0.5 * np.sum(mass * qd**2, axis=-1) + potential
    out = {
        "output_acceleration": qdd[:, 3 * linkage.body_index(linkage.output) + 2],
        "energy": energy,
        "q": q,
        "qd": qd,
        "qdd": qdd,
    }
    row = 0
    for kind, item in _rows(linkage, closed):
        if kind == "driver":
            out["driver_torque"] = -lam[:, row]
            row += 1
        else:
            out[f"force_{item.name}"] = np.hypot(lam[:, row], lam[:, row + 1])
            out[f"reaction_{item.name}"] = -lam[:, row : row + 2]
            row += 2
    return out


def start_state(linkage: Linkage, offsets=None, rates=None, settings: AssemblySettings = AssemblySettings(),
                t: float = 0.0) -> np.ndarray:
    """The scene's state y0 = (q, q', driver work 0) at time t (s): every ideal joint closed, the driver exact,
    every clearance journal at its eccentricity in ``offsets`` (m, (x, y), by joint name; centred if absent) and
    moving relative to its bearing at ``rates`` (m/s; zero if absent)."""
    closed = linkage.clearance_joints
    offsets = {j.name: (offsets or {}).get(j.name, (0.0, 0.0)) for j in closed}
    q0 = assemble(linkage, t, settings)
    tt = np.array([t])
    q, ok = _newton(linkage, q0[None], tt, closed, offsets, settings)
    if not ok[0]:
        raise LinkageError(
            linkage.names.get("linkage", "linkage"), "does not assemble with its journals at the given eccentricities"
        )
    _, jac, nu = constraints(linkage, q, tt, closed, offsets)
    row = 0
    for kind, item in _rows(linkage, closed):
        if kind == "clearance":
            nu[0, row : row + 2] = (rates or {}).get(item.name, (0.0, 0.0))
        row += 1 if kind == "driver" else 2
    qd = np.linalg.solve(jac[0], nu[0])
    return np.concatenate([q[0], qd, [0.0]])


def journal_offsets(linkage: Linkage, states: np.ndarray) -> np.ndarray:
    """Eccentricity e = journal centre - bearing centre (m) and its rate (m/s) of each clearance joint in the states
    (..., >= 6 nb): shape (..., joint, 4) as (e_x, e_y, e_x', e_y') in the fixed frame."""
    nq = linkage.n_coordinates
    q, qd = states[..., :nq], states[..., nq : 2 * nq]
    out = []
    for j in linkage.clearance_joints:
        pj, vj = _world_stack(linkage, q, qd, j.journal)
        pb, vb = _world_stack(linkage, q, qd, j.bearing)
        out.append(np.concatenate([pj - pb, vj - vb], axis=-1))
    return np.stack(out, axis=-2)


def _world_stack(linkage: Linkage, q: np.ndarray, qd: np.ndarray, ref: tuple[str, str]):
    """World position and velocity (..., 2) of a body point over a stack of states."""
    b = linkage.body_index(ref[0])
    sx, sy = linkage.point(ref)
    if b < 0:
        shape = q.shape[:-1] + (2,)
        return np.broadcast_to(np.array([sx, sy]), shape), np.zeros(shape)
    phi, w = q[..., 3 * b + 2], qd[..., 3 * b + 2]
    c, s = np.cos(phi), np.sin(phi)
    rx, ry = c * sx - s * sy, s * sx + c * sy
    pos = np.stack([q[..., 3 * b] + rx, q[..., 3 * b + 1] + ry], axis=-1)
    vel = np.stack([qd[..., 3 * b] - w * ry, qd[..., 3 * b + 1] + w * rx], axis=-1)
    return pos, vel
