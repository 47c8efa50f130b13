"""Mechanical chains (Druzhinsky): networks of masses, springs, dampers and ideal levers.

Mobility analogy, harmonic motion exp(j w t), SI units (w in rad/s):

* a two-terminal element's complex kinematic characteristic (mobility) is
  K = V / Q: mass (to the inertial frame) 1/(j w m), spring j w / k,
  damper 1/c;
* elements sharing a force add mobilities (series); elements sharing a
  velocity add inverse mobilities (parallel);
* an ideal lever a->b imposes v_b = eta v_a and transmits power without loss
  (force at a = eta times force at b), so a chain behind it is seen at a with
  mobility K / eta^2.

Three routes are offered, written independently so that they check each other:

``solve_network``
    node velocities with complex element impedances 1/K, constraints (levers,
    rigid joints, the kinematic drive) by Lagrange multipliers; gives the input
    force, every node velocity, every element force and every constraint force.
``solve_matrices``
    the same network assembled once into real M, K, C matrices on node
    displacements, constraints eliminated with a null-space basis, solved as
    (K - w^2 M + j w C) X = F.
``series_parallel_mobility``
    closed-form reduction of a series/parallel expression tree.

Vulfson's tangential stiffness of a joint with clearance is ``vulfson_stiffness``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Literal

import numpy as np
from numba import njit
from numpy.typing import ArrayLike, NDArray

from ..compilecache import use_for_numba

use_for_numba()  # compiled code cached in the compile cache folder, never below lib/

ComplexArray = NDArray[np.complex128]
FloatArray = NDArray[np.float64]
GROUND = "ground"


def vulfson_stiffness(reaction: ArrayLike, clearance: ArrayLike, normal_stiffness: float) -> FloatArray:
    """Tangential stiffness k_tau = k_n |R| / (k_n Delta + |R|) of a joint with clearance (N/m).

    reaction |R| in N, clearance Delta in m, normal (pin bending) stiffness k_n in N/m.
    Delta -> 0 gives k_n (no clearance); |R| -> 0 gives 0 without a division by zero
    unless both vanish, where the limit depends on the path and k_n is returned.
    """
    r = np.abs(np.asarray(reaction, dtype=float))
    d = np.asarray(clearance, dtype=float)
    if np.any(d < 0):
        raise ValueError(f"clearance must be >= 0, got {d}")
    den = normal_stiffness * d + r
    with np.errstate(invalid="ignore", divide="ignore"):
        k = np.where(den > 0, normal_stiffness * r / np.where(den > 0, den, 1.0), normal_stiffness)
    return k


@dataclass(frozen=True)
class Element:
    """A two-terminal element between nodes a and b (b = GROUND for a mass).

    kind: 'mass' (kg), 'spring' (N/m) or 'damper' (N s/m).
    """

    name: str
    kind: Literal["mass", "spring", "damper"]
    a: str
    b: str
    value: float


@dataclass(frozen=True)
class Lever:
    """Ideal lever (or, with ratio 1, a rigid joint): v_b = ratio * v_a, lossless."""

    name: str
    a: str
    b: str
    ratio: float


@dataclass(frozen=True)
class Network:
    """A mechanical chain: declared nodes, elements, levers and one driven node.

    drive: 'velocity' (kinematic excitation, the drive amplitude is a velocity
    in m/s) or 'force' (N).
    """

    nodes: tuple[str, ...]
    elements: tuple[Element, ...]
    levers: tuple[Lever, ...] = ()
    drive_node: str = ""
    drive: Literal["velocity", "force"] = "velocity"
    index: dict[str, int] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        if len(set(self.nodes)) != len(self.nodes) or GROUND in self.nodes:
            raise ValueError(f"nodes must be unique and not '{GROUND}': {self.nodes}")
        known = set(self.nodes) | {GROUND}
        for e in self.elements:
            if e.kind not in ("mass", "spring", "damper"):
                raise ValueError(f"element {e.name}: unknown kind {e.kind!r}")
            if not np.isfinite(e.value) or e.value < 0:
                raise ValueError(f"element {e.name}: {e.kind} must be >= 0 and finite, got {e.value!r}")
            for end in (e.a, e.b):
                if end not in known:
                    raise ValueError(f"element {e.name} is joined to undeclared node {end!r}")
            if e.kind == "mass" and e.b != GROUND:
                raise ValueError(f"element {e.name}: a mass is referred to the inertial frame (b = '{GROUND}')")
        for lever in self.levers:
            if not np.isfinite(lever.ratio) or lever.ratio == 0:
                raise ValueError(f"lever {lever.name}: ratio must be non-zero and finite, got {lever.ratio!r}")
            for end in (lever.a, lever.b):
                if end not in self.nodes:
                    raise ValueError(f"lever {lever.name} is joined to undeclared node {end!r}")
        if self.drive_node not in self.nodes:
            raise ValueError(f"drive node {self.drive_node!r} is not declared")
        object.__setattr__(self, "index", {n: i for i, n in enumerate(self.nodes)})


# --- route 1: complex impedances and Lagrange multipliers -----------------------------------------


@dataclass(frozen=True)
class ChainResponse:
    """Frequency response of a network (arrays over w).

    input_force: force at the driven node (N) for a velocity drive;
    input_velocity: velocity of the driven node (m/s) for a force drive;
    velocity: (n_w, n_nodes); element_force: name -> force a->b (N);
    lever_force: name -> force the lever applies at its output b (N);
    singular: True where the system matrix is singular (an undamped resonance hit exactly).
    """

    omega: FloatArray
    input_force: ComplexArray
    input_velocity: ComplexArray
    velocity: ComplexArray
    element_force: dict[str, ComplexArray]
    lever_force: dict[str, ComplexArray]
    singular: NDArray[np.bool_]

    @property
    def mobility(self) -> ComplexArray:
        """Input mobility K = V / Q (m/(N s))."""
        with np.errstate(divide="ignore", invalid="ignore"):
            return self.input_velocity / self.input_force


def _element_impedance(e: Element, omega: FloatArray) -> ComplexArray:
    """Q / V of one element (the inverse of its mobility), N s/m."""
    jw = 1j * omega
    if e.kind == "mass":
        return jw * e.value
    if e.kind == "spring":
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(omega == 0, np.inf, e.value / np.where(omega == 0, 1.0, jw))
    return np.full(omega.shape, e.value, dtype=complex)


def _batched_solve(a: ComplexArray, b: ComplexArray) -> tuple[ComplexArray, NDArray[np.bool_]]:
    """Solve a[k] x[k] = b[k]; singular systems give NaN and a flag instead of an exception."""
    try:
        return np.linalg.solve(a, b[..., None])[..., 0], np.zeros(a.shape[0], dtype=bool)
    except np.linalg.LinAlgError:
        x = np.full(b.shape, np.nan + 0j)
        flags = np.zeros(a.shape[0], dtype=bool)
        for k in range(a.shape[0]):
            try:
                x[k] = np.linalg.solve(a[k], b[k])
            except np.linalg.LinAlgError:
                flags[k] = True
        return x, flags


def near_singular(a: ComplexArray, rcond: float) -> NDArray[np.bool_]:
    """True where a[k], row- and column-equilibrated (so that units do not matter), has a reciprocal
    condition number below ``rcond``.  The condition number is the Frobenius one, |A|_F |A^-1|_F, which
    lies between the 2-norm condition and n times it, at the price of one LU factorisation and n solves
    instead of an SVD (compiled, ``_frobenius_conditions``; benchmarks/chains.py times the solve with and
    without this check).  An exactly singular matrix, or one with a zero row or column, is flagged."""
    with np.errstate(invalid="ignore"):
        return ~(_frobenius_conditions(np.ascontiguousarray(a, dtype=np.complex128)) * rcond < 1.0)


@njit(cache=True)
def _frobenius_conditions(a):
    """|S|_F |S^-1|_F of each a[k] equilibrated to S (rows scaled to a largest |entry| of 1, then columns),
    by LU with partial pivoting; inf where S is singular (a zero row, column or pivot)."""
    count, n = a.shape[0], a.shape[1]
    out = np.empty(count)
    lu = np.empty((n, n), dtype=np.complex128)
    col = np.empty(n)
    x = np.empty(n, dtype=np.complex128)
    for k in range(count):
        singular = False
        for i in range(n):
            big = 0.0
            for j in range(n):
                big = max(big, abs(a[k, i, j]))
            if big == 0.0:
                singular = True
            for j in range(n):
                lu[i, j] = a[k, i, j] / big if big > 0.0 else 0.0
        for j in range(n):
            big = 0.0
            for i in range(n):
                big = max(big, abs(lu[i, j]))
            col[j] = big
            if big == 0.0:
                singular = True
        if singular:
            out[k] = np.inf
            continue
        norm2 = 0.0
        for i in range(n):
            for j in range(n):
                lu[i, j] /= col[j]
                norm2 += lu[i, j].real ** 2 + lu[i, j].imag ** 2
        perm = np.arange(n)
        for c in range(n):  # LU with partial pivoting, in place
            p = c
            for i in range(c + 1, n):
                if abs(lu[i, c]) > abs(lu[p, c]):
                    p = i
            if lu[p, c] == 0.0:
                singular = True
                break
            if p != c:
                for j in range(n):
                    lu[c, j], lu[p, j] = lu[p, j], lu[c, j]
                perm[c], perm[p] = perm[p], perm[c]
            for i in range(c + 1, n):
                lu[i, c] /= lu[c, c]
                f = lu[i, c]
                for j in range(c + 1, n):
                    lu[i, j] -= f * lu[c, j]
        if singular:
            out[k] = np.inf
            continue
        inv2 = 0.0
        for e in range(n):  # column e of S^-1: solve L U x = P e_e
            for i in range(n):
                x[i] = 1.0 if perm[i] == e else 0.0
            for i in range(n):
                for j in range(i):
                    x[i] -= lu[i, j] * x[j]
            for i in range(n - 1, -1, -1):
                for j in range(i + 1, n):
                    x[i] -= lu[i, j] * x[j]
                x[i] /= lu[i, i]
                inv2 += x[i].real ** 2 + x[i].imag ** 2
        out[k] = np.sqrt(norm2 * inv2)
    return out


def network_system(net: Network, w: NDArray[np.float64], amp: ComplexArray) -> tuple[ComplexArray, ComplexArray]:
    """(A, b) of route 1 at every w (rad/s): node impedance rows, one row per lever and, for a velocity
    drive, the drive row; unknowns are the node velocities, then the multipliers."""
    n = len(net.nodes)
    ix = net.index
    size = n + len(net.levers) + (1 if net.drive == "velocity" else 0)
    a = np.zeros((w.size, size, size), dtype=complex)
    rhs = np.zeros((w.size, size), dtype=complex)
    for e in net.elements:
        z = _element_impedance(e, w)
        i = ix[e.a]
        a[:, i, i] += z
        if e.b != GROUND:
            j = ix[e.b]
            a[:, j, j] += z
            a[:, i, j] -= z
            a[:, j, i] -= z
    for c, lever in enumerate(net.levers):  # ratio * v_a - v_b = 0; multiplier = force at b
        row = n + c
        ia, ib = ix[lever.a], ix[lever.b]
        a[:, row, ia] = lever.ratio
        a[:, row, ib] = -1.0
        a[:, ia, row] = lever.ratio
        a[:, ib, row] = -1.0
    d = ix[net.drive_node]
    if net.drive == "velocity":
        a[:, size - 1, d] = 1.0
        a[:, d, size - 1] = -1.0  # multiplier = force applied at the drive node
        rhs[:, size - 1] = amp
    else:
        rhs[:, d] = amp
    return a, rhs


def solve_network(
    net: Network, omega: ArrayLike, drive_amplitude: ArrayLike = 1.0, singular_rcond: float = 1.0e-13
) -> ChainResponse:
    """Route 1: node velocities and constraint forces at every w (rad/s, > 0).

    The unknowns are the node velocities and one multiplier per constraint
    (each lever, and the drive for a velocity drive).  For a velocity drive the
    drive multiplier is the input force.
    """
    w = np.atleast_1d(np.asarray(omega, dtype=float))
    if np.any(w <= 0):
        raise ValueError("frequencies must be > 0 (a spring's mobility is infinite at w = 0)")
    amp = np.broadcast_to(np.asarray(drive_amplitude, dtype=complex), w.shape)
    n = len(net.nodes)
    ix = net.index
    size = n + len(net.levers) + (1 if net.drive == "velocity" else 0)
    d = ix[net.drive_node]
    a, rhs = network_system(net, w, amp)
    x, flags = _batched_solve(a, rhs)
    if singular_rcond > 0:  # flag near-singular solves too (an undamped resonance hit to rounding)
        flags = flags | near_singular(a, singular_rcond)
    x = np.where(flags[:, None], np.nan + 0j, x)
    v = x[:, :n]
    forces = {}
    for e in net.elements:
        z = _element_impedance(e, w)
        dv = v[:, ix[e.a]] - (v[:, ix[e.b]] if e.b != GROUND else 0.0)
        forces[e.name] = z * dv
    lever_force = {lever.name: x[:, n + c] for c, lever in enumerate(net.levers)}
    if net.drive == "velocity":
        q, vin = x[:, size - 1], amp.astype(complex)
    else:
        q, vin = amp.astype(complex), v[:, d]
    return ChainResponse(w, q, vin, v, forces, lever_force, flags)


# --- route 2: real matrices on displacements, null-space constraint elimination --------------------


def assemble_matrices(net: Network) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """(M, K, C, G): real mass, stiffness and damping matrices on node displacements and
    the lever constraint matrix G (G x = 0)."""
    n = len(net.nodes)
    mats = {"mass": np.zeros((n, n)), "spring": np.zeros((n, n)), "damper": np.zeros((n, n))}
    for e in net.elements:
        m = mats[e.kind]
        i = net.index[e.a]
        m[i, i] += e.value
        if e.b != GROUND:
            j = net.index[e.b]
            m[j, j] += e.value
            m[i, j] -= e.value
            m[j, i] -= e.value
    g = np.zeros((len(net.levers), n))
    for c, lever in enumerate(net.levers):
        g[c, net.index[lever.a]] = lever.ratio
        g[c, net.index[lever.b]] = -1.0
    return mats["mass"], mats["spring"], mats["damper"], g


def solve_matrices(
    net: Network, omega: ArrayLike, drive_amplitude: ArrayLike = 1.0
) -> tuple[ComplexArray, ComplexArray]:
    """Route 2: (input force or input velocity, node velocities) from (K - w^2 M + j w C) X = F.

    Constraints are eliminated with an orthonormal null-space basis T of G
    (x = T q); a velocity drive is imposed by a particular solution that moves the
    driven node by X_d = V / (j w) and satisfies G x = 0.
    """
    w = np.atleast_1d(np.asarray(omega, dtype=float))
    amp = np.broadcast_to(np.asarray(drive_amplitude, dtype=complex), w.shape)
    from scipy.linalg import null_space

    m, k, c, g = assemble_matrices(net)
    n = m.shape[0]
    d = net.index[net.drive_node]
    if net.drive == "velocity":
        # constraints G x = 0 and e_d . x = X_d: particular x_p = P X_d, homogeneous T q
        full = np.vstack([g, np.eye(n)[d]])
        t = null_space(full) if full.shape[0] else np.eye(n)
        p = np.linalg.lstsq(full, np.r_[np.zeros(g.shape[0]), 1.0], rcond=None)[0]
    else:
        t = null_space(g) if g.shape[0] else np.eye(n)
        p = np.zeros(n)
    dyn = k[None] - (w**2)[:, None, None] * m[None] + 1j * w[:, None, None] * c[None]
    reduced = np.einsum("ia,wij,jb->wab", t, dyn, t)
    if net.drive == "velocity":
        xd = amp / (1j * w)
        rhs = -np.einsum("ia,wij,j->wa", t, dyn, p) * xd[:, None]
    else:
        f = np.zeros((w.size, n), dtype=complex)
        f[:, d] = amp
        rhs = np.einsum("ia,wi->wa", t, f)
    q = np.linalg.solve(reduced, rhs[..., None])[..., 0]
    x = np.einsum("ia,wa->wi", t, q)
    if net.drive == "velocity":
        x = x + p[None] * xd[:, None]
        # input force: the residual of the full dynamic equation at the driven node, projected
        # out of the lever constraints: Q = e_d . (dyn x) - (lever reactions at d)
        resid = np.einsum("wij,wj->wi", dyn, x)
        # lever reactions lam solve G^T lam = resid on the non-driven rows
        rows = [i for i in range(n) if i != d]
        lam = np.linalg.lstsq(g.T[rows], resid[:, rows].T, rcond=None)[0] if g.shape[0] else np.zeros((0, w.size))
        q_in = resid[:, d] - (g.T[d] @ lam if g.shape[0] else 0.0)
        return q_in, 1j * w[:, None] * x
    return 1j * w * x[:, d], 1j * w[:, None] * x


# --- route 3: series/parallel expression trees -----------------------------------------------------


@dataclass(frozen=True)
class Series:
    """Children share one force; mobilities add."""

    children: tuple


@dataclass(frozen=True)
class Parallel:
    """Children share one velocity; inverse mobilities add."""

    children: tuple


@dataclass(frozen=True)
class Through:
    """A subtree seen through an ideal lever of ratio eta (mobility divided by eta^2)."""

    ratio: float
    child: object


def element_mobility(e: Element, omega: FloatArray) -> ComplexArray:
    """K = V/Q of one element: 1/(j w m), j w / k, 1/c."""
    jw = 1j * np.asarray(omega, dtype=float)
    if e.kind == "mass":
        return 1.0 / (jw * e.value)
    if e.kind == "spring":
        return jw / e.value
    return np.full(jw.shape, 1.0 / e.value, dtype=complex)


def series_parallel_mobility(tree, omega: ArrayLike) -> ComplexArray:
    """Route 3: mobility of a Series/Parallel/Through tree of Elements (m/(N s))."""
    w = np.asarray(omega, dtype=float)
    if isinstance(tree, Element):
        return element_mobility(tree, w)
    if isinstance(tree, Series):
        return sum((series_parallel_mobility(c, w) for c in tree.children), np.zeros(w.shape, dtype=complex))
    if isinstance(tree, Parallel):
        return 1.0 / sum(
            (1.0 / series_parallel_mobility(c, w) for c in tree.children), np.zeros(w.shape, dtype=complex)
        )
    if isinstance(tree, Through):
        return series_parallel_mobility(tree.child, w) / tree.ratio**2
    raise TypeError(f"not a chain tree node: {tree!r}")


# --- resonances ---------------------------------------------------------------------------------


def resonances(net: Network, tol: float = 1.0e-9) -> tuple[FloatArray, FloatArray]:
    """(velocity resonances, force resonances) of the driven node, rad/s, undamped.

    Velocity resonance (K = 0, infinite input force): natural frequencies with the
    driven node held.  Force resonance (K -> infinity, zero input force): natural
    frequencies with the driven node free.  Massless coordinates are condensed out.
    """
    from scipy.linalg import null_space

    m, k, _, g = assemble_matrices(net)
    n = m.shape[0]
    d = net.index[net.drive_node]
    out = []
    for held in (True, False):
        rows = [g] + ([np.eye(n)[d]] if held else [])
        con = np.vstack(rows) if any(r.size for r in rows) else np.zeros((0, n))
        t = null_space(con) if con.shape[0] else np.eye(n)
        mr, kr = t.T @ m @ t, t.T @ k @ t
        # static condensation of massless directions
        evals, evecs = np.linalg.eigh(mr)
        massive = evals > tol * max(evals.max(initial=0.0), 1.0)
        if not massive.any():
            out.append(np.array([]))
            continue
        u_m, u_0 = evecs[:, massive], evecs[:, ~massive]
        kmm, kmz, kzz = u_m.T @ kr @ u_m, u_m.T @ kr @ u_0, u_0.T @ kr @ u_0
        kc = kmm - kmz @ np.linalg.pinv(kzz) @ kmz.T if u_0.size else kmm
        mc = u_m.T @ mr @ u_m
        lam = np.linalg.eigvals(np.linalg.solve(mc, kc)).real
        lam = np.sort(lam[lam > tol * max(np.abs(lam).max(initial=0.0), 1.0)])
        out.append(np.sqrt(lam))
    return out[0], out[1]


# --- route 4: a state-space model (scipy.signal) --------------------------------------------------


def state_space(net: Network):
    """scipy.signal.StateSpace from the force at the driven node to its velocity (force drive only).

    Lever constraints are eliminated with a null-space basis T (x = T q); the reduced mass
    matrix T^T M T must be non-singular (every free direction carries mass).
    """
    from scipy.linalg import null_space
    from scipy.signal import StateSpace

    if net.drive != "force":
        raise ValueError("state_space needs a force-driven network (drive='force')")
    m, k, c, g = assemble_matrices(net)
    t = null_space(g) if g.shape[0] else np.eye(m.shape[0])
    mr, kr, cr = t.T @ m @ t, t.T @ k @ t, t.T @ c @ t
    if np.linalg.matrix_rank(mr) < mr.shape[0]:
        raise ValueError("the reduced mass matrix is singular: a free direction carries no mass")
    b = t.T @ np.eye(m.shape[0])[net.index[net.drive_node]]
    minv = np.linalg.inv(mr)
    n = mr.shape[0]
    a_mat = np.block([[np.zeros((n, n)), np.eye(n)], [-minv @ kr, -minv @ cr]])
    b_mat = np.concatenate([np.zeros(n), minv @ b])[:, None]
    c_mat = np.concatenate([np.zeros(n), b])[None, :]  # velocity of the driven node = b^T q'
    return StateSpace(a_mat, b_mat, c_mat, np.zeros((1, 1)))
