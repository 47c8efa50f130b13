"""The states of the clearance scenes: runs continued in pieces and from a saved state, starts off-centre, the compiled
NDF integrator against scipy's BDF, peaks against the sampling, and one scene's state with its three-tolerance error
bar."""

import copy

import numpy as np
import pytest

from conftest import load_yaml
from linkwork.papers.clearance.fourbar import initial_state, integrate, inverse_dynamics, journal_offsets, offset_start
from linkwork.papers.clearance.fourbar import run as Run
from linkwork.papers.clearance.adapter import parameters, scene_effects

SECTION = load_yaml("config/config.yaml")["clearance"]
DRY = {"method": "dopri5", "rtol": 1e-9, "atol": 1e-12, "first_step_s": 1e-7, "max_step_s": 1e-3}


def _scene(variant, name):
    p = parameters(SECTION, variant, name)
    joints, effects = scene_effects(SECTION, name)
    return p, joints, effects


def _cycle_times(p, k, per):
    T = 2 * np.pi / p.crank_speed
    return k * T + np.arange(per + 1) * T / per


@pytest.mark.parametrize("method", ["dopri5", "dop853"])
def test_a_run_in_pieces_is_the_run_in_one_piece(method):
    """The integrators carry their step and the contact memory across a cut: four one-cycle pieces of the same output
    times give the four-cycle run (a dry scene in permanent contact, where the latched impact velocity matters).
    Dormand-Prince 5(4) lands on every output, so bit for bit; DOP853 lands only on a piece's end (its outputs come
    from its dense output), so to its tolerance: 5e-5 c in the eccentricity, 2e-4 of the largest acceleration."""
    p, joints, effects = _scene("slender", "dry_2")
    per = 360
    T = 2 * np.pi / p.crank_speed
    t = np.arange(4 * per + 1) * T / per
    integ = {**DRY, "method": method}
    states, whole = integrate(p, joints, effects, t, integ)[:2]
    run = Run(p, joints, effects, integ)
    pieces = [run.advance(t[k * per : (k + 1) * per + 1]) for k in range(4)]
    joined_states = np.concatenate([pieces[0][0]] + [x[0][1:] for x in pieces[1:]])
    joined = np.concatenate([pieces[0][1]] + [x[1][1:] for x in pieces[1:]])
    if method == "dopri5":
        assert np.array_equal(joined, whole)
    else:
        assert (
            np.abs(_eccentricity(p, joints, joined_states) - _eccentricity(p, joints, states)).max()
            < 5e-5 * p.clearance
        )
        assert np.abs(joined[:, 0] - whole[:, 0]).max() < 2e-4 * np.abs(whole[:, 0]).max()
    assert run.was.all() and run.latched[0] > 0  # in contact, with an impact velocity latched


def test_a_run_restarted_from_its_saved_state_continues_the_same_motion():
    """``memory()`` holds time, state and contact memory: a new run from it follows the original over the next cycle
    to the integrator's tolerance (only the first step size differs)."""
    p, joints, effects = _scene("decoded", "dry_1")
    per = 360
    run = Run(p, joints, effects, DRY)
    run.advance(_cycle_times(p, 0, per))
    saved = run.memory()
    _, going_on = run.advance(_cycle_times(p, 1, per))
    _, restarted = Run(p, joints, effects, DRY, memory=saved).advance(_cycle_times(p, 1, per))
    scale = np.abs(going_on[:, 0]).max()
    assert np.abs(restarted[:, 0] - going_on[:, 0]).max() < 1e-5 * scale


@pytest.mark.parametrize("name", ["dry_1", "dry_2", "dry_both"])
def test_an_off_centre_start_puts_every_journal_where_asked_and_keeps_the_ideal_joints_closed(name):
    """``offset_start``: each clearance journal at the asked eccentricity and rate (to 1e-9 of c and of c omega, a
    second route: the offsets read back from the state by ``journal_offsets``), while the ground pins, the drive
    and every ideal joint hold (the first right-hand side reports no constraint drift)."""
    p, joints, effects = _scene("slender", name)
    c, w = p.clearance, p.crank_speed
    ecc, rate = np.array([0.6, -0.6]) * c, np.array([0.5, 0.5]) * c * w
    y0 = offset_start(p, joints, ecc, rate)
    got = journal_offsets(p, joints, y0)
    assert np.abs(got[:, :2] - ecc).max() < 1e-9 * c
    assert np.abs(got[:, 2:] - rate).max() < 1e-9 * c * w
    _, diags, *_ = integrate(p, joints, effects, np.array([0.0]), DRY, y0=y0)
    assert diags[0, 3] < 1e-12  # |Phi| of the ideal constraints at the start
    assert np.allclose(offset_start(p, joints, (0.0, 0.0), (0.0, 0.0))[:9], initial_state(p, joints)[:9], atol=1e-12)


def test_the_compiled_ndf_agrees_with_scipys_bdf_and_with_inverse_dynamics():
    """Second routes for the compiled variable-order NDF: on the ideal linkage it equals inverse dynamics; on a
    lubricated scene (stiff film) over one cycle it agrees with scipy's BDF at the same tolerance to well below
    the claims' margins (the two take different step sequences)."""
    p, _, _ = _scene("slender", "lubricated_2")
    ndf = {"method": "ndf", "rtol": 1e-9, "atol": 1e-12, "first_step_s": 1e-7, "max_step_s": 1e-3}
    t = _cycle_times(p, 0, 360)
    _, ideal_run, *_ = integrate(p, (), ("gravity",), t, ndf)
    ideal = inverse_dynamics(p, t, gravity=True)
    assert (
        np.abs(ideal_run[:, 0] - ideal["rocker_acceleration"]).max() < 1e-6 * np.abs(ideal["rocker_acceleration"]).max()
    )
    p, joints, effects = _scene("decoded", "lubricated_2")
    a = integrate(p, joints, effects, t, ndf)[1]
    b = integrate(p, joints, effects, t, {**ndf, "method": "bdf"})[1]
    scale = np.abs(b[:, 0]).max()
    assert np.abs(a[:, 0] - b[:, 0]).max() < 1e-4 * scale
    assert np.abs(a[:, 4] - b[:, 4]).max() < 1e-4 * p.clearance  # the journal's eccentricity


def test_the_compiled_ndf_continues_after_a_rounding_size_last_step():
    """A cycle's last step can be cut to what is left of it, a few units in the last place of t; the next cycle starts
    from that step size.  The compiled NDF raises it to its floor of ten units in the last place, as scipy's BDF does,
    instead of giving up (it gave up, and every later cycle of the run went to scipy's BDF in Python: 17 of the 33 s
    of a lubricated scene).  The continued run agrees with scipy's BDF from the same state."""
    p, joints, effects = _scene("decoded", "lubricated_2")
    ndf = {"method": "ndf", "rtol": 1e-10, "atol": 1e-13, "first_step_s": 1e-7, "max_step_s": 1e-3}
    run = Run(p, joints, effects, ndf)
    t = _cycle_times(p, 0, 360)
    run.advance(t[:91])
    memory = run.memory()
    run.h = 2.0 * np.spacing(run.t)  # the remainder a cut leaves
    _, a = run.advance(t[90:181])
    assert run.fallbacks == 0
    _, b = Run(p, joints, effects, {**ndf, "method": "bdf"}, memory=memory).advance(t[90:181])
    assert np.abs(a[:, 0] - b[:, 0]).max() < 1e-4 * np.abs(b[:, 0]).max()
    assert np.abs(a[:, 4] - b[:, 4]).max() < 1e-4 * p.clearance


def _eccentricity(p, joints, ys):
    return np.linalg.norm(journal_offsets(p, joints, ys)[..., 0:2], axis=-1)


def test_the_compiled_dop853_is_scipys_dop853_and_its_outputs_do_not_move_its_steps():
    """Second routes for the compiled DOP853 (the dry scenes' integrator): on a dry scene it follows scipy's DOP853 on
    the same right-hand side (the same algorithm) to rounding until the first impact, and through the first two impacts
    within its own error (5e-4 c at rtol 1e-9 in the work-precision study); its steps do not land on the outputs, so
    14400 outputs a cycle or two end in the same state bit for bit; and a dense output inside a step agrees with a run
    that ends there (before the impacts)."""
    p, joints, effects = _scene("slender", "dry_2")
    integ = {**DRY, "method": "dop853"}
    t = _cycle_times(p, 0, 14400)[: 14400 // 50 + 1]  # the first two impacts (0.02 cycle, as the work-precision study)
    ours, diags, *_ = integrate(p, joints, effects, t, integ)
    theirs = integrate(p, joints, effects, t, {**integ, "method": "scipy-dop853"})[0]
    first = int(np.argmax(diags[:, 5] > 0))
    assert 0 < first < t.size - 1  # the window holds the first impacts
    gap = np.abs(_eccentricity(p, joints, ours) - _eccentricity(p, joints, theirs)) / p.clearance
    assert gap[:first].max() < 1e-9  # before the first impact: the same steps, to rounding
    assert gap.max() < 2e-3  # through the impacts the two step sequences part at their error (5e-4 c at rtol 1e-9)
    ends = integrate(p, joints, effects, t[[0, -1]], integ)[0]
    assert np.array_equal(ends[-1], ours[-1])
    k = first - 2  # an output inside a step, in free flight (after the impacts the step sequences part, as above)
    landed = integrate(p, joints, effects, t[[0, k]], integ)[0]
    assert abs(_eccentricity(p, joints, landed)[-1] - _eccentricity(p, joints, ours)[k]).item() < 1e-9 * p.clearance


def test_the_peak_deviation_converges_as_the_sampling_grows():
    """The peak of (scene - ideal) over one cycle of a dry scene with impacts (slender links, joint 2), sampled at
    900 ... 28800 points a cycle: a coarse grid misses the impact spike (up to 3600 points a cycle the peak is more
    than 10 % low, whatever the grid), the pipeline's sampling catches it, within 0.1 % of twice the sampling."""
    p, joints, effects = _scene("slender", "dry_2")
    run = Run(p, joints, effects, DRY)
    run.advance(_cycle_times(p, 0, 100))
    saved = run.memory()
    pipeline = SECTION["numerics"]["points_per_cycle"]
    samplings = (900, 1800, 3600, pipeline, 2 * pipeline)
    peaks = {}
    for per in samplings:
        t = _cycle_times(p, 1, per)
        _, d = Run(p, joints, effects, DRY, memory=saved).advance(t)
        peaks[per] = np.abs(d[:, 0] - inverse_dynamics(p, t, gravity=True)["rocker_acceleration"]).max()
    finest = peaks[2 * pipeline]
    assert peaks[3600] < 0.9 * finest  # the old grid's peak
    assert abs(peaks[pipeline] - finest) < 1e-3 * finest
    assert abs(peaks[pipeline] - finest) < 1e-3 * abs(
        peaks[3600] - finest
    )  # the spike is resolved only from the pipeline sampling on


@pytest.mark.parametrize("n", [720, 721])
def test_the_ripple_is_the_content_above_the_cutoff_harmonic(n):
    """The ripple of one turn (n steps, the end point included): sines at harmonics 3 (below the cutoff 50), 51 and
    80 (above) on a drift (a turn that does not close) give sqrt((b^2 + c^2) / 2) exactly, the drift and the low
    sine contributing nothing; by a second route, the RMS of what is left in time after the line and the harmonics
    up to the cutoff are taken off (the inverse transform), for an even and an odd n (the Nyquist term's weight).
    Without the line the drift's jump would leak: the same signal's ripple is then over 20 % larger."""
    from linkwork.papers.clearance.settling import ripple, ripple_harmonic

    k = np.arange(n + 1) / n
    b, c = 0.3, 0.2
    x = 5.0 * np.sin(2 * np.pi * 3 * k) + b * np.sin(2 * np.pi * 80 * k) + c * np.cos(2 * np.pi * 51 * k) + 7.0 * k
    assert ripple(x, 50) == pytest.approx(np.sqrt((b**2 + c**2) / 2), rel=1e-12)
    line = x[0] + (x[-1] - x[0]) * k[:-1]
    spectrum = np.fft.rfft(x[:-1] - line)
    spectrum[51:] = 0.0
    left = x[:-1] - line - np.fft.irfft(spectrum, n)
    assert ripple(x, 50) == pytest.approx(np.sqrt(np.mean(left**2)), rel=1e-10)
    assert ripple(np.stack([x, 2 * x]), 50) == pytest.approx(np.array([1.0, 2.0]) * ripple(x, 50), rel=1e-12)
    jump = np.fft.rfft(x[:-1])  # no line taken off: the drift's jump at the turn's end leaks into every harmonic
    assert np.sqrt(2 * np.sum(np.abs(jump[51:]) ** 2)) / n > 1.2 * ripple(x, 50)
    assert ripple_harmonic(500.0, 20 * np.pi) == 50 and ripple_harmonic(499.0, 20 * np.pi) == 49


def test_a_scene_settles_onto_its_state_and_carries_a_three_tolerance_error_bar():
    """A real scene (link inertias as printed, joint 1 dry, one start): its state is a periodic orbit found before the
    cap; the judged window starts after the transient and holds whole periods; the measure is the mean over one period;
    the two check integrators, restarted from the section point, stay on the orbit and move the measure by far less than
    the margins the claims are decided by (1e-4 of it); the start settled again from its initial state at the first
    check integrator reaches a recorded state, and the error bar holds the largest of all these changes; the ripple the
    runner took of the last turn is the ripple of the stored time series' last turn."""
    from linkwork.papers.clearance.studies import scene

    cfg = copy.deepcopy(SECTION)
    cfg["states"]["starts"] = cfg["states"]["starts"][:1]
    ds = scene(cfg, "decoded", "dry_1")
    assert str(ds.state_status.values[0]) == "periodic" and int(ds.state_period.values[0]) >= 1
    first, stop, transient = int(ds.window_first[0]), int(ds.window_stop[0]), int(ds.state_transient[0])
    assert (
        first >= transient
        and (stop - first) % int(ds.state_period[0]) == 0
        and stop <= int(ds.record_cycles[0]) < cfg["states"]["max_cycles"]
    )
    rms = ds.cycle_deviation.sel(measure="rms", quantity="rocker_acceleration").values[0]
    assert np.isclose(
        float(ds.judged_mean.sel(measure="rms", quantity="rocker_acceleration")[0]),
        rms[first : first + int(ds.state_period[0])].mean(),
    )
    assert (ds.check_kept_state.values == 1).all() and ds.sizes["check"] == 2
    rms = dict(measure="rms", quantity="rocker_acceleration")
    measure = float(ds.judged_mean.sel(**rms)[0])
    assert np.abs(ds.check_delta.sel(**rms)[0]).max() < 1e-4 * measure
    assert str(ds.reach_status.values[0]) in ("periodic", "stationary") and np.isfinite(ds.reach_same_state.values[0])
    largest = max(float(np.abs(ds.check_delta.sel(**rms)[0]).max()), abs(float(ds.reach_delta.sel(**rms)[0])))
    assert float(ds.numerical_error.sel(**rms)[0]) == pytest.approx(
        largest + float(ds.convergence_error.sel(**rms)[0]), rel=1e-12
    )
    # on a periodic state a check's own measure is the pipeline's judged measure plus its change, for every measure
    assert np.allclose(
        ds.check_mean.values[0], ds.judged_mean.values[0][None] + ds.check_delta.values[0], rtol=1e-12, atol=0.0
    )
    assert ds.attrs["sampling_over_contact_frequency"] >= 4.0
    # the ripple of the last turn run, per cycle as the runner took it and again from the stored time series (the
    # figures' record: its last turn, the end point included)
    from linkwork.papers.clearance.settling import ripple

    per = cfg["numerics"]["points_per_cycle"]
    last = (ds.rocker_acceleration - ds.ideal_rocker_acceleration).values[-(per + 1):]
    n = int(ds.record_cycles[0])
    taken = float(ds.cycle_deviation.sel(measure="ripple", quantity="rocker_acceleration").values[0][n - 1])
    assert ripple(last, int(ds.attrs["ripple_harmonic"])) == pytest.approx(taken, rel=1e-12) and taken > 0


class _Scripted:
    """A stand-in for CycleRunner: per cycle the section point and measures of a scripted orbit after a transient
    (the scripted columns repeated over the measures, as many rows as a CycleRunner gives)."""

    fallbacks = 0

    def __init__(self, orbit, measures, transient=3):
        from linkwork.papers.clearance.settling import MEASURE_ROWS

        measures = np.asarray(measures, float)
        self.orbit, self.transient, self.n = np.asarray(orbit, float), transient, 0
        self.measures = np.tile(measures, len(MEASURE_ROWS) // measures.shape[1])

    def step(self, n):
        k = np.arange(self.n, self.n + n)
        self.n += n
        kick = np.where(k < self.transient, 1.0, 0.0)[:, None]
        return self.orbit[k % len(self.orbit)] + kick, self.measures[k % len(self.measures)] + kick


def test_the_state_a_start_reaches_at_the_check_tolerance_is_compared_with_the_pipelines():
    """``reach_state``: a start that reaches the pipeline's period-2 orbit again is 'the same state' with its measure
    difference; one that falls into a coexisting period-1 state is 'another state', and the difference of the two
    states' measures is what enters the error bar; a failing check integrator records no value."""
    from linkwork.engines.states import settle
    from linkwork.papers.clearance.settling import reach_state

    st = {
        "chunk_cycles": 4,
        "max_cycles": 60,
        "max_period": 4,
        "section_tolerance": 1e-9,
        "periods": 3,
        "min_cycles": 20,
        "state_tolerance": 0.2,
    }
    orbit2, meas2 = [[0.3, 0.1], [-0.4, 0.2]], [[10.0, 1.0], [12.0, 3.0]]
    pipeline = _Scripted(orbit2, meas2)
    found = settle(pipeline.step, 4, 60, 4, 1e-9, 3, 20, 0.95)
    assert found["period"] == 2
    same = reach_state(
        lambda _c, **_: _Scripted(orbit2, [[10.5, 1.0], [12.5, 3.0]], transient=7), found, {}, {"rtol": 1e-10}, st, 5,
        0.95,
    )
    assert same["same"] == 1.0 and same["period"] == 2 and np.allclose(same["delta"], np.tile([0.5, 0.0], 3))
    other = reach_state(
        lambda _c, **_: _Scripted([[0.9, -0.9]], [[30.0, 2.0]]), found, {}, {"rtol": 1e-10}, st, 5, 0.95
    )
    assert other["same"] == 0.0 and other["period"] == 1 and np.allclose(other["delta"], np.tile([30.0 - 11.0, 0.0], 3))

    class _Failing:
        fallbacks = 0

        def step(self, n):
            raise RuntimeError("step size underflow")

    failed = reach_state(lambda _c, **_: _Failing(), found, {}, {"rtol": 1e-10}, st, 5, 0.95)
    assert failed["status"] == "failed" and np.isnan(failed["delta"]).all() and np.isnan(failed["same"])


def test_a_row_that_drifts_over_a_stationary_window_has_no_interval():
    """``judged_statistics`` on a state that is not periodic: a row the settling rule did not read (the ripple) that
    drifts over the window gets no interval (infinite half-width, as a record at the cap); the steady rows keep a
    finite batch-means interval; on a periodic state every row is exact."""
    from linkwork.papers.clearance.settling import judged_statistics

    rng = np.random.default_rng(1)  # a seed whose noise passes the thirds test (one in twenty does not, at 95 %)
    n = 60
    steady = 10.0 + rng.standard_normal(n)
    drifting = np.linspace(0.004, 0.016, n) + 1e-4 * rng.standard_normal(n)
    measures = np.stack([steady, steady + 1.0, drifting], axis=1)
    out = judged_statistics(measures, {"status": "stationary", "window": (0, n), "period": 0}, 5, 0.95)
    assert np.isfinite(out[:2, 1]).all() and np.isinf(out[2, 1]) and np.isinf(out[2, 2])
    assert out[2, 0] == pytest.approx(drifting.mean())
    periodic = judged_statistics(measures, {"status": "periodic", "window": (0, n), "period": 1}, 5, 0.95)
    assert (periodic[:, 1] == 0.0).all()
