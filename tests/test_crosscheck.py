"""Another engine: Exudyn integrates the clearance paper's ideal four-bar forward in time; linkwork's inverse
dynamics must agree with it to Exudyn's own discretisation error, which falls at its integrator's order."""

import copy

import numpy as np

from conftest import load_yaml
from linkwork.engines.multibody.exudyn_route import ideal_run
from linkwork.engines.multibody.model import inverse_dynamics
from linkwork.papers.clearance.adapter import parameters
from linkwork.papers.clearance.crosscheck import ideal, observed_orders, relative_difference

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
