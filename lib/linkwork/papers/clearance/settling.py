"""The state a clearance scene settles into, per start, and its numerical error bar.

A scene is started from each of ``states.starts`` (every clearance journal at an eccentricity and moving at a rate
relative to its bearing, as fractions of the radial clearance c and of c times the crank speed).  Each start runs
cycle by cycle; once per crank turn (at the dead point the run starts from) its Poincaré section is recorded: every
clearance joint's eccentricity and its rate, scaled by c and c omega.  ``linkwork.engines.states.settle`` decides
when the state is found (a periodic orbit, or stationary statistics over enough cycles) and which cycles are judged.

The numerical error bar of a state comes from three tolerances on the same state: the pipeline run and reruns at
each setting of ``check_integrators`` restarted from the section point (with the contact memory) at the start of
the judged window.  Where a rerun settles onto another state (its section leaves the pipeline orbit by more than
``states.state_tolerance``), the state itself depends on the tolerance, and the claims that use it are undetermined
for that reason.  Besides, each start is settled once more from its initial state at the first check integrator
(``reach_state``): where coexisting states attract neighbouring trajectories, which one a start reaches can depend on
the integrator; the measure of the state reached there enters the error bar too.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from .fourbar import initial_state, journal_offsets, offset_start, run
from ...engines.states import NOT_PERIODIC, PERIODIC, section_period, settle, thirds_agree

#: The claims' measures of one turn's deviation from the ideal curve: its RMS, its peak |.|, and its ripple (the RMS of
#: its content above ``claims.ripple_cutoff_hz``: the paper's "small fluctuation peaks" of claim 3, which a size does
#: not measure).
MEASURES = ("rms", "peak", "ripple")
#: The compared responses, in the order of the measure rows.
RESPONSES = ("rocker_acceleration", "crank_torque")
#: Per cycle: each measure of each compared response (rows of the per-cycle measures, in this order).
MEASURE_ROWS = tuple((m, q) for m in MEASURES for q in RESPONSES)
#: The rows the settling rule's transient cut and stationarity test read (the RMS and the peak, as the rule was set
#: and checked); the ripple rows are recorded every turn and judged on the window those rows give.
SETTLE_ROWS = tuple(i for i, (m, _) in enumerate(MEASURE_ROWS) if m in ("rms", "peak"))
#: Per cycle and clearance joint: the extremes kept (largest penetration, eccentricity, dry force, |film radial force|).
EXTREMES = ("penetration", "eccentricity", "contact_force", "film_force")


def start_state(p, joints, start: Mapping[str, Any]) -> np.ndarray:
    """The initial state of one start (``start``: eccentricity and rate as fractions of c and c omega)."""
    ecc, rate = np.asarray(start["eccentricity"], dtype=float), np.asarray(start["rate"], dtype=float)
    if not ecc.any() and not rate.any():
        return initial_state(p, joints)
    c, w = p.clearance, p.crank_speed
    return offset_start(p, joints, ecc * c, rate * c * w)


def section_point(p, joints, states: np.ndarray) -> np.ndarray:
    """Poincaré section components (dimensionless) of states (..., >= 18): per clearance joint e_x / c, e_y / c,
    e_x' / (c omega), e_y' / (c omega), joints in order."""
    scale = np.array([1.0, 1.0, p.crank_speed, p.crank_speed]) * p.clearance
    return (journal_offsets(p, joints, states) / scale).reshape(states.shape[:-1] + (-1,))


class CycleRunner:
    """Runs a scene cycle by cycle and keeps what the claims and the report read: per cycle the section point, the
    run's whole state (restartable), the measures (MEASURE_ROWS) and the joint extremes; the last ``shown`` cycles'
    diagnostics for the figures."""

    def __init__(
        self,
        p,
        joints,
        effects,
        integrator,
        ideal_cycle: Mapping[str, np.ndarray],
        per: int,
        shown: int,
        ripple_cutoff_hz: float,
        y0=None,
        memory=None,
    ):
        self.p, self.joints, self.per, self.shown = p, tuple(joints), per, shown
        self.run = run(p, joints, effects, integrator, y0=y0, memory=memory)
        self.ideal = np.stack([ideal_cycle[q] for q in RESPONSES])  # one turn, its end point included
        self.harmonic = ripple_harmonic(ripple_cutoff_hz, p.crank_speed)
        self.memories, self.extremes, self.last, self.peak_refinement = [], [], [], []

    @property
    def fallbacks(self) -> int:
        """Cycles of this run the compiled NDF handed to scipy's BDF (``simulate.Run.fallbacks``)."""
        return self.run.fallbacks

    def step(self, n: int) -> tuple[np.ndarray, np.ndarray]:
        """``n`` more cycles: (section points (n, components), measures (n, MEASURE_ROWS))."""
        T = 2 * np.pi / self.p.crank_speed
        points, measures = [], []
        for _ in range(n):
            self.memories.append(self.run.memory())
            points.append(section_point(self.p, self.joints, self.run.y))
            t = self.run.t + np.arange(self.per + 1) * T / self.per
            _, diags = self.run.advance(t)
            turn = diags[:, :2].T - self.ideal
            d = turn[:, :-1]
            measures.append(np.r_[np.sqrt(np.mean(d**2, axis=1)), np.abs(d).max(axis=1), ripple(turn, self.harmonic)])
            self.peak_refinement.append([peak_refinement(row) for row in d])
            cols = [[4 + 6 * k + 1, 4 + 6 * k, 4 + 6 * k + 3, 4 + 6 * k + 4] for k in range(len(self.joints))]
            self.extremes.append(
                np.array(
                    [
                        [
                            np.nanmax(diags[:, c[0]]), np.nanmax(diags[:, c[1]]), np.nanmax(diags[:, c[2]]),
                            np.nanmax(np.abs(diags[:, c[3]])),
                        ]
                        for c in cols
                    ]
                )
            )
            self.last = (self.last + [(t, diags)])[-self.shown:]
        return np.array(points), np.array(measures)


def ripple_harmonic(cutoff_hz: float, crank_speed: float) -> int:
    """The highest crank harmonic at or below ``cutoff_hz`` (Hz) at ``crank_speed`` (rad/s): the ripple is the content
    above it."""
    return int(np.floor(cutoff_hz * 2.0 * np.pi / crank_speed + 1e-9))


def ripple(x: np.ndarray, harmonic: int) -> np.ndarray:
    """RMS of the content above crank harmonic ``harmonic`` of rows ``x`` (..., n + 1): one turn sampled at n equal
    steps, its end point included.  The straight line from the first to the last sample is taken off first, so that
    a turn that does not close (a state that is not periodic) puts no jump into the high harmonics; then Parseval's
    sum over the harmonics above ``harmonic`` of the discrete Fourier transform.  Units of x."""
    x = np.asarray(x, dtype=float)
    n = x.shape[-1] - 1
    line = x[..., :1] + (x[..., -1:] - x[..., :1]) * (np.arange(n) / n)
    spectrum = np.fft.rfft(x[..., :-1] - line, axis=-1) / n
    weight = np.full(spectrum.shape[-1], 2.0)  # each harmonic k and -k of a real signal
    weight[0] = 1.0
    if n % 2 == 0:
        weight[-1] = 1.0  # the Nyquist harmonic is its own conjugate
    weight[: harmonic + 1] = 0.0
    return np.sqrt(np.sum(weight * np.abs(spectrum) ** 2, axis=-1))


def peak_refinement(x: np.ndarray) -> float:
    """How much the peak of |x| (a periodic sample of one cycle) rises when refined by the parabola through the largest
    sample and its two neighbours (>= 0): an estimate of what the sampling misses of a narrow peak."""
    a = np.abs(x)
    k = int(np.argmax(a))
    y0, y1, y2 = a[k - 1], a[k], a[(k + 1) % a.size]
    curvature = y0 - 2.0 * y1 + y2
    return float(-((y0 - y2) ** 2) / (8.0 * curvature)) if curvature < 0 else 0.0


def settle_start(runner: CycleRunner, st: Mapping[str, Any], confidence: float) -> dict[str, Any]:
    """Settle one start (``st``: the ``states`` settings) and return ``engines.states.settle``'s record."""
    return settle(
        runner.step, st["chunk_cycles"], st["max_cycles"], st["max_period"], st["section_tolerance"], st["periods"],
        st["min_cycles"], confidence, rows=SETTLE_ROWS,
    )


def convergence_error(measures: np.ndarray, found: Mapping[str, Any]) -> np.ndarray:
    """Per measure row: what a periodic state that still converges can move its measure beyond the last period, from
    the per-period means over the judged window: the last change times rho / (1 - rho), rho the ratio of the last two
    changes (at most 0.99; 0 where fewer than three periods are judged or the state is not periodic)."""
    if found["status"] != PERIODIC:
        return np.zeros(measures.shape[1])
    first, stop = found["window"]
    k = found["period"]
    n = (stop - first) // k
    if n < 3:
        return np.zeros(measures.shape[1])
    means = measures[stop - n * k : stop].reshape(n, k, -1).mean(axis=1)
    d1, d2 = np.abs(means[-2] - means[-3]), np.abs(means[-1] - means[-2])
    rho = np.clip(np.divide(d2, d1, out=np.zeros_like(d2), where=d1 > 0), 0.0, 0.99)
    return d2 * rho / (1.0 - rho)


def judged_statistics(measures: np.ndarray, found: Mapping[str, Any], batch: int, confidence: float) -> np.ndarray:
    """Per measure row: (mean, confidence half-width, standard error, degrees of freedom, cycles judged) over the
    judged window.  A periodic state: the mean over its last period (the most settled), exact (half-width 0: the
    orbit repeats to the section tolerance).  A stationary one: batch means over the window, where that row is itself
    stationary over the window (its last third agrees with its middle third, ``thirds_agree``: the settling rule reads
    only some rows, and a row it did not read can still drift); a row that drifts has no interval (infinite
    half-width).  A record that reached the cap: its mean drifts, no interval (infinite half-width)."""
    from .statistics import mean_ci

    first, stop = found["window"]
    x = measures[first:stop]
    out = np.empty((measures.shape[1], 5))
    for r in range(measures.shape[1]):
        if found["status"] == PERIODIC:
            out[r] = (x[-found["period"]:, r].mean(), 0.0, 0.0, float("inf"), found["period"])
        else:
            mean, half, se, dof = mean_ci(x[:, r], batch, confidence)
            if found["status"] != "stationary" or not thirds_agree(x[:, r], confidence)[0]:
                half, se = float("inf"), float("inf")
            out[r] = (mean, half, se, dof, x.shape[0])
    return out


def check_state(
    make_runner, found: Mapping[str, Any], runner: CycleRunner, checks, st: Mapping[str, Any]
) -> dict[str, np.ndarray]:
    """The same state at each check integrator: restarted from the section point (with the contact memory) at the start
    of the last judged period (a periodic state) or of the judged window (else), run ``check_cycles`` cycles (at least
    two periods).  Per check: the mean of each measure row over its last period (periodic state) or over all its cycles
    (else), against the pipeline's mean over its judged period or the same cycles of the window (any drift left in the
    state is counted with the error) and that mean itself; whether the rerun keeps the state (its last section point
    within
    ``state_tolerance`` times max(1, |component|) of a point of the pipeline orbit, in every component; NaN where the
    state is not periodic: not testable); the period its section shows over the rerun (0 where the rerun is too short to
    show one: a report, not a test; -1 where the check integrator failed, its delta then NaN); and how many of the
    reruns' cycles the compiled NDF handed to scipy's BDF (``simulate.Run.fallbacks``).

    ``make_runner(integrator, memory)`` builds a CycleRunner at a check integrator from a run state."""
    first, stop = found["window"]
    period = found["period"]
    n = max(st["check_cycles"], 2 * period) if period != NOT_PERIODIC else st["check_cycles"]
    measures = found["measures"]
    deltas = np.full((len(checks), measures.shape[1]), np.nan)
    means = np.full((len(checks), measures.shape[1]), np.nan)
    kept, periods, distances = (
        np.full(len(checks), np.nan), np.zeros(len(checks), dtype=int), np.full(len(checks), np.nan),
    )
    orbit = found["points"][stop - period : stop] if period != NOT_PERIODIC else None
    restart = stop - period if period != NOT_PERIODIC else first
    fallbacks = 0
    for i, integ in enumerate(checks):
        rerun = make_runner(integ, runner.memories[restart])
        try:
            pts, meas = rerun.step(n)
        except RuntimeError:  # the check integrator gave up (a step size underflow): this check has no value
            periods[i] = -1
            continue
        finally:
            fallbacks += rerun.fallbacks
        if period != NOT_PERIODIC:
            ours = meas[-period:].mean(axis=0)
            base = measures[stop - period : stop].mean(axis=0)
            k, _ = section_period(pts, st["max_period"], 0.0, st["section_tolerance"], 2)
            periods[i] = k
            scale = np.maximum(1.0, np.abs(orbit))
            distances[i] = np.min(np.max(np.abs(pts[-1][None] - orbit) / scale, axis=1))
            kept[i] = float(distances[i] <= st["state_tolerance"])
        else:
            ours = meas.mean(axis=0)
            base = measures[first : min(first + n, stop)].mean(axis=0)
        deltas[i], means[i] = ours - base, ours
    return {
        "delta": deltas, "mean": means, "kept": kept, "period": periods, "distance": distances, "fallbacks": fallbacks,
    }


def reach_state(
    make_runner,
    found: Mapping[str, Any],
    start_runner_args: Mapping[str, Any],
    check,
    st: Mapping[str, Any],
    batch: int,
    confidence: float,
) -> dict[str, Any]:
    """The start settled again from its initial state at the check integrator ``check`` (``make_runner(check,
    **start_runner_args)`` builds its runner): the state it reaches (status, period), its measure (judged as the
    pipeline's: ``judged_statistics``'s mean per measure row) minus the pipeline's, and whether it is the pipeline's
    state (both periodic with the same period and its last section point within ``state_tolerance`` times
    max(1, |component|) of a point of the pipeline orbit: 1, else 0; NaN where the pipeline state is not periodic:
    not testable); the cycles the compiled NDF handed to scipy's BDF.  A failed check integrator (step size underflow):
    status 'failed', the rest NaN."""
    n_rows = found["measures"].shape[1]
    out = {"status": "failed", "period": -1, "delta": np.full(n_rows, np.nan), "same": np.nan, "cycles": 0}
    runner = make_runner(check, **start_runner_args)
    try:
        reached = settle_start(runner, st, confidence)
    except RuntimeError:
        return out
    finally:
        out["fallbacks"] = runner.fallbacks
    ours = judged_statistics(reached["measures"], reached, batch, confidence)[:, 0]
    base = judged_statistics(found["measures"], found, batch, confidence)[:, 0]
    out.update(status=reached["status"], period=reached["period"], delta=ours - base, cycles=reached["points"].shape[0])
    if found["period"] != NOT_PERIODIC:
        orbit = found["points"][found["window"][1] - found["period"] : found["window"][1]]
        last = reached["points"][reached["window"][1] - 1]
        distance = np.min(np.max(np.abs(last[None] - orbit) / np.maximum(1.0, np.abs(orbit)), axis=1))
        out["same"] = float(reached["period"] == found["period"] and distance <= st["state_tolerance"])
    return out
