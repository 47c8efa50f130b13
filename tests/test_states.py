"""The settled state of a driven system from its Poincaré section (linkwork.engines.states): periods found, the
transient kept out of the judged window, records that do not repeat called so."""

import numpy as np
import pytest

from linkwork.engines.states import NOT_PERIODIC, judged_window, repeats_after, section_period

ORBIT3 = np.array([[0.2, -1.0], [0.9, 0.4], [-0.5, 0.1]])  # three section points, two components


def _approach(orbit: np.ndarray, cycles: int, amplitude: float, rate: float) -> np.ndarray:
    """A record that approaches a periodic ``orbit`` geometrically: x_n = orbit[n mod k] + amplitude rate^n (1, -1)."""
    n = np.arange(cycles)
    return orbit[n % len(orbit)] + amplitude * rate ** n[:, None] * np.array([1.0, -1.0])


def test_a_period_three_orbit_is_period_three_and_its_transient_is_left_out():
    """An approach to a period-3 orbit from far away (a long transient, amplitude 5, rate 0.8): the period is 3, not
    1, 2 or 6; the transient ends where the approach falls below the tolerance, and no judged cycle lies in it."""
    record = _approach(ORBIT3, 120, 5.0, 0.8)
    tol = 1e-6
    period, transient = section_period(record, max_period=8, rtol=tol)
    assert period == 3
    spread = record[60:].max(axis=0) - record[60:].min(axis=0)
    # the first cycle from which every point lies within the tolerance of the record's last period (the approach
    # is geometric: this is later than where consecutive periods first repeat to it)
    last = record[117:]
    dist = np.abs(record - last[(np.arange(120) - 117) % 3])
    expected = int(np.flatnonzero(np.any(dist > tol * spread, axis=1))[-1]) + 1
    assert transient == expected and transient > 40  # a long transient, found exactly
    first, stop = judged_window(120, period, transient, min_cycles=30)
    assert first >= transient and stop == 120 and (stop - first) % 3 == 0 and stop - first >= 30
    judged = record[first:stop]
    # on the orbit, not on the transient: a geometric approach that repeats to tol after one period (contraction
    # 0.8^3 per period) lies within tol / (1 - 0.8^3) of its limit
    assert np.all(np.abs(judged - ORBIT3[np.arange(first, stop) % 3]) <= tol * spread / (1 - 0.8 ** 3))
    before = record[: transient - 3] - ORBIT3[np.arange(transient - 3) % 3]
    assert np.any(np.abs(before) > tol * spread / (1 - 0.8 ** 3))


def test_period_one_and_period_two_are_told_apart():
    """A fixed point is period 1; an alternation is period 2 (it does not repeat after one cycle)."""
    fixed = _approach(np.array([[0.3, 0.7]]), 60, 1.0, 0.5)
    assert section_period(fixed, 8, 1e-9, atol=1e-12)[0] == 1
    two = _approach(ORBIT3[:2], 60, 1.0, 0.5)
    assert section_period(two, 8, 1e-9)[0] == 2
    assert not repeats_after(two[40:], 1, np.full(2, 1e-3)).any()


def test_a_chaotic_record_is_not_periodic():
    """The logistic map at r = 4 (chaotic) repeats with no period up to the bound: not periodic, and nothing is
    judged as an orbit."""
    x = np.empty(400)
    x[0] = 0.2345
    for i in range(1, x.size):
        x[i] = 4.0 * x[i - 1] * (1.0 - x[i - 1])
    period, transient = section_period(x, max_period=12, rtol=1e-6)
    assert (period, transient) == (NOT_PERIODIC, 400)
    assert judged_window(400, period, transient, 30) == (400, 400)


@pytest.mark.parametrize("cycles", [5, 8])
def test_a_record_too_short_for_two_periods_is_not_called_periodic(cycles):
    """A period-3 orbit needs two whole periods after its transient to be recognised; a shorter record is not."""
    record = _approach(ORBIT3, cycles, 5.0, 0.8)
    assert section_period(record, 8, 1e-6)[0] == NOT_PERIODIC


def test_a_settled_state_with_section_noise_below_the_tolerance_is_periodic():
    """Integration error on the section (1e-9 of the spread) does not break the period; at 1e-3 of the spread
    with a tolerance of 1e-6 it does, and the record is not called periodic."""
    rng = np.random.default_rng(7)
    record = _approach(ORBIT3, 90, 2.0, 0.7)
    quiet = record + 1e-9 * rng.standard_normal(record.shape)
    loud = record + 1e-3 * rng.standard_normal(record.shape)
    assert section_period(quiet, 8, 1e-6)[0] == 3
    assert section_period(loud, 8, 1e-6)[0] == NOT_PERIODIC


def _stepper(points: np.ndarray, measures: np.ndarray):
    """A ``settle`` step function that hands out a prepared record chunk by chunk, and counts what it was asked for."""
    asked = []

    def step(n):
        done = sum(asked)
        asked.append(n)
        return points[done : done + n], measures[done : done + n]

    return step, asked


def test_settle_finds_a_period_three_orbit_after_a_long_transient_and_judges_none_of_it():
    """``settle`` on a record that approaches a period-3 orbit from far away (rate 0.85: about 100 cycles to reach
    the tolerance): period 3, stopped soon after the orbit is reached (not at the cap), the judged window whole
    periods after the transient, and every cycle before the transient still off the orbit."""
    from linkwork.engines.states import PERIODIC, settle

    record = _approach(ORBIT3, 400, 5.0, 0.85)
    measures = np.linalg.norm(record, axis=1)[:, None]
    step, asked = _stepper(record, measures)
    # min_cycles 100: the orbit is proven (its section within 1e-4 of the last period) before 100 cycles could be
    # judged as a stationary record, which the period-3 pattern's own scatter would let a geometric approach pass
    found = settle(
        step, chunk=4, max_cycles=400, max_period=8, section_tol=1e-4, periods=3, min_cycles=100, confidence=0.95
    )
    assert found["status"] == PERIODIC and found["period"] == 3
    first, stop = found["window"]
    assert first >= found["transient"] > 60 and (stop - first) % 3 == 0 and stop - first >= 3
    assert (
        sum(asked) < found["transient"] + (3 + 1) * 3 + 4
    )  # stopped within a chunk of the proof (periods + 1 periods), far from the cap
    off = np.abs(record[: found["transient"] - 3] - ORBIT3[np.arange(found["transient"] - 3) % 3]).max(axis=1)
    assert off.max() > 1e-4


def test_settle_judges_a_noisy_state_only_after_its_transient_has_gone():
    """A state that is not periodic (noise on the measure, a section that never repeats) behind a slow exponential
    transient (time constant 20 cycles, 30 times the noise at the start): ``settle`` runs until the last third
    agrees with the middle third after the MSER cut, the cut at most a third of the record; the judged window holds
    at least ``min_cycles`` cycles, starts after the cut, and what is left of the transient in it moves the judged
    mean by less than half the cycle-to-cycle scatter (true for 200 of 200 seeds when this rule was chosen; a bias
    below the mean's own interval cannot be promised: a transient that small is invisible in 50 noisy cycles)."""
    from linkwork.engines.states import STATIONARY, settle

    rng = np.random.default_rng(3)
    n = 600
    noise = 1.0
    measures = (100.0 + 30.0 * noise * np.exp(-np.arange(n) / 20.0) + noise * rng.standard_normal(n))[:, None]
    points = rng.standard_normal((n, 2))  # a section that never repeats
    step, _ = _stepper(points, measures)
    found = settle(
        step, chunk=4, max_cycles=n, max_period=8, section_tol=1e-3, periods=3, min_cycles=50, confidence=0.95
    )
    assert found["status"] == STATIONARY and found["period"] == 0
    first, stop = found["window"]
    assert stop - first >= 50
    left = float(
        np.mean(30.0 * noise * np.exp(-np.arange(first, stop) / 20.0))
    )  # the transient's share of the judged mean
    assert left < 0.5 * noise and first == found["transient"] and first <= stop // 3


def test_a_drift_that_never_stops_reaches_the_cap_and_says_so():
    """A measure that keeps drifting (a transient longer than any record) is never called stationary: the record
    ends at the cycle cap with that status."""
    from linkwork.engines.states import CAP, settle, thirds_agree

    n = 120
    measures = np.linspace(100.0, 160.0, n)[:, None] + 0.1 * np.random.default_rng(1).standard_normal((n, 1))
    step, _ = _stepper(np.random.default_rng(2).standard_normal((n, 2)), measures)
    found = settle(
        step, chunk=10, max_cycles=n, max_period=8, section_tol=1e-3, periods=3, min_cycles=50, confidence=0.95
    )
    assert found["status"] == CAP and found["points"].shape[0] == n
    assert not thirds_agree(measures.T, 0.95)[0]
    assert thirds_agree(100.0 + np.random.default_rng(4).standard_normal((2, 90)), 0.95)[0]


def test_settle_reads_only_the_rows_it_is_given_and_returns_every_row():
    """``rows`` names the measure rows the transient cut and the stationarity test read: a second row that keeps
    drifting holds a record at the cap when it is read, and is recorded but not read when ``rows`` leaves it out
    (the record then settles as stationary on the first row, and the drifting row comes back whole)."""
    from linkwork.engines.states import CAP, STATIONARY, settle

    n = 120
    rng = np.random.default_rng(5)
    steady = 100.0 + rng.standard_normal(n)
    drifting = np.linspace(100.0, 160.0, n) + 0.1 * rng.standard_normal(n)
    measures = np.stack([steady, drifting], axis=1)
    points = rng.standard_normal((n, 2))
    step, _ = _stepper(points, measures)
    read_all = settle(
        step, chunk=10, max_cycles=n, max_period=8, section_tol=1e-3, periods=3, min_cycles=50, confidence=0.95
    )
    step, _ = _stepper(points, measures)
    first_only = settle(
        step, chunk=10, max_cycles=n, max_period=8, section_tol=1e-3, periods=3, min_cycles=50, confidence=0.95,
        rows=(0,),
    )
    assert read_all["status"] == CAP
    assert first_only["status"] == STATIONARY and first_only["measures"].shape[1] == 2
    assert np.array_equal(first_only["measures"], measures[: first_only["measures"].shape[0]])
