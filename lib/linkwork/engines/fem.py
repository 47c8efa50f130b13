"""Planar frame finite elements (Euler-Bernoulli, 3 dof per node: u, v, theta).

Small, pure functions: an element stiffness in global coordinates, assembly of
a rigid-jointed frame, and a static solve with fixed degrees of freedom.  SI
units throughout.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from numba import njit
from numpy.typing import NDArray

from ..compilecache import use_for_numba

use_for_numba()  # compiled code cached in the compile cache folder, never below lib/

FloatArray = NDArray[np.float64]


def frame_element_stiffness(
    youngs_modulus: float, area: float, second_moment: float, start: Sequence[float], end: Sequence[float]
) -> FloatArray:
    """6x6 stiffness of a 2-node planar frame element in global coordinates.

    Parameters: E (Pa), A (m^2), I (m^4), end coordinates (m).  Dof order
    (u1, v1, theta1, u2, v2, theta2); units N/m, N, N m.
    """
    dx, dy = end[0] - start[0], end[1] - start[1]
    length = float(np.hypot(dx, dy))
    if length <= 0.0:
        raise ValueError("frame element has zero length")
    c, s = dx / length, dy / length
    ea, ei = youngs_modulus * area / length, youngs_modulus * second_moment
    l2, l3 = length**2, length**3
    local = np.array(
        [
            [ea, 0, 0, -ea, 0, 0],
            [0, 12 * ei / l3, 6 * ei / l2, 0, -12 * ei / l3, 6 * ei / l2],
            [0, 6 * ei / l2, 4 * ei / length, 0, -6 * ei / l2, 2 * ei / length],
            [-ea, 0, 0, ea, 0, 0],
            [0, -12 * ei / l3, -6 * ei / l2, 0, 12 * ei / l3, -6 * ei / l2],
            [0, 6 * ei / l2, 2 * ei / length, 0, -6 * ei / l2, 4 * ei / length],
        ]
    )
    rot = np.array([[c, s, 0], [-s, c, 0], [0, 0, 1.0]])
    t = np.zeros((6, 6))
    t[:3, :3] = rot
    t[3:, 3:] = rot
    return t.T @ local @ t


def assemble_frame(
    nodes: FloatArray, elements: Sequence[tuple[int, int]], sections: Sequence[tuple[float, float, float]]
) -> FloatArray:
    """Global stiffness of a rigid-jointed frame.

    nodes: (n, 2) coordinates (m); elements: node index pairs; sections:
    (E, A, I) per element.
    """
    n = len(nodes)
    k = np.zeros((3 * n, 3 * n))
    for (i, j), (e, a, inertia) in zip(elements, sections, strict=True):
        ke = frame_element_stiffness(e, a, inertia, nodes[i], nodes[j])
        dofs = np.r_[3 * i : 3 * i + 3, 3 * j : 3 * j + 3]
        k[np.ix_(dofs, dofs)] += ke
    return k


def solve_static(stiffness: FloatArray, load: FloatArray, fixed: Sequence[int]) -> FloatArray:
    """Displacements for K u = f with the listed dofs held at zero."""
    free = np.setdiff1d(np.arange(len(load)), np.asarray(fixed, dtype=int))
    u = np.zeros(len(load))
    u[free] = np.linalg.solve(stiffness[np.ix_(free, free)], load[free])
    return u


# --- element matrices in local coordinates -------------------------------------------------------


def _gauss(n: int) -> tuple[FloatArray, FloatArray]:
    """Gauss-Legendre points and weights on [0, 1]."""
    x, w = np.polynomial.legendre.leggauss(n)
    return 0.5 * (x + 1.0), 0.5 * w


def quintic_hermite(xi: FloatArray, length: float) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Quintic Hermite shape functions for (v, v', v'') at both ends, and their x-derivatives.

    xi in [0, 1]; returns N, dN/dx, d2N/dx2 with shape (len(xi), 6), ordered
    (v1, v1', v1'', v2, v2', v2'').  Slopes and curvatures are per unit length.
    """
    x = np.asarray(xi, dtype=float)[:, None]
    L = length
    # on [0, 1]: value, first and second derivative polynomials (coefficients from the Hermite conditions)
    h = np.hstack(
        [
            1 - 10 * x**3 + 15 * x**4 - 6 * x**5,
            (x - 6 * x**3 + 8 * x**4 - 3 * x**5) * L,
            (0.5 * x**2 - 1.5 * x**3 + 1.5 * x**4 - 0.5 * x**5) * L**2,
            10 * x**3 - 15 * x**4 + 6 * x**5,
            (-4 * x**3 + 7 * x**4 - 3 * x**5) * L,
            (0.5 * x**3 - x**4 + 0.5 * x**5) * L**2,
        ]
    )
    dh = np.hstack(
        [
            -30 * x**2 + 60 * x**3 - 30 * x**4,
            (1 - 18 * x**2 + 32 * x**3 - 15 * x**4) * L,
            (x - 4.5 * x**2 + 6 * x**3 - 2.5 * x**4) * L**2,
            30 * x**2 - 60 * x**3 + 30 * x**4,
            (-12 * x**2 + 28 * x**3 - 15 * x**4) * L,
            (1.5 * x**2 - 4 * x**3 + 2.5 * x**4) * L**2,
        ]
    ) / L
    d2h = np.hstack(
        [
            -60 * x + 180 * x**2 - 120 * x**3,
            (-36 * x + 96 * x**2 - 60 * x**3) * L,
            (1 - 9 * x + 18 * x**2 - 10 * x**3) * L**2,
            60 * x - 180 * x**2 + 120 * x**3,
            (-24 * x + 84 * x**2 - 60 * x**3) * L,
            (3 * x - 12 * x**2 + 10 * x**3) * L**2,
        ]
    ) / L**2
    return h, dh, d2h


def cubic_hermite(xi: FloatArray, length: float) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Cubic Hermite shape functions for (v, v') at both ends and x-derivatives, shape (len(xi), 4)."""
    x = np.asarray(xi, dtype=float)[:, None]
    L = length
    h = np.hstack([1 - 3 * x**2 + 2 * x**3, (x - 2 * x**2 + x**3) * L, 3 * x**2 - 2 * x**3, (-(x**2) + x**3) * L])
    dh = np.hstack([-6 * x + 6 * x**2, (1 - 4 * x + 3 * x**2) * L, 6 * x - 6 * x**2, (-2 * x + 3 * x**2) * L]) / L
    d2h = np.hstack([-6 + 12 * x, (-4 + 6 * x) * L, 6 - 12 * x, (-2 + 6 * x) * L]) / L**2
    return h, dh, d2h


#: local dof layouts: which local dofs are axial (u) and which transverse (v family), per element kind
LAYOUTS = {
    "frame6": {"axial": (0, 3), "transverse": (1, 2, 4, 5), "size": 6, "per_end": 3},
    "quintic8": {"axial": (0, 4), "transverse": (1, 2, 3, 5, 6, 7), "size": 8, "per_end": 4},
}


def local_matrices(kind: str, youngs_modulus: float, area: float, second_moment: float, density: float, length: float,
                   gauss_points: int = 8) -> tuple[FloatArray, FloatArray]:
    """(K, M) of a beam element in local coordinates, by Gauss quadrature of the shape functions.

    kind 'frame6': (u1, v1, v1', u2, v2, v2'), linear axial and cubic transverse (the standard frame);
    kind 'quintic8': (u1, v1, v1', v1'', u2, v2, v2', v2''), linear axial and quintic transverse.
    Consistent mass (rho A, no rotary inertia).  SI units.
    """
    axial_k, axial_m, bend_k, bend_m = shape_integrals(kind, float(length), gauss_points)
    return (youngs_modulus * area * axial_k + youngs_modulus * second_moment * bend_k,
            density * area * (axial_m + bend_m))


@lru_cache(maxsize=256)
def shape_integrals(
    kind: str, length: float, gauss_points: int = 8
) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """Integrals of the shape-function products over one element of ``length`` (m), scattered into the element's dof
    layout: (int N'^T N' (axial), int N^T N (axial), int H''^T H'' (transverse), int H^T H (transverse))."""
    lay = LAYOUTS[kind]
    xi, w = _gauss(gauss_points)
    shapes = cubic_hermite if kind == "frame6" else quintic_hermite
    h, _, d2h = shapes(xi, length)
    lin = np.stack([1 - xi, xi], axis=1)
    dlin = np.array([-1.0, 1.0]) / length
    n = lay["size"]
    out = [np.zeros((n, n)) for _ in range(4)]
    ax, tr = np.ix_(lay["axial"], lay["axial"]), np.ix_(lay["transverse"], lay["transverse"])
    out[0][ax] = length * np.outer(dlin, dlin)
    out[1][ax] = length * (lin.T * w) @ lin
    out[2][tr] = length * (d2h.T * w) @ d2h
    out[3][tr] = length * (h.T * w) @ h
    for a in out:
        a.setflags(write=False)
    return tuple(out)  # type: ignore[return-value]


def local_to_global(kind: str, angle: FloatArray) -> FloatArray:
    """Transformation T (local = T global) for elements at direction ``angle`` (rad), shape (..., n, n).

    Translations rotate; slopes and curvatures of a planar element are the same in both frames.
    """
    lay = LAYOUTS[kind]
    a = np.asarray(angle, dtype=float)
    c, s = np.cos(a), np.sin(a)
    t = np.zeros(a.shape + (lay["size"], lay["size"]))
    for end in range(2):
        o = end * lay["per_end"]
        t[..., o, o], t[..., o, o + 1] = c, s
        t[..., o + 1, o], t[..., o + 1, o + 1] = -s, c
        for extra in range(2, lay["per_end"]):
            t[..., o + extra, o + extra] = 1.0
    return t


@lru_cache(maxsize=256)
def _curvature_shapes(kind: str, length: float, points: int) -> FloatArray:
    """Second derivatives of the transverse shape functions at ``points`` equally spaced stations."""
    shapes = cubic_hermite if kind == "frame6" else quintic_hermite
    d2h = shapes(np.linspace(0.0, 1.0, points), length)[2]
    d2h.setflags(write=False)
    return d2h


def element_strain_extremes(
    kind: str, length: float, half_depth: float, local_u: FloatArray, points: int = 9
) -> FloatArray:
    """max over the element of |h v''| + |u'| (the strain of eq. (8) divided by E), for local dof vectors (..., n)."""
    lay = LAYOUTS[kind]
    d2h = _curvature_shapes(kind, float(length), points)
    v = local_u[..., list(lay["transverse"])]
    curvature = np.einsum("pk,...k->...p", d2h, v)
    axial = (local_u[..., lay["axial"][1]] - local_u[..., lay["axial"][0]]) / length
    return (half_depth * np.abs(curvature) + np.abs(axial)[..., None]).max(axis=-1)


# --- meshes of beams whose joints share some dofs ------------------------------------------------


@dataclass(frozen=True)
class BeamMesh:
    """Beam elements on numbered nodes, with per-end keys for the dofs beyond the translations.

    kind: 'frame6' (extra dof per end: slope) or 'quintic8' (slope and curvature).
    elements: (node_i, node_j) pairs.  extra_keys[e][end]: one key per extra dof of that end
    (slope[, curvature]); ends with equal keys share the dof, None fixes it at zero.
    fixed_nodes: nodes whose translations are held at zero.
    """

    kind: str
    n_nodes: int
    elements: tuple[tuple[int, int], ...]
    extra_keys: tuple[tuple[tuple, tuple], ...]
    fixed_nodes: frozenset = frozenset()

    def dof_indices(self) -> tuple[int, NDArray[np.int64]]:
        """(number of free dofs, element-to-global index array with -1 for fixed dofs)."""
        return _dof_indices(self)


@lru_cache(maxsize=64)
def _dof_indices(mesh: BeamMesh) -> tuple[int, NDArray[np.int64]]:
    """The dof numbering of a mesh (cached: meshes are immutable)."""
    index: dict = {}
    for node in range(mesh.n_nodes):
        if node not in mesh.fixed_nodes:
            index[("x", node)] = len(index)
            index[("y", node)] = len(index)
    for ends in mesh.extra_keys:
        for keys in ends:
            for key in keys:
                if key is not None and ("extra", key) not in index:
                    index[("extra", key)] = len(index)
    per_end = LAYOUTS[mesh.kind]["per_end"]
    table = np.full((len(mesh.elements), 2 * per_end), -1, dtype=np.int64)
    for e, ((i, j), ends) in enumerate(zip(mesh.elements, mesh.extra_keys, strict=True)):
        for end, (node, keys) in enumerate(((i, ends[0]), (j, ends[1]))):
            o = end * per_end
            table[e, o] = index.get(("x", node), -1)
            table[e, o + 1] = index.get(("y", node), -1)
            for k, key in enumerate(keys):
                table[e, o + 2 + k] = index[("extra", key)] if key is not None else -1
    table.setflags(write=False)
    return len(index), table


def rotate(t: FloatArray, m_loc: FloatArray) -> FloatArray:
    """T^T m T for a stack of transformations T (c, n, n) and one local matrix m (n, n)."""
    return np.swapaxes(t, -1, -2) @ m_loc @ t


def assemble(mesh: BeamMesh, element_matrices: list[FloatArray], angles: FloatArray) -> FloatArray:
    """Global matrices over configurations: sum of T^T m T scattered by the dof table.

    element_matrices: one local matrix per element; angles: (n_config, n_elements) element directions.
    Returns (n_config, n_dof, n_dof).
    """
    return scatter(mesh, rotated(mesh, element_matrices, angles))


def rotated(mesh: BeamMesh, element_matrices: list[FloatArray], angles: FloatArray) -> list[FloatArray]:
    """Each element's matrix in the global frame, T^T m T over configurations: one (n_config, size, size) per element
    (angles: (n_config, n_elements), rad)."""
    angles = np.atleast_2d(angles)
    return [rotate(local_to_global(mesh.kind, angles[:, e]), m_loc) for e, m_loc in enumerate(element_matrices)]


def scatter(mesh: BeamMesh, element_globals: list[FloatArray]) -> FloatArray:
    """Global matrices (n_config, n_dof, n_dof): the elements' global-frame matrices (``rotated``) summed by the dof
    table, element by element."""
    n_dof, table = mesh.dof_indices()
    out = np.zeros((element_globals[0].shape[0], n_dof, n_dof))
    for e, m_glob in enumerate(element_globals):
        idx = table[e]
        keep = np.flatnonzero(idx >= 0)
        gi = idx[keep]
        out[:, gi[:, None], gi[None, :]] += m_glob[:, keep[:, None], keep[None, :]]
    return out


def gather(mesh: BeamMesh, u: FloatArray) -> FloatArray:
    """Element dof vectors (global frame) from global solutions u (n_config, n_dof): (n_config, n_el, size)."""
    _, table = mesh.dof_indices()
    padded = np.concatenate([u, np.zeros(u.shape[:-1] + (1,))], axis=-1)
    return padded[..., np.where(table >= 0, table, u.shape[-1])]


def scatter_weighted(table: NDArray[np.int64], bases: FloatArray, weights: FloatArray, n_dof: int) -> FloatArray:
    """Global matrices (n_config, n_dof, n_dof) from element matrices that are weighted sums of fixed bases:
    sum over elements e of (sum over b of weights[e, b] bases[e, b]) scattered by the dof table (``table``: element
    to global index, -1 for a fixed dof; ``bases``: (n_el, n_bases, n_config, size, size), already in the global
    frame).  With the section properties as the weights (E A and E I for the stiffness, rho A for the mass), the
    bases depend only on the geometry and the motion, so a change of diameter or material reassembles without a
    rotation.  Compiled; equal to ``assemble`` with the weighted local matrices up to rounding
    (tests/test_fem.py)."""
    return _scatter_weighted(np.asarray(table), np.ascontiguousarray(bases), np.asarray(weights, dtype=float),
                             int(n_dof))


@njit(cache=True)
def _scatter_weighted(table, bases, weights, n_dof):
    n_el, n_b, n_c, size, _ = bases.shape
    out = np.zeros((n_c, n_dof, n_dof))
    for c in range(n_c):
        for e in range(n_el):
            for i in range(size):
                gi = table[e, i]
                if gi < 0:
                    continue
                for j in range(size):
                    gj = table[e, j]
                    if gj < 0:
                        continue
                    acc = 0.0
                    for b in range(n_b):
                        acc += weights[e, b] * bases[e, b, c, i, j]
                    out[c, gi, gj] += acc
    return out


@njit(cache=True)
def scatter_vectors(table, element_vectors, n_dof):
    """Global vectors (n_config, n_dof) from element vectors (n_el, n_config, size) summed by the dof table
    (``table``: element to global index, -1 for a fixed dof).  Compiled."""
    n_el, n_c, size = element_vectors.shape
    out = np.zeros((n_c, n_dof))
    for c in range(n_c):
        for e in range(n_el):
            for i in range(size):
                gi = table[e, i]
                if gi >= 0:
                    out[c, gi] += element_vectors[e, c, i]
    return out


@njit(cache=True)
def _cholesky_solve_into(lower, r, x):
    """x = (L L^T)^-1 r for one lower factor L (d, d)."""
    d = r.size
    for i in range(d):
        s = r[i]
        for k in range(i):
            s -= lower[i, k] * x[k]
        x[i] = s / lower[i, i]
    for i in range(d - 1, -1, -1):
        s = x[i]
        for k in range(i + 1, d):
            s -= lower[k, i] * x[k]
        x[i] = s / lower[i, i]


@njit(cache=True)
def cholesky_solve_batch(lower, b):
    """Solutions x[s] of (L[s] L[s]^T) x[s] = b[s] for stacks of lower Cholesky factors (n, d, d;
    ``np.linalg.cholesky``) and right-hand sides (n, d).  Compiled: two triangular solves per system."""
    out = np.empty_like(b)
    for c in range(b.shape[0]):
        _cholesky_solve_into(lower[c], b[c], out[c])
    return out


def newmark_history(
    step_factor: FloatArray,
    k: FloatArray,
    c: FloatArray,
    f: FloatArray,
    u0: FloatArray,
    v0: FloatArray,
    a0: FloatArray,
    dt: float,
    steps: int,
    beta: float = 0.25,
    gamma: float = 0.5,
) -> FloatArray:
    """Newmark's method on M u'' + C u' + K u = F with matrices that vary periodically over ``f.shape[0]`` steps
    (angle index s of step number i is (i + 1) mod n): displacements (m) after each of ``steps`` steps of ``dt`` (s)
    from u0, v0, a0.  ``step_factor[s]`` is the lower Cholesky factor of M + gamma dt C + beta dt^2 K at angle s
    (``np.linalg.cholesky``): one factorisation per angle, reused in every revolution.  Compiled, the predictor, the
    residual and the two triangular solves in one loop; ``newmark_steps`` is the same method in numpy with a direct
    solve of the step matrix (tests/test_fem.py compares them)."""
    return _newmark_compiled(
        step_factor, k, c, f, np.asarray(u0, dtype=float), np.asarray(v0, dtype=float), np.asarray(a0, dtype=float),
        float(dt), int(steps), float(beta), float(gamma),
    )


def newmark_steps(step_matrix, k, c, f, ud, vd, ad, dt, steps, beta, gamma):
    """Newmark's method in plain numpy, each step's acceleration by a direct solve of the step matrix
    ``step_matrix[s]`` = M + gamma dt C + beta dt^2 K (the reference ``newmark_history`` is tested against)."""
    n = f.shape[0]
    history = np.empty((steps, ud.size))
    for step in range(steps):
        s = (step + 1) % n
        pred_u = ud + dt * vd + (0.5 - beta) * dt**2 * ad
        pred_v = vd + (1 - gamma) * dt * ad
        ad = np.linalg.solve(step_matrix[s], f[s] - c[s] @ pred_v - k[s] @ pred_u)
        ud = pred_u + beta * dt**2 * ad
        vd = pred_v + gamma * dt * ad
        history[step] = ud
    return history


@njit(cache=True)
def _newmark_compiled(step_factor, k, c, f, ud, vd, ad, dt, steps, beta, gamma):
    n = f.shape[0]
    d = ud.size
    history = np.empty((steps, d))
    u, v, a = ud.copy(), vd.copy(), ad.copy()
    pu, pv, r = np.empty(d), np.empty(d), np.empty(d)
    for step in range(steps):
        s = (step + 1) % n
        for i in range(d):
            pu[i] = u[i] + dt * v[i] + (0.5 - beta) * dt**2 * a[i]
            pv[i] = v[i] + (1 - gamma) * dt * a[i]
        for i in range(d):
            acc = f[s, i]
            for j in range(d):
                acc -= c[s, i, j] * pv[j] + k[s, i, j] * pu[j]
            r[i] = acc
        _cholesky_solve_into(step_factor[s], r, a)
        for i in range(d):
            u[i] = pu[i] + beta * dt**2 * a[i]
            v[i] = pv[i] + gamma * dt * a[i]
            history[step, i] = u[i]
    return history
