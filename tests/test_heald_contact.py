"""The heald linkage with clearance joints at E and F (issue 24's heald question): the engine's springs and rocking
driver against independent routes, and the contact study on a short run.

Independent routes: the driver's power against the rate of the mechanical energy plus the warp damper's dissipation
(a power balance, not the multipliers' solve), and the compiled right-hand side against the constraint equations
written in numpy with the springs' forces assembled apart.
"""

from __future__ import annotations

import numpy as np

from conftest import load_yaml
from linkwork.configformat import DESIGN_FIELDS, narrow
from linkwork.engines.multibody import assembly
from linkwork.papers.heald import contact
from linkwork.papers.heald.adapter import parameters
from linkwork.units import RAD_S_PER_RPM

SECTION = narrow(load_yaml("config/config.yaml")["heald"], ["parameters", "drive", "cam", "contact"], DESIGN_FIELDS)
P = parameters(SECTION)


def _ideal(rpm: float):
    return contact.linkage(SECTION["contact"], SECTION["cam"], P, rpm * RAD_S_PER_RPM, clearances=False)


def test_the_drivers_power_balances_the_energy_rate_and_the_warp_dampers_loss():
    """Ideal joints (the linkage is then rigid and driven): T theta' = dE/dt + c_O v_y^2, E the kinetic energy plus
    gravity's and the warp spring's, its rate by fourth-order central differences of the engine's energy; to 1e-6 of
    the power."""
    lk = _ideal(300.0)
    n = 4001
    t = np.linspace(0.0, lk.driver.period, n)
    out = assembly.inverse_dynamics(lk, t, gravity=True)
    power = out["driver_torque"] * lk.driver.angle(t)[1]
    dt = t[1] - t[0]
    e = out["energy"]
    rate = (e[:-4] - 8 * e[1:-3] + 8 * e[3:-1] - e[4:]) / (12 * dt)
    frame = lk.body_index("frame")
    pos, vel = assembly._world_stack(lk, out["q"], out["qd"], ("frame", "P"))
    loss = P["c_O"] * vel[:, 1] ** 2
    assert frame >= 0 and np.ptp(pos[:, 1]) > 0.01  # the frame is lifted by centimetres
    assert np.abs(power[2:-2] - rate - loss[2:-2]).max() < 1e-6 * np.abs(power).max()


def test_the_closed_form_reversal_margin_separates_the_two_cases():
    """The nominal warp pulls the frame harder than its weight (the load at E and F reverses at any speed); the
    least-reversal corner does not (its margin below 1)."""
    ranges = {k: tuple(v["range"]) for k, v in SECTION["parameters"].items() if "range" in v}
    nominal = contact.reversal_margin(P, SECTION["cam"])
    corner = contact.reversal_margin(
        contact.case_parameters(P, ranges, SECTION["contact"]["cases"]["weight_dominant"]), SECTION["cam"]
    )
    assert nominal > 1.0 > corner


def test_first_loss_brackets_the_speed():
    rpm = np.array([25.0, 50.0, 100.0, 200.0])
    assert contact.first_loss(rpm, np.array([False, False, True, True])) == (50.0, 100.0)
    held, lost = contact.first_loss(rpm, np.array([True, True, True, True]))
    assert np.isnan(held) and lost == 25.0
    held, lost = contact.first_loss(rpm, np.array([False] * 4))
    assert held == 200.0 and np.isnan(lost)


def test_a_journal_flies_where_the_load_reverses_and_stays_in_contact_where_it_does_not():
    """A short study at 50 rev/min (physics, not a snapshot): with the nominal warp the load at E and F reverses and a
    journal leaves its bearing's wall; in the least-reversal corner both stay in contact.  The chain's forces are
    finite and the study's error bar is recorded."""
    cfg = {**SECTION["contact"], "speeds_rpm": [50.0], "points_per_cycle": 360,
           "states": {**SECTION["contact"]["states"], "min_cycles": 4, "max_cycles": 12, "check_cycles": 1}}
    ds = contact.study({**SECTION, "contact": cfg})
    assert bool(ds.contact_lost.sel(case="nominal", speed=50.0))
    assert not bool(ds.contact_lost.sel(case="weight_dominant", speed=50.0))
    assert np.isfinite(ds.chain_E.values).all() and (ds.force_numerical_error.values >= 0.0).all()


def test_the_rigid_reaction_reverses_along_the_rod_past_a_sideways_force():
    """The least-reversal corner: the rigid linkage's reaction at E and F keeps its sense along the rod at low speed
    and reverses at the speed found (its component along the rod touches zero there, positive just below), past a
    sideways force equal to its smallest magnitude; the nominal warp reverses it at every speed."""
    ranges = {k: tuple(v["range"]) for k, v in SECTION["parameters"].items() if "range" in v}
    p = contact.case_parameters(P, ranges, SECTION["contact"]["cases"]["weight_dominant"])
    cfg, cam = SECTION["contact"], SECTION["cam"]
    speed, sideways, quasi = contact.rigid_reversal(cfg, cam, p, 1.0, np.array([100.0, 200.0]), 360)
    assert not quasi.any() and (100.0 < speed).all() and (speed < 200.0).all()
    low = contact.rigid_reactions(cfg, cam, p, 100.0 * RAD_S_PER_RPM, 360)
    sense = np.sign(low[:, :, 0].mean(axis=0))
    for j in range(2):
        at = contact.rigid_reactions(cfg, cam, p, speed[j] * RAD_S_PER_RPM, 360)[:, j]
        below = contact.rigid_reactions(cfg, cam, p, 0.99 * speed[j] * RAD_S_PER_RPM, 360)[:, j]
        assert abs((sense[j] * at[:, 0]).min()) < 1e-6 * np.abs(at).max() and (sense[j] * below[:, 0]).min() > 0
        assert np.isclose(np.hypot(*at.T).min(), sideways[j])
    nominal = contact.rigid_reversal(cfg, cam, P, 1.0, np.array([100.0, 200.0]), 360)
    assert nominal[2].all()
