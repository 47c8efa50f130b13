"""The heald paper's analyses beyond the chain routes (tests/test_chains.py): independence of model B's joint
forces from the warp branch, damping ratios, kinetostatic reactions, flip points, the cam's Fourier series."""

import numpy as np
import pytest
from scipy.integrate import quad

from conftest import load_yaml
from linkwork.papers.heald.adapter import omega_grid, parameters
from linkwork.papers.heald.dynamics import (
    cam_harmonics,
    cam_profile,
    clearance_difference_for_ratio,
    damped_modes,
    flip_point,
    harmonic_transfer,
    kinetostatic_reactions,
    periodic_peaks,
    self_consistent_reactions,
)
from linkwork.papers.heald.model import build, kinetostatic_reactions_b, reduced_masses
from linkwork.papers.heald.studies import joint_forces

CFG = load_yaml("config/config.yaml")["heald"]
P = parameters(CFG)
W = omega_grid(CFG["speeds"])


@pytest.mark.parametrize("change", [{"k_O": 7.0e3}, {"M_P": 11.5}, {"c_O": 75.0}, {"k_O": 4.5e4, "M_P": 5.5, "c_O": 6.0}])
def test_model_b_joint_forces_do_not_depend_on_the_warp_branch(change):
    """Under a velocity drive each branch on the driven node sees the prescribed motion: moving the warp branch's
    parameters leaves Q_E and Q_F unchanged to round-off, while the drive force Q does change (the test can fail)."""
    q0, e0, f0, _ = joint_forces("B", P, "elastic", W, 1e-4)
    q1, e1, f1, _ = joint_forces("B", {**P, **change}, "elastic", W, 1e-4)
    np.testing.assert_allclose(e1, e0, rtol=1e-8, atol=0)
    np.testing.assert_allclose(f1, f0, rtol=1e-8, atol=0)
    assert np.max(np.abs(q1 - q0) / np.abs(q0)) > 1e-3


def test_model_a_joint_forces_do_depend_on_the_warp_branch():
    """The contrast: in the physical linkage the warp spring loads both joints."""
    _, e0, _, _ = joint_forces("A", P, "elastic", W, 1e-4)
    _, e1, _, _ = joint_forces("A", {**P, "k_O": 7.0e3}, "elastic", W, 1e-4)
    assert np.max(np.abs(e1 - e0) / np.abs(e0)) > 1e-2


def test_damping_ratio_of_model_b_warp_mode_is_the_closed_form():
    """Complex eigenvalues against zeta = c / (2 sqrt(k m)) of the warp branch (D held), and the undamped joints."""
    wn, zeta = damped_modes(build("B", P, "elastic"), held=True)
    closed = P["c_O"] / (2 * np.sqrt(P["k_O"] * P["M_P"]))
    k = int(np.argmin(np.abs(wn - np.sqrt(P["k_O"] / P["M_P"]))))
    assert zeta[k] == pytest.approx(closed, rel=1e-12)
    assert np.sqrt(P["k_O"] / P["M_P"]) == pytest.approx(wn[k], rel=1e-12)
    assert np.allclose(np.delete(zeta, k), 0.0, atol=1e-12)


def test_damped_modes_match_the_undamped_resonances_without_damping():
    """With the dampers removed, |lambda| are the resonances (held) and antiresonances (free) of the engine."""
    from linkwork.engines.chains import resonances

    p = {**P, "c_O": 0.0, "c_joint": 0.0}
    vel, force = resonances(build("A", p, "elastic"))
    np.testing.assert_allclose(damped_modes(build("A", p, "elastic"), held=True)[0], vel, rtol=1e-9)
    np.testing.assert_allclose(damped_modes(build("A", p, "elastic"), held=False)[0], force, rtol=1e-9)


def test_model_b_kinetostatic_reactions_closed_form_against_the_network():
    """The closed form of model B's reactions against the ideal-joint network solved at the operating speed."""
    np.testing.assert_allclose(kinetostatic_reactions_b(P), kinetostatic_reactions("B", P), rtol=1e-9)
    m_e, _ = reduced_masses(P)
    assert kinetostatic_reactions_b(P)[0] == pytest.approx(m_e * P["omega_op"] ** 2 * P["stroke_D"], rel=1e-2)  # rigid limit


def test_model_b_ignores_the_assumed_reactions():
    _, e0, f0, _ = joint_forces("B", P, "elastic", W, 1e-4)
    _, e1, f1, _ = joint_forces("B", {**P, "reaction_E": 17.0, "reaction_F": 555.0}, "elastic", W, 1e-4)
    np.testing.assert_array_equal(e0, e1)
    np.testing.assert_array_equal(f0, f1)


def test_self_consistent_reactions_reproduce_themselves_and_follow_the_clearance_difference():
    """Fixed point: the chain's forces with k_tau(R) are R; quasi-statically R_E - R_F = k_n (Delta_F - Delta_E)."""
    sc = self_consistent_reactions(P)
    assert sc["converged"]
    assert sc["ratio"] == pytest.approx(1.0, rel=1e-6)  # equal clearances, symmetric linkage
    r = sc["R_E"]
    assert sc["split_slope"] == pytest.approx(P["k_n"] * P["clearance_E"] / (P["k_n"] * P["clearance_E"] + r), rel=2e-2)
    delta = clearance_difference_for_ratio(P, 3.0)
    q = self_consistent_reactions({**P, "clearance_F": P["clearance_E"] + delta})
    assert q["ratio"] == pytest.approx(3.0, rel=1e-5)
    assert q["R_E"] - q["R_F"] == pytest.approx(P["k_n"] * delta, rel=5e-2)


def test_flip_point_bisection():
    assert flip_point(lambda x: x**2 > 2.0, 1.0, 3.0, 1e-9) == pytest.approx(np.sqrt(2.0), rel=1e-8)
    assert flip_point(lambda x: x < -5.0, 0.0, 3.0, 1e-9) != flip_point(lambda x: x < -5.0, 0.0, 3.0, 1e-9)  # NaN: no flip


def test_cam_fourier_coefficients_against_quadrature_and_the_profile():
    """FFT coefficients against the Fourier integrals by quadrature; the series reconstructs the profile."""
    beta = 0.3
    c = cam_harmonics(beta, 12, 4096)
    for h in (1, 3, 5):
        re = quad(lambda t: cam_profile(np.array([t]), beta)[0] * np.cos(h * t), 0, 2 * np.pi, limit=200)[0] / np.pi
        im = -quad(lambda t: cam_profile(np.array([t]), beta)[0] * np.sin(h * t), 0, 2 * np.pi, limit=200)[0] / np.pi
        assert c[h - 1] == pytest.approx(re + 1j * im, abs=1e-7)
    theta = np.linspace(0, 2 * np.pi, 500, endpoint=False)
    full = cam_harmonics(beta, 200, 4096)
    series = 0.5 + np.real(np.exp(1j * np.outer(theta, np.arange(1, 201))) @ full)
    assert np.max(np.abs(series - cam_profile(theta, beta))) < 1e-4
    assert np.allclose(c[1::2], 0.0, atol=1e-12)  # half-wave symmetry: no even harmonics


def test_periodic_peaks_of_one_harmonic_are_the_amplitude():
    """A pure first harmonic: the peak over a turn is the harmonic amplitude |Q|."""
    tr = harmonic_transfer("A", P, W[:50], 3)
    pe, pf = periodic_peaks(tr, np.array([1e-4, 0.0, 0.0]), 4096)
    _, e, f, _ = joint_forces("A", P, "elastic", W[:50], 1e-4)
    np.testing.assert_allclose(pe, np.abs(e), rtol=1e-5)
    np.testing.assert_allclose(pf, np.abs(f), rtol=1e-5)


def test_damping_ratios_of_undamped_modes_are_plain_zero():
    """Model B's joint branches have no damper: their damping ratio is 0, never a negative zero or a round-off negative
    (the report printed '-0.0000')."""
    _, zeta = damped_modes(build("B", P, "elastic"), held=True)
    assert (zeta >= 0).all() and not np.signbit(zeta).any()
    assert (zeta == 0).sum() == 2


def test_bounded_text_places_the_ends_at_the_located_boundaries():
    from linkwork.papers.heald.findings import bounded_text

    x = np.array([1.0, 2.0, 3.0, 4.0, 5.0])
    ok = np.array([False, True, True, False, False])
    assert bounded_text(x, ok, lambda i: x[i] + 0.25) == "1.25–3.25"
    assert bounded_text(x, np.array([False, False, True, True, True]), lambda i: 2.5) == "2.5–5"
    assert bounded_text(x, np.ones(5, bool), lambda i: 0.0).startswith("all of")


def test_sweep_boundary_is_the_flip_value_or_the_closed_form():
    """Along a one-input sweep the range table's ends are the flip table's bisection values (so both tables print the
    same number); where the flip table has none, a bisection of its own, checked against model B's closed form
    sqrt(k_O/M_P) = upper end of the limit's band."""
    import xarray as xr

    from linkwork.papers.heald.findings import sweep_boundary

    published = load_yaml("config/published/heald.yaml")
    flips = xr.Dataset({"flip_model": ("flip", np.array(["B"], dtype=object)), "flip_claim": ("flip", np.array(["limit_41_89"], dtype=object)),
                        "flip_input": ("flip", np.array(["M_P"], dtype=object)), "flip_value": ("flip", [9.4213])})
    boundary = sweep_boundary(CFG, published, flips)
    assert boundary("B", "limit_41_89", "heald_mass", 9.0, 9.5) == 9.4213
    flips["flip_value"] = ("flip", [99.0])  # not in the bracket: located afresh
    upper = 41.89 * 1.10
    closed = P["k_O"] / upper**2
    assert boundary("B", "limit_41_89", "heald_mass", 9.0, 9.5) == pytest.approx(closed, rel=2e-3)
    # the reaction-ratio sweep is reaction_E over the assumed reaction_F
    flips = xr.Dataset({"flip_model": ("flip", np.array(["A"], dtype=object)), "flip_claim": ("flip", np.array(["force_E_many_times_F"], dtype=object)),
                        "flip_input": ("flip", np.array(["reaction_E"], dtype=object)), "flip_value": ("flip", [312.5])})
    assert sweep_boundary(CFG, published, flips)("A", "force_E_many_times_F", "reaction_ratio", 3.0, 3.2) == pytest.approx(312.5 / P["reaction_F"])


def test_cam_window_and_notes():
    """The significance window of each harmonic, and the summary's note on a verdict the cam changes."""
    import xarray as xr

    from linkwork.papers.heald.findings import notes

    f = xr.Dataset({"verdict_sine_nominal": (("model", "claim"), np.array([["matches", "deviates"]], dtype=object)),
                    "verdict_cam_nominal": (("model", "claim"), np.array([["deviates", "deviates"]], dtype=object))},
                   coords={"model": ["B"], "claim": ["forces_grow_with_frequency", "limit_41_89"]})
    text = notes(xr.Dataset(), f)
    assert "model B, forces grow: matches → deviates" in text and "limit" not in text
    from linkwork.papers.heald.studies import cam_study

    variables, _ = cam_study(CFG, P, ["B"], W[:20], 1e-4)
    amp, low = variables["cam_harmonic_amplitude"].values, variables["cam_harmonic_window_low"].values
    assert low[6] == pytest.approx(amp[8])  # h = 7: the strongest higher one is h = 9
    assert low[-1] == 0.0


# --- eq. (2) holds only for a massless driven node (issue 22) ---------------------------------------------------


def test_eq2_is_the_chain_mobility_when_the_driven_node_has_no_mass():
    """With m_D = m_E6 = m_F6 = 0 the network's mobility of model B (with the node-mass element, of mass 0) is eq. (2)
    to round-off."""
    from linkwork.papers.heald.model import eq2_node_mass_difference

    diff, _ = eq2_node_mass_difference({**P, "m_D": 0.0, "m_E6": 0.0, "m_F6": 0.0}, W)
    assert diff < 1e-8


def test_eq2_breaks_with_the_rod_mass_on_the_driven_node():
    """With the assumed rod masses on D the network differs from eq. (2); the difference is the closed form
    |j w m K_2 / (1 + j w m K_2)| (a second route), it exceeds 10 near the chain's shifted antiresonance and tends to
    m / (m + sum of branch masses) at low frequency."""
    from linkwork.papers.heald.model import eq2_mobility, eq2_node_mass_difference, eq2_with_node_mass, model_b_parameters, node_mass, reduced_masses

    u = {**P, "c_joint": 0.0, "c_O": 0.0}
    diff, at = eq2_node_mass_difference(P, W)
    k2, _, _ = eq2_mobility(u, W)
    closed = np.abs(eq2_with_node_mass(u, W) - k2) / np.abs(k2)
    assert diff == pytest.approx(float(closed.max()), rel=1e-6)
    assert at == pytest.approx(float(W[np.argmax(closed)]))
    assert diff > 10.0
    m = node_mass(P)
    low = np.array([W[0] * 1e-3])
    k_low, _, _ = eq2_mobility(u, low)
    branch_mass = sum(reduced_masses(model_b_parameters(u))) + P["M_P"]
    assert float(np.abs(eq2_with_node_mass(u, low) - k_low)[0] / np.abs(k_low)[0]) == pytest.approx(m / (m + branch_mass), rel=1e-4)


# --- the inputs each model reads (issue 22: model B's table lists only these) ---------------------------------


@pytest.mark.parametrize("model", ["A", "B"])
def test_listed_inputs_are_exactly_those_that_move_the_model(model):
    """Each labelled parameter moved by 30 % (c_joint, 0 at its assumed value, set to 50 N s/m): the model's drive force,
    joint forces and resonances move for every listed input and for no other (the listing in the report's input
    tables is this one)."""
    from linkwork.engines.chains import resonances
    from linkwork.papers.heald.model import MODEL_INPUTS
    from linkwork.papers.heald.studies import lowest_resonance

    def state(cfg_params):
        p = parameters({**CFG, "parameters": cfg_params})
        q, e, f, _ = joint_forces(model, p, "elastic", W, 1e-4)
        vel, force = resonances(build(model, {**p, "c_joint": 0.0, "c_O": 0.0}, "elastic"))
        return np.concatenate([np.abs(q), np.abs(e), np.abs(f), vel, force, [lowest_resonance(model, p)]])

    base = state(CFG["parameters"])
    moving = set()
    for name, entry in CFG["parameters"].items():
        value = entry["value"] * 1.3 if entry["value"] else 50.0
        moved_state = state({**CFG["parameters"], name: {**entry, "value": value}})
        if np.max(np.abs(moved_state - base) / np.maximum(np.abs(base), 1e-300)) > 1e-9:
            moving.add(name)
    assert moving == set(MODEL_INPUTS[model])
