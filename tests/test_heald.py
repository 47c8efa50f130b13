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
from linkwork.papers.heald.dynamics import joint_forces

CFG = load_yaml("config/config.yaml")["heald"]
P = parameters(CFG)
W = omega_grid(CFG["speeds"])


@pytest.mark.parametrize(
    "change", [{"k_O": 7.0e3}, {"M_P": 11.5}, {"c_O": 75.0}, {"k_O": 4.5e4, "M_P": 5.5, "c_O": 6.0}]
)
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
    assert kinetostatic_reactions_b(P)[0] == pytest.approx(
        m_e * P["omega_op"] ** 2 * P["stroke_D"], rel=1e-2
    )  # rigid limit


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
    assert flip_point(lambda x: x < -5.0, 0.0, 3.0, 1e-9) != flip_point(
        lambda x: x < -5.0, 0.0, 3.0, 1e-9
    )  # NaN: no flip


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
    flips = xr.Dataset(
        {
            "flip_model": ("flip", np.array(["B"], dtype=object)),
            "flip_claim": ("flip", np.array(["limit_41_89"], dtype=object)),
            "flip_input": ("flip", np.array(["M_P"], dtype=object)),
            "flip_value": ("flip", [9.4213]),
        }
    )
    boundary = sweep_boundary(CFG, published, flips)
    assert boundary("B", "limit_41_89", "heald_mass", 9.0, 9.5) == 9.4213
    flips["flip_value"] = ("flip", [99.0])  # not in the bracket: located afresh
    upper = 41.89 * 1.10
    closed = P["k_O"] / upper**2
    assert boundary("B", "limit_41_89", "heald_mass", 9.0, 9.5) == pytest.approx(closed, rel=2e-3)
    # the reaction-ratio sweep is reaction_E over the assumed reaction_F
    flips = xr.Dataset(
        {
            "flip_model": ("flip", np.array(["A"], dtype=object)),
            "flip_claim": ("flip", np.array(["force_E_many_times_F"], dtype=object)),
            "flip_input": ("flip", np.array(["reaction_E"], dtype=object)),
            "flip_value": ("flip", [312.5]),
        }
    )
    assert sweep_boundary(CFG, published, flips)(
        "A", "force_E_many_times_F", "reaction_ratio", 3.0, 3.2
    ) == pytest.approx(312.5 / P["reaction_F"])


def test_cam_window_and_notes():
    """The significance window of each harmonic, and the summary's note on a verdict the cam changes."""
    import xarray as xr

    from linkwork.papers.heald.findings import notes

    f = xr.Dataset(
        {
            "verdict_sine_nominal": (("model", "claim"), np.array([["reproduced", "differs"]], dtype=object)),
            "verdict_cam_nominal": (("model", "claim"), np.array([["differs", "differs"]], dtype=object)),
            "verdict_cam_by_joint_damping": (
                ("model", "claim", "joint_damping"),
                np.array([[["differs", "reproduced"], ["differs", "differs"]]], dtype=object),
            ),
            "largest_dip_cam_by_joint_damping": (("model", "joint_damping"), [[0.765, 0.0012]]),
            "joint_branch_damping_ratio": (("model", "joint_damping"), [[0.0, 0.0498]]),
        },
        coords={"model": ["B"], "claim": ["forces_grow_with_frequency", "limit_41_89"], "joint_damping": [0.0, 500.0]},
    )
    text = notes(xr.Dataset(), f)
    assert "model B, forces grow: reproduced → differs" in text and "limit" not in text
    assert (
        "(500 N s/m, a damping ratio of 0.050)" in text
        and "is reproduced instead" in text
        and "from 76% to 0.12%" in text
    )
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
    from linkwork.papers.heald.model import (
        eq2_mobility, eq2_node_mass_difference, eq2_with_node_mass, model_b_parameters, node_mass, reduced_masses,
    )

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
    assert float(np.abs(eq2_with_node_mass(u, low) - k_low)[0] / np.abs(k_low)[0]) == pytest.approx(
        m / (m + branch_mass), rel=1e-4
    )


# --- the inputs each model reads (issue 22: model B's table lists only these) ---------------------------------


@pytest.mark.parametrize("model", ["A", "B"])
def test_listed_inputs_are_exactly_those_that_move_the_model(model):
    """Each labelled parameter moved by 30 % (c_joint, 0 at its assumed value, set to 50 N s/m): the model's drive
    force, joint forces and resonances move for every listed input and for no other (the listing in the report's input
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
    from linkwork.papers.heald.uncertainty import model_inputs

    listed = {i.path for i in model_inputs(CFG, model)}
    assert listed == {f"parameters.{n}.value" for n in MODEL_INPUTS[model] if "range" in CFG["parameters"][n]} | {
        "drive.frequency.value"
    }


# --- the drive frequency as a scenario (issue 22) ------------------------------------------------------------


def test_half_shaft_drive_is_the_shaft_drive_at_half_the_speed():
    """A drive at half the shaft frequency gives at shaft speed W what the shaft drive gives at W / 2 (a second
    route: the frequency axis rescaled by hand, the operating speed of model B's kinetostatic reactions with it), and
    the shaft speed at which the drive meets the lowest resonance doubles."""
    from linkwork.papers.heald.adapter import DRIVE_RATIO, drive_ratio
    from linkwork.papers.heald.studies import lowest_resonance

    half = {**P, "drive_ratio": DRIVE_RATIO["half-shaft"]}
    for model in ("A", "B"):
        got = joint_forces(model, half, "elastic", W, 1e-4)
        ref = joint_forces(model, {**P, "omega_op": P["omega_op"] / 2}, "elastic", W / 2, 1e-4)
        for a, b in zip(got[:3], ref[:3], strict=True):
            np.testing.assert_allclose(a, b, rtol=1e-12)
        assert lowest_resonance(model, half) == pytest.approx(2 * lowest_resonance(model, P), rel=1e-12)
    assert P["drive_ratio"] == 1.0
    assert drive_ratio({**CFG, "drive": {"frequency": {**CFG["drive"]["frequency"], "value": "half-shaft"}}}) == 0.5
    with pytest.raises(ValueError, match="unknown drive frequency"):
        drive_ratio({**CFG, "drive": {"frequency": {**CFG["drive"]["frequency"], "value": "quarter"}}})


def test_drive_choice_is_a_labelled_scenario_the_uncertainty_study_sees():
    """The drive frequency is a labelled choice with readable labels, and the study's inputs carry it as a choice
    (the core runs it as a scenario, never samples a number for it)."""
    from linkwork.papers.heald.adapter import DRIVE_RATIO
    from linkwork.papers.heald.uncertainty import inputs

    entry = CFG["drive"]["frequency"]
    assert set(entry["choices"]) == set(DRIVE_RATIO) and len(entry["choice_labels"]) == len(entry["choices"])
    drive = [i for i in inputs(CFG) if i.path == "drive.frequency.value"]
    assert len(drive) == 1 and drive[0].choices == tuple(entry["choices"])


# --- corners of the declared ranges (issue 22: the core's bounded search needs a known target) -----------------


def test_model_a_lowest_resonance_at_the_soft_heavy_corner_is_the_closed_form():
    """At R = 10 N, Delta = 0.3 mm, k_n = 2e7 N/m, eta = 2.5, k_O = 5e3 N/m and every mass at its heaviest (M_P = 12 kg)
    model A with D held is one degree of freedom: the frame P with the levers' springs and masses reduced to it, w^2 =
    (k_O + (k_E + k_F) / eta^2) / (M_out + (m_E7 + m_F8) / eta^2), about 31 rad/s (the samples reported 72-721)."""
    from linkwork.engines.chains import vulfson_stiffness
    from linkwork.papers.heald.studies import lowest_resonance

    corner = dict(P)
    for name, entry in CFG["parameters"].items():
        if name.startswith(("m_", "M_")):
            corner[name] = entry["range"][1]
    corner.update(
        reaction_E=10.0, reaction_F=10.0, clearance_E=3e-4, clearance_F=3e-4, k_n=2e7, eta7=2.5, eta8=2.5, k_O=5e3,
        M_P=12.0,
    )
    k_tau = float(vulfson_stiffness(10.0, 3e-4, 2e7))
    m_out = corner["M_G"] + corner["m_H9"] + corner["M_K"] + corner["m_L10"] + corner["M_P"]
    closed = np.sqrt((5e3 + 2 * k_tau / 2.5**2) / (m_out + (corner["m_E7"] + corner["m_F8"]) / 2.5**2))
    assert lowest_resonance("A", corner) == pytest.approx(closed, rel=1e-9)
    assert 30.0 < closed < 32.0
    # the same corner through the study's results function, the one the core's bounded search evaluates
    from linkwork.papers.heald.uncertainty import results

    values = {
        **{n: e["range"][1] for n, e in CFG["parameters"].items() if n.startswith(("m_", "M_"))},
        "reaction_E": 10.0,
        "reaction_F": 10.0,
        "clearance_E": 3e-4,
        "clearance_F": 3e-4,
        "k_n": 2e7,
        "eta7": 2.5,
        "eta8": 2.5,
        "k_O": 5e3,
        "M_P": 12.0,
    }
    cfg = {**CFG, "parameters": {n: {**e, "value": values.get(n, e["value"])} for n, e in CFG["parameters"].items()}}
    (ds,) = results(cfg)
    assert float(ds.first_resonance.sel(model="A")) == pytest.approx(closed, rel=1e-9)


# --- the dwell-cam clause with damped joints (issue 22) ------------------------------------------------------


def test_largest_dip_is_the_largest_relative_fall():
    from linkwork.papers.heald.studies import largest_dip

    assert largest_dip(np.array([1.0, 2.0, 3.0])) == 0.0
    assert largest_dip(np.array([1.0, 4.0, 3.0, 5.0]), np.array([2.0, 1.0, 3.0, 4.0])) == pytest.approx(0.5)


def test_joint_damping_shrinks_the_cam_dips_of_model_b():
    """Model B's joint branches: undamped, the cam's 9th harmonic meeting them near the top of the band makes the
    peak joint forces fall by tens of per cent; with c_joint = 500 N s/m their damping ratio is c / (2 sqrt(k m))
    (closed form) and the fall is below 1 %."""
    from linkwork.papers.heald.model import joint_stiffness, model_b_parameters, reduced_masses
    from linkwork.papers.heald.studies import cam_measures, joint_branch_damping

    cam = CFG["cam"]
    c = cam_harmonics(cam["rise_fraction"]["value"], cam["harmonics"], cam["samples"])
    dips = []
    for cj in (0.0, 500.0):
        q = {**P, "c_joint": cj}
        values, _ = cam_measures(
            "B", q, harmonic_transfer("B", q, W, cam["harmonics"]), c * 1e-4 / abs(c[0]), cam["samples"],
            cam["significant_harmonic"],
        )
        dips.append(values["largest_dip"])
    assert dips[0] > 0.1 and dips[1] < 0.01
    q = {**P, "c_joint": 500.0}
    b = model_b_parameters(q)
    k, m = joint_stiffness(b, "E", "elastic"), reduced_masses(b)[0]
    assert joint_branch_damping("B", q) == pytest.approx(500.0 / (2 * np.sqrt(k * m)), rel=1e-6)
