"""The beat-up six-bar as a linkage description (the sley-pin question): its ideal kinematics by the multibody engine
against the paper room's own chain solution, and the clearance scene's study."""

import numpy as np

from conftest import load_yaml
from linkwork.engines.multibody import assembly
from linkwork.papers.beatup.adapter import crank_sense, six_bar
from linkwork.papers.beatup.model import CRANK_SENSES, dead_centres, sley_motion
from linkwork.papers.beatup.sley_pin import _linkage, _pin, study
from linkwork.units import rpm_to_rad_s

SECTION = load_yaml("config/config.yaml")["beatup"]


def test_the_engine_moves_the_sley_as_the_papers_chain_does():
    """The description built from the six-bar's lengths, assembled and driven by the engine: the sley angle and its
    angular acceleration over a turn against ``model.sley_motion`` (the dyad chain, theta6'' omega^2), to 1e-9."""
    mech = six_bar(SECTION["sixbar"])
    omega = CRANK_SENSES[crank_sense(SECTION["sixbar"])] * rpm_to_rad_s(
        SECTION["sley_pin"]["loom_speed_rev_min"]["value"]
    )
    front = dead_centres(mech).front
    linkage = _linkage(mech, SECTION["sley_pin"], omega, front, None)
    t = np.linspace(0.0, linkage.driver.period, 181)
    ideal = assembly.inverse_dynamics(linkage, t, gravity=False)
    chain = sley_motion(mech, np.mod(front + omega * t, 2 * np.pi))
    sley = ideal["q"][:, 3 * linkage.body_index("sley") + 2]
    assert np.abs(np.angle(np.exp(1j * (sley - chain.theta6)))).max() < 1e-9
    expected = chain.theta6_accel * omega**2
    assert np.abs(ideal["output_acceleration"] - expected).max() < 1e-9 * np.abs(expected).max()


def test_the_sley_pin_study_records_a_settled_state_and_its_error_bar():
    """A short run of the study (a coarse turn, few turns): the state is found, the peaks are finite and the clearance
    scene's acceleration differs from the ideal one (the pin's impacts), the ideal pin's peak equals the ideal
    curve's."""
    section = {
        **SECTION,
        "sley_pin": {
            **SECTION["sley_pin"],
            "points_per_turn": 1800,
            "states": {**SECTION["sley_pin"]["states"], "min_cycles": 4, "check_cycles": 2},
        },
    }
    ds = study(section)
    assert ds.attrs["state_status"] in ("periodic", "stationary")
    assert np.isfinite(ds.peak_in_window.values).all() and (ds.pin_peak_in_window_numerical_error.values >= 0.0).all()
    assert (ds.pin_peak_in_window_low <= ds.peak_in_window.sel(mechanism="six-bar, clearance at the sley pin")).all()
    assert float(ds.rms_deviation) > 0.0 and float(ds.max_contact_force) > 0.0
    assert abs(_pin(SECTION["sley_pin"]).clearance - SECTION["sley_pin"]["pin"]["radial_clearance_m"]["value"]) < 1e-15
