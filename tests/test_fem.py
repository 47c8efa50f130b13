"""Beam elements against closed forms (cantilever), with fitted convergence rates."""

import numpy as np
import pytest
from scipy.linalg import eigh

from linkwork.engines.fem import BeamMesh, assemble, local_matrices, solve_static

E, RHO, L = 70e9, 2640.0, 0.25
D = 0.008
A, I = np.pi * D**2 / 4, np.pi * D**4 / 64
BETA_L = np.array([1.8751040687, 4.6940911330, 7.8547574382])  # cantilever eigenvalues


def cantilever(kind: str, n: int):
    """A cantilever along x of n elements, clamped at node 0; returns (K, M) and the tip dof indices."""
    per_end_extra = 1 if kind == "frame6" else 2
    elements = tuple((i, i + 1) for i in range(n))
    def keys(node):
        if node == 0:  # clamped: slope held; the curvature (root moment) stays free
            return (None, "k0")[:per_end_extra]
        return tuple(f"{q}{node}" for q in ("s", "k")[:per_end_extra])
    mesh = BeamMesh(kind, n + 1, elements, tuple((keys(i), keys(i + 1)) for i in range(n)), frozenset({0}))
    k_e, m_e = local_matrices(kind, E, A, I, RHO, L / n)
    angles = np.zeros((1, n))
    k = assemble(mesh, [k_e] * n, angles)[0]
    m = assemble(mesh, [m_e] * n, angles)[0]
    n_dof, table = mesh.dof_indices()
    tip = table[-1][mesh_per_end(kind) : mesh_per_end(kind) + 2]
    return k, m, tip, table


def mesh_per_end(kind):
    return 3 if kind == "frame6" else 4


@pytest.mark.parametrize("kind", ["frame6", "quintic8"])
def test_static_tip_deflection_is_exact(kind):
    for n in (1, 3):
        k, m, tip, table = cantilever(kind, n)
        f = np.zeros(k.shape[0])
        f[tip[1]] = -10.0  # tip load P, transverse
        u = np.linalg.solve(k, f)
        assert np.isclose(u[tip[1]], -10.0 * L**3 / (3 * E * I), rtol=1e-10)
        f = np.zeros(k.shape[0])
        f[tip[0]] = 10.0  # axial
        assert np.isclose(np.linalg.solve(k, f)[tip[0]], 10.0 * L / (E * A), rtol=1e-10)


@pytest.mark.parametrize(("kind", "low", "high"), [("frame6", 3.6, 4.4), ("quintic8", 7.0, 9.5)])
def test_natural_frequencies_converge_at_the_expected_rate(kind, low, high):
    """Frequency error ~ h^(2(p-1)): about 4 for cubic, 8 for quintic Hermite elements."""
    exact = BETA_L**2 * np.sqrt(E * I / (RHO * A * L**4))
    meshes = [2, 3, 4, 6] if kind == "frame6" else [1, 2, 3]
    errors = []
    for n in meshes:
        k, m, _, _ = cantilever(kind, n)
        lam = eigh(k, m, eigvals_only=True)
        w = np.sqrt(lam[lam > 1.0])  # bending modes (axial modes are far higher)
        errors.append(abs(w[0] - exact[0]) / exact[0])
    rate = -np.polyfit(np.log(meshes), np.log(errors), 1)[0]
    assert low < rate < high, (rate, errors)
    k, m, _, _ = cantilever(kind, 8)
    w = np.sqrt(eigh(k, m, eigvals_only=True))
    bending = np.sort(w)[:3]
    assert np.allclose(bending, exact, rtol=2e-3)


def test_frame_element_matches_the_closed_form_matrix():
    from linkwork.engines.fem import frame_element_stiffness

    k_loc, _ = local_matrices("frame6", E, A, I, RHO, L)
    assert np.allclose(k_loc, frame_element_stiffness(E, A, I, (0.0, 0.0), (L, 0.0)), rtol=1e-12, atol=1e-9)


def test_static_solve_with_fixed_dofs():
    k, _, tip, _ = cantilever("frame6", 2)
    f = np.zeros(k.shape[0])
    f[tip[1]] = 1.0
    u = solve_static(k, f, [])
    assert np.isclose(u[tip[1]], L**3 / (3 * E * I))


def test_compiled_newmark_steps_equal_the_numpy_loop_and_a_closed_form():
    """The compiled Newmark loop (Cholesky factors of the step matrices, triangular solves) against the same method in
    numpy with a direct solve of each step matrix (to rounding) and, on one undamped oscillator with constant
    matrices, against the average-acceleration method's exact discrete solution: a rotation of (u, v / omega) by
    2 atan(omega dt / 2) per step."""
    from linkwork.engines.fem import newmark_history, newmark_steps

    rng = np.random.default_rng(3)
    n, d = 12, 6
    k = rng.normal(size=(n, d, d))
    c = 1e-3 * rng.normal(size=(n, d, d))
    f = rng.normal(size=(n, d))
    b = rng.normal(size=(n, d, d))
    step_matrix = b @ np.swapaxes(b, 1, 2) + d * np.eye(d)  # symmetric positive definite, as M + gamma dt C + ...
    u0, v0, a0 = rng.normal(size=(3, d))
    compiled = newmark_history(np.linalg.cholesky(step_matrix), k, c, f, u0, v0, a0, 1e-3, 5 * n)
    reference = newmark_steps(step_matrix, k, c, f, u0, v0, a0, 1e-3, 5 * n, 0.25, 0.5)
    assert np.allclose(compiled, reference, rtol=1e-12, atol=1e-12 * np.abs(reference).max())
    assert not np.array_equal(compiled[0], u0)  # the loop moved

    omega, dt, steps = 3.0, 0.05, 200
    kk, mm = np.full((1, 1, 1), omega**2), np.ones((1, 1, 1))
    factor = np.sqrt(mm + 0.25 * dt**2 * kk)
    u = newmark_history(factor, kk, np.zeros((1, 1, 1)), np.zeros((1, 1)), [1.0], [0.0], [-(omega**2)], dt, steps)[
        :, 0
    ]
    phase = 2 * np.arctan(omega * dt / 2) * np.arange(1, steps + 1)
    assert np.allclose(u, np.cos(phase), atol=1e-10)


def test_cholesky_solves_against_numpy():
    """The compiled stacked triangular solves with numpy's Cholesky factors against numpy's direct solve."""
    from linkwork.engines.fem import cholesky_solve_batch

    rng = np.random.default_rng(5)
    b = rng.normal(size=(7, 9, 9))
    a = b @ np.swapaxes(b, 1, 2) + 0.1 * np.eye(9)
    rhs = rng.normal(size=(7, 9))
    x = cholesky_solve_batch(np.linalg.cholesky(a), rhs)
    assert np.allclose(x, np.linalg.solve(a, rhs[..., None])[..., 0], rtol=1e-10)
    assert np.allclose(np.einsum("kij,kj->ki", a, x), rhs, rtol=1e-10, atol=1e-12)


def _distributed_load(kind: str, n: int, table, q_y: float, q_x0: float) -> np.ndarray:
    """Consistent nodal loads of a uniform transverse load q_y (N/m) and an axial load q_x0 (1 - x/L) (N/m) on the
    cantilever of ``cantilever``, by Gauss quadrature of the shape functions."""
    from linkwork.engines.fem import LAYOUTS, _gauss, cubic_hermite, quintic_hermite

    lay, h = LAYOUTS[kind], L / n
    xi, w = _gauss(8)
    shapes = (cubic_hermite if kind == "frame6" else quintic_hermite)(xi, h)[0]
    f = np.zeros(int(table.max()) + 1)
    for e in range(n):
        x = (e + xi) * h
        local = np.zeros(lay["size"])
        local[list(lay["transverse"])] = h * (w * q_y) @ shapes
        local[list(lay["axial"])] = h * (w * q_x0 * (1 - x / L)) @ np.stack([1 - xi, xi], axis=1)
        dofs = table[e]  # the element's dofs in its local order (-1: held)
        keep = dofs >= 0
        np.add.at(f, dofs[keep], local[keep])
    return f


@pytest.mark.parametrize("kind", ["frame6", "quintic8"])
def test_the_stress_at_the_clamp_converges_at_order_one_through_the_element_constant_axial_strain(kind):
    """The accuracy page's first-order term, on a problem with a known solution: a cantilever under a uniform transverse
    load and an axial load falling linearly to zero at the tip.  Exact at the clamp: v'' = q_y L^2 / (2 EI) and
    u' = q_x0 L / (2 EA).  The element's curvature there converges at order 2 (cubic Hermite) or is exact (quintic: the
    deflection is a quartic); its axial strain, constant over an element (linear u), is the element's mean and converges
    at order 1; so does the strain |h v''| + |u'| the transplanter's peak stress is made of."""
    from linkwork.engines.fem import LAYOUTS, _curvature_shapes, element_strain_extremes

    lay, q_y, q_x0, half = LAYOUTS[kind], 50.0, 4.0e4, D / 2
    kappa_exact, axial_exact = q_y * L**2 / (2 * E * I), q_x0 * L / (2 * E * A)
    meshes = (4, 8, 16, 32)
    bend, axial, strain = [], [], []
    for n in meshes:
        k, _, _, table = cantilever(kind, n)
        u = np.linalg.solve(k, _distributed_load(kind, n, table, q_y, q_x0))
        local = np.where(table[0] >= 0, u[np.maximum(table[0], 0)], 0.0)  # element 0's dofs (held ones zero)
        kappa = (_curvature_shapes(kind, L / n, 2) @ local[list(lay["transverse"])])[0]
        bend.append(abs(kappa - kappa_exact) / kappa_exact)
        eps = (local[lay["axial"][1]] - local[lay["axial"][0]]) / (L / n)
        axial.append(abs(eps - axial_exact) / axial_exact)
        total = half * kappa_exact + axial_exact
        strain.append(abs(element_strain_extremes(kind, L / n, half, local) - total) / total)
    order = lambda e: np.log2(e[-2] / e[-1])  # noqa: E731  (the finest pair's observed order)
    assert 0.95 < order(axial) < 1.05, axial
    if kind == "frame6":
        assert 1.9 < order(bend) < 2.1, bend
    else:
        assert max(bend) < 1e-9, bend
    assert 0.9 < order(strain) < 1.1, strain
