"""Mechanical chains: four routes agree, eq. (2) for model B, hard cases, bad input."""

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st
from scipy.signal import freqresp

from conftest import load_yaml
from linkwork.engines.chains import (
    GROUND,
    Element,
    Lever,
    Network,
    Parallel,
    Series,
    _frobenius_conditions,
    near_singular,
    network_system,
    resonances,
    series_parallel_mobility,
    solve_matrices,
    solve_network,
    state_space,
    vulfson_stiffness,
)
from linkwork.papers.heald.adapter import parameters
from linkwork.papers.heald.model import build, eq2_mobility, joint_stiffness, model_a, model_b, model_b_tree

P = parameters(load_yaml("config/config.yaml")["heald"])
W = np.linspace(1.0, 400.0, 997)


def _rel(a, b):
    """Normwise relative difference max|a - b| / max|b| (element-wise ratios blow up at antiresonances)."""
    return np.max(np.abs(a - b)) / np.max(np.abs(b))


@pytest.mark.parametrize("model", ["A", "B"])
@pytest.mark.parametrize("variant", ["ideal", "elastic"])
def test_network_and_matrix_routes_agree(model, variant):
    net = build(model, P, variant)
    r = solve_network(net, W, 1j * W * 1e-4)
    q, v = solve_matrices(net, W, 1j * W * 1e-4)
    assert _rel(q, r.input_force) < 1e-9
    assert np.max(np.abs(v - r.velocity)) < 1e-9 * np.max(np.abs(r.velocity))


def test_series_parallel_and_eq2_match_the_network_for_model_b():
    undamped = {**P, "c_joint": 0.0, "c_O": 0.0, "eta8": 1.7}  # unequal E and F branches: strict interlacing
    net = model_b(undamped)
    k_net = 1.0 / solve_network(net, W, 1.0).input_force
    k_tree = series_parallel_mobility(model_b_tree(undamped), W)
    k_eq2, zeros, poles = eq2_mobility(undamped, W)
    assert _rel(k_tree, k_net) < 1e-9
    assert _rel(k_eq2, k_net) < 1e-9
    # interlacing of velocity resonances (zeros of K) and force resonances (poles)
    assert zeros[0] < poles[0] < zeros[1] < poles[1] < zeros[2]
    vel, force = resonances(net)
    assert np.allclose(np.sort(vel), zeros, rtol=1e-9) and np.allclose(np.sort(force), poles, rtol=1e-9)


@pytest.mark.filterwarnings("ignore:Badly conditioned filter coefficients")  # scipy's internal ss -> zpk step
@pytest.mark.parametrize("model", ["A", "B"])
def test_state_space_route(model):
    """Force-driven versions of both models: the state-space model's frequency response equals the network's,
    evaluated directly as C (jwI - A)^-1 B (to 1e-9) and by scipy.signal through zeros, poles and gain.  That
    conversion is badly conditioned (scipy warns) and its rounding follows the machine's BLAS kernels: 2.5e-9 for
    model B on one EPYC, below 1e-9 on another, so scipy's route is held to 1e-7."""
    p = {**P, "c_joint": 5.0}
    net = build(model, p, "elastic")
    if model == "B":  # the driven node needs mass for a state-space model
        net = Network(
            net.nodes, (*net.elements, Element("drive_mass", "mass", "D", GROUND, 0.5)), net.levers, "D", "force"
        )
    else:
        net = Network(net.nodes, net.elements, net.levers, "D", "force")
    ss = state_space(net)
    r = solve_network(net, W, 1.0)
    eye = np.eye(ss.A.shape[0])
    direct = np.array([(ss.C @ np.linalg.solve(1j * w * eye - ss.A, ss.B))[0, 0] for w in W]) + ss.D[0, 0]
    assert _rel(direct, r.input_velocity) < 1e-9
    _, h = freqresp(ss.to_zpk(), W)
    assert _rel(h, r.input_velocity) < 1e-7


@st.composite
def random_chains(draw):
    """Random series chains with side masses: node i -- spring/damper -- node i+1, mass on every node."""
    n = draw(st.integers(2, 6))
    nodes = tuple(f"n{i}" for i in range(n))
    els = []
    for i in range(n - 1):
        els.append(Element(f"k{i}", "spring", nodes[i], nodes[i + 1], draw(st.floats(1e3, 1e7))))
        els.append(Element(f"c{i}", "damper", nodes[i], nodes[i + 1], draw(st.floats(0.1, 50.0))))
    for i in range(n):
        els.append(Element(f"m{i}", "mass", nodes[i], GROUND, draw(st.floats(0.1, 10.0))))
    els.append(Element("anchor", "spring", nodes[-1], GROUND, draw(st.floats(1e3, 1e6))))
    return Network(nodes, tuple(els), (), "n0", draw(st.sampled_from(["velocity", "force"])))


HYPOTHESIS_FOUND = Network(
    ("n0", "n1"),
    (
        Element("k0", "spring", "n0", "n1", 9999960.0), Element("c0", "damper", "n0", "n1", 1.0),
        Element("m0", "mass", "n0", GROUND, 0.109375), Element("m1", "mass", "n1", GROUND, 0.1),
        Element("anchor", "spring", "n1", GROUND, 1000.0),
    ),
    (),
    "n0",
    "force",
)


@settings(max_examples=40, deadline=None)
@given(random_chains())
@example(HYPOTHESIS_FOUND)
def test_routes_agree_on_random_chains(net):
    """The routes agree to within the conditioning of the case: random chains reach damping ratios below 1e-4
    next to stiffness ratios of 1e4, where route 1's matrix has a condition number of 1e8 or more near a
    resonance.  The bound is 10 eps times the largest (Frobenius) condition number over the grid, or 1e-8 where
    that is smaller (the paper's mechanisms, better conditioned, meet 1e-9 above).  Hypothesis found a chain
    with k = 1e7 N/m, c = 1 N s/m on 0.1 kg (condition 2.3e8) whose routes differ by 2.0e-8."""
    r = solve_network(net, W, 1.0)
    q, v = solve_matrices(net, W, 1.0)
    a, _ = network_system(net, W, np.ones(W.size, dtype=complex))
    condition = max(np.linalg.cond(m, "fro") for m in a)
    bound = max(1e-8, 10 * np.finfo(float).eps * condition)
    if net.drive == "velocity":
        assert _rel(q, r.input_force) < bound
    else:
        assert _rel(q, r.input_velocity) < bound


def test_series_parallel_reduction_with_a_lever():
    k, m, eta = 2e5, 3.0, 2.5
    tree = Series((Element("k", "spring", "a", "b", k), Parallel((Element("m", "mass", "b", GROUND, m),))))
    net = Network(
        ("a", "b", "c"), (Element("k", "spring", "a", "b", k), Element("m", "mass", "c", GROUND, m)),
        (Lever("l", "b", "c", eta),), "a",
    )
    from linkwork.engines.chains import Through

    tree = Series((Element("k", "spring", "a", "b", k), Through(eta, Element("m", "mass", "b", GROUND, m))))
    assert _rel(series_parallel_mobility(tree, W), 1 / solve_network(net, W, 1.0).input_force) < 1e-9


def test_model_a_force_ratio_is_the_joint_stiffness_ratio():
    _, q_e, q_f = (
        solve_network(model_a(P), W, 1j * W * 1e-4).element_force[k] for k in ("joint_E", "joint_E", "joint_F")
    )
    ratio = np.abs(q_e) / np.abs(q_f)
    assert np.allclose(ratio, joint_stiffness(P, "E", "elastic") / joint_stiffness(P, "F", "elastic"), rtol=1e-9)


# --- hard cases ----------------------------------------------------------------------------------


@pytest.mark.hard
def test_exactly_at_a_resonance():
    undamped = {**P, "c_joint": 0.0, "c_O": 0.0}
    vel, _ = resonances(model_b(undamped))
    r = solve_network(model_b(undamped), np.array([vel[0], 1.01 * vel[0]]), 1.0)
    assert r.singular.tolist() == [True, False]  # flagged, no exception, no garbage
    assert np.isnan(r.input_force[0]) and np.isfinite(r.input_force[1])
    damped = solve_network(model_b(P), np.array([vel[0]]), 1.0)  # c_O > 0: finite
    assert not damped.singular[0] and np.isfinite(damped.input_force[0])


def test_near_singular_agrees_with_the_svd_condition_number():
    """Second route: matrices built from chosen singular values; the Frobenius check flags every one whose
    2-norm reciprocal condition is far below rcond and none far above it (the two differ by at most n)."""
    rng = np.random.default_rng(7)
    n, count, rcond = 7, 400, 1e-13

    def unitary():
        q, _ = np.linalg.qr(rng.normal(size=(n, n)) + 1j * rng.normal(size=(n, n)))
        return q

    exponents = rng.uniform(-18, -8, count)
    a = np.array([unitary() @ np.diag(np.r_[1.0, rng.uniform(1e-3, 1, n - 2), 10.0**e]) @ unitary() for e in exponents])
    s = np.linalg.svd(a, compute_uv=False)
    svd_rcond = s[:, -1] / s[:, 0]
    flagged = near_singular(a, rcond)
    assert np.all(flagged[svd_rcond < rcond / (10 * n)])
    assert not np.any(flagged[svd_rcond > 10 * n * rcond])
    assert near_singular(np.zeros((1, n, n), dtype=complex), rcond).tolist() == [True]


def test_compiled_frobenius_condition_agrees_with_numpy_inverse():
    """Second route: the compiled LU condition equals |S|_F |S^-1|_F with numpy's equilibration and batched inverse
    (to rounding), on random complex matrices of mixed scales (rows and columns scaled over ten decades)."""
    rng = np.random.default_rng(11)
    n, count = 6, 200
    a = (rng.normal(size=(count, n, n)) + 1j * rng.normal(size=(count, n, n))) * 10.0 ** rng.uniform(
        -5, 5, (count, n, 1)
    ) * 10.0 ** rng.uniform(-5, 5, (count, 1, n))
    mag = np.abs(a)
    row = mag.max(axis=2, keepdims=True)
    scaled = a / row / (mag / row).max(axis=1, keepdims=True)
    expected = np.linalg.norm(scaled, axis=(1, 2)) * np.linalg.norm(np.linalg.inv(scaled), axis=(1, 2))
    assert np.allclose(_frobenius_conditions(a), expected, rtol=1e-9, atol=0.0)
    a[3, 2] = 0.0  # a zero row: singular, flagged
    assert np.isinf(_frobenius_conditions(a)[3])


@pytest.mark.hard
def test_zero_clearance_recovers_the_ideal_joint():
    tiny = {**P, "clearance_E": 1e-15, "clearance_F": 1e-15}
    for model in ("A", "B"):
        a = solve_network(build(model, tiny, "elastic"), W, 1.0).element_force["joint_E"]
        b = solve_network(build(model, P, "ideal"), W, 1.0).element_force["joint_E"]
        assert _rel(a, b) < 1e-6
    # and a very stiff pin approaches the rigid joint (a lever of ratio 1): the difference is the
    # physical (w / w_n)^2 = w^2 m / k, about 3e-5 here, not round-off
    stiff = Network(
        ("D", "e"), (Element("j", "spring", "D", "e", 1e10), Element("m", "mass", "e", GROUND, 2.0)), (), "D"
    )
    rigid = Network(("D", "e"), (Element("m", "mass", "e", GROUND, 2.0),), (Lever("j", "D", "e", 1.0),), "D")
    diff = _rel(solve_network(stiff, W, 1.0).input_force, solve_network(rigid, W, 1.0).input_force)
    assert diff < 1.1 * W.max() ** 2 * 2.0 / 1e10


@pytest.mark.hard
def test_vulfson_limits_without_division_errors():
    with np.errstate(all="raise"):
        assert vulfson_stiffness(0.0, 1e-4, 5e7) == 0.0
        assert vulfson_stiffness(0.0, 0.0, 5e7) == 5e7
        assert vulfson_stiffness(300.0, 0.0, 5e7) == 5e7
        assert np.all(np.isfinite(vulfson_stiffness(np.array([0.0, 1e-9, 1.0]), np.array([0.0, 1e-4, 1e-4]), 5e7)))
    # large clearance: k_tau -> |R| / Delta
    assert np.isclose(vulfson_stiffness(10.0, 1.0, 5e7), 10.0, rtol=1e-6)


@pytest.mark.hard
def test_low_frequency_limit():
    w = np.array([1e-6, 1e-3])
    r = solve_network(model_a(P), w, 1j * w * 1e-4)
    # quasi-static: the joints carry the warp's static load through the levers, in series with their compliance
    k_joints = joint_stiffness(P, "E", "elastic") + joint_stiffness(P, "F", "elastic")
    k_warp = P["eta7"] ** 2 * P["k_O"]  # (eta7 = eta8) the warp seen at E and F
    total = np.abs(r.element_force["joint_E"] + r.element_force["joint_F"])
    assert np.allclose(total, k_warp * 1e-4 / (1 + k_warp / k_joints), rtol=1e-6)
    with pytest.raises(ValueError, match="> 0"):
        solve_network(model_a(P), np.array([0.0]))


def test_bad_networks_are_rejected():
    with pytest.raises(ValueError, match="element m: mass must be >= 0"):
        Network(("a",), (Element("m", "mass", "a", GROUND, -1.0),), (), "a")
    with pytest.raises(ValueError, match="lever l: ratio must be non-zero"):
        Network(("a", "b"), (Element("m", "mass", "a", GROUND, 1.0),), (Lever("l", "a", "b", 0.0),), "a")
    with pytest.raises(ValueError, match="undeclared node 'z'"):
        Network(("a",), (Element("k", "spring", "a", "z", 1.0),), (), "a")


def test_interlacing_of_zeros_and_poles():
    from linkwork.papers.heald.studies import interlaced

    assert interlaced(np.array([1.0, 3.0, 5.0]), np.array([2.0, 4.0]))
    assert not interlaced(np.array([1.0, 2.0, 5.0]), np.array([3.0, 4.0]))
    assert not interlaced(np.array([2.0, 4.0]), np.array([1.0, 3.0, 5.0]))  # must start with a zero
    assert interlaced(np.array([1.0, 3.0, 3.0]), np.array([2.0, 3.0]))  # equal branches: a pole on a double zero
    w = np.linspace(10, 1000, 50)
    _, num, den = eq2_mobility(P, w)
    assert interlaced(num, den)  # the property the paper's form relies on, at the assumed parameters
