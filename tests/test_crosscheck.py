"""Another engine: Exudyn integrates the clearance paper's ideal four-bar forward in time; linkwork's inverse
dynamics must agree with it to Exudyn's own discretisation error, which falls at its integrator's order."""

import copy

import numpy as np

from conftest import load_yaml
from linkwork.engines.multibody.exudyn_route import ideal_run
from linkwork.engines.multibody.model import inverse_dynamics
from linkwork.papers.clearance.adapter import parameters
from linkwork.papers.clearance.crosscheck import dry, ideal, observed_orders, relative_difference, time_to_reach

SECTION = load_yaml("config/config.yaml")["clearance"]


def test_exudyn_and_inverse_dynamics_agree_to_second_order_in_exudyns_step():
    for variant in SECTION["variants"]:
        p = parameters(SECTION, variant, "ideal")
        end = 0.5 * 2 * np.pi / p.crank_speed  # half a turn from the dead point
        steps = np.array([6e-4, 2e-4])
        diffs = []
        for step in steps:
            run = ideal_run(p, end, float(step), 1e-12)
            ours = inverse_dynamics(p, run["t"], True)
            assert abs(run["t"][-1] - end) < 1e-12
            diffs.append([relative_difference(run[q], ours[q]) for q in ("rocker_acceleration", "crank_torque")])
        diffs = np.array(diffs)
        assert diffs[-1].max() < 1e-3
        orders = observed_orders(steps, diffs)
        assert np.all((orders > 1.7) & (orders < 2.3))  # Newmark is second order: the models are the same


def test_a_wrong_coupler_mass_is_seen_by_the_cross_check():
    """The check can fail: Exudyn with a coupler mass (and so inertia) 10 % off disagrees far beyond its step error."""
    p = parameters(SECTION, "slender", "ideal")
    wrong = copy.deepcopy(SECTION)
    wrong["bodies"]["coupler"]["mass_kg"] *= 1.1
    q = parameters(wrong, "slender", "ideal")
    end = 0.5 * 2 * np.pi / p.crank_speed
    run = ideal_run(q, end, 2e-4, 1e-12)
    ours = inverse_dynamics(p, run["t"], True)
    assert relative_difference(run["crank_torque"], ours["crank_torque"]) > 1e-2


def test_the_study_records_agreement_and_the_observed_order():
    cfg = copy.deepcopy(SECTION)
    cfg["crosscheck"].update(cycles=0.25, steps_s=[2e-4, 6e-4])
    ds = ideal(cfg)
    assert list(ds.step.values) == [6e-4, 2e-4]  # coarse to fine, whatever the config's order
    assert bool(ds.agree.all())
    assert np.all(np.abs(ds.observed_order.values - 2.0) < 0.3)
    assert "Exudyn" in ds.attrs["engine"]


def test_exudyns_dry_contact_force_is_linkworks_law():
    """Second route for the contact law: the Exudyn route's Python force against linkwork's compiled kernels
    (Hertz with Lankarani-Nikravesh damping, Ambrosio's friction) on random joint states."""
    from linkwork.engines.multibody.exudyn_route import contact_force
    from linkwork.engines.multibody.kernels import friction_coefficient, hertz_damping_factor

    p = parameters(SECTION, "slender", "dry_both")
    rng = np.random.default_rng(11)
    checked = 0
    for _ in range(300):
        angle = rng.uniform(0, 2 * np.pi)
        e = p.clearance * rng.uniform(0.98, 1.02)  # about half of them in contact
        u = [e * np.cos(angle), e * np.sin(angle), 0.0]
        v = list(rng.normal(0, 0.05, 2)) + [0.0]
        w_j, w_b = rng.normal(0, 5, 2)
        latched = abs(rng.normal(0, 0.05))
        f, ft = contact_force(p, latched, u, v, w_j, w_b)
        n = np.array(u[:2]) / e
        t = np.array([-n[1], n[0]])
        if e <= p.clearance:
            assert f == [0.0, 0.0, 0.0] and ft == 0.0
            continue
        delta_dot = float(np.dot(v[:2], n))
        fn = p.hertz_stiffness * (e - p.clearance) ** 1.5 * hertz_damping_factor(0, p.restitution, delta_dot, max(latched, p.impact_velocity_floor))
        v_t = float(np.dot(v[:2], t)) + w_j * p.journal_radius - w_b * p.bearing_radius
        ft_ref = friction_coefficient(v_t, p.friction, p.v0, p.v1) * fn
        on_journal = -np.array(f[:2])
        np.testing.assert_allclose(on_journal, -fn * n + ft_ref * t, rtol=1e-12, atol=1e-9 * max(fn, 1.0))
        assert abs(ft - ft_ref) <= 1e-12 * abs(ft_ref)
        checked += 1
    assert checked > 50  # enough states in contact


def test_the_dry_study_compares_per_cycle_means_against_its_margin():
    """A short dry run in both engines (one settle cycle, two recorded): shapes, the margin's definition, and
    Exudyn's clearance joint acting as a joint (its deviation from ideal within a factor 2 of ours)."""
    cfg = copy.deepcopy(SECTION)
    cfg["numerics"].update(settle_cycles=1, points_per_cycle=360)
    cfg["crosscheck"].update(record_cycles=2, dry_steps_s=[2e-5, 4e-5])
    ds = dry(cfg, "slender", "dry_2")
    assert ds.sizes == {"setting": 4, "quantity": 2, "cycle": 2}
    assert list(ds.setting.values[2:]) == ["Exudyn step 4e-05 s", "Exudyn step 2e-05 s"]  # coarse to fine
    assert np.all(ds.cycle_rms_deviation.values > 0)
    mean = ds["mean"].values
    np.testing.assert_allclose(ds.relative_difference.values, (mean[-1] - mean[0]) / mean[0])
    assert np.array_equal(ds.agree.values, np.abs(mean[-1] - mean[0]) <= ds.margin.values)
    assert np.all((mean[-1] / mean[0] > 0.5) & (mean[-1] / mean[0] < 2.0))


def test_time_to_reach_reads_the_work_precision_front():
    """The least time over the settings at least as accurate as the target; NaN if none is."""
    errors, times = np.array([0.3, 0.05, 0.06, 0.001]), np.array([1.0, 2.0, 3.0, 4.0])
    assert time_to_reach(errors, times, 0.055) == 2.0  # not 3.0: the front, not the setting order
    assert time_to_reach(errors, times, 0.3) == 1.0
    assert np.isnan(time_to_reach(errors, times, 1e-4))
