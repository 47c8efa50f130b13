"""The state a driven system settles into, from its Poincaré section (the state sampled once per drive period).

A record of section points x_0, x_1, ... (one row per drive cycle, one column per state component) settles onto a
periodic orbit of period k when, from some cycle t on, every point repeats k cycles later to a tolerance.  The
smallest such k is the orbit's period and t the transient's length; the claims of a paper are then judged on the
cycles after t (whole periods), never on the transient.  A record in which no k up to a bound repeats is "not
periodic" (a quasi-periodic or chaotic state, or one that has not settled yet): it is judged by other means.

Pure numerics on arrays: no units of its own (the section's components keep theirs; tolerances are per component).
"""

from __future__ import annotations

import numpy as np

#: Period reported for a record in which no period up to the bound repeats.
NOT_PERIODIC = 0


def repeats_after(points: np.ndarray, period: int, tol: np.ndarray) -> np.ndarray:
    """For each cycle i (0 .. n - period - 1), whether the section point of cycle i + ``period`` equals that of cycle
    i to ``tol`` in every component (|x[i + k] - x[i]| <= tol)."""
    x = np.atleast_2d(np.asarray(points, dtype=float).T).T
    return np.all(np.abs(x[period:] - x[:-period]) <= tol, axis=1)


def section_period(points, max_period: int, rtol: float, atol: float = 0.0, periods: int = 2) -> tuple[int, int]:
    """(period, transient) of a Poincaré section record ``points`` (cycles x components, or one component).

    The period is the smallest k <= ``max_period`` such that, from some cycle t on, every point repeats k cycles
    later (``repeats_after``) and lies within the tolerance of the record's last period (no slow drift), over at
    least ``periods`` whole periods up to the end of the record; the tolerance
    of a component is ``rtol`` times its spread over the last half of the record plus ``atol``.  The transient is
    that t (cycles before the orbit).  A record with no such k: (NOT_PERIODIC, number of cycles).

    A state that approaches its orbit contracting by a factor rho per period lies within tol / (1 - rho) of it once
    it repeats to tol; the distance to the last period bounds what a drift can leave in the judged window."""
    x = np.atleast_2d(np.asarray(points, dtype=float).T).T
    n = x.shape[0]
    tail = x[n // 2:]
    tol = rtol * (tail.max(axis=0) - tail.min(axis=0)) + atol
    for k in range(1, max_period + 1):
        if n - k < periods * k:
            break
        close = repeats_after(x, k, tol)
        misses = np.flatnonzero(~close)
        start = int(misses[-1]) + 1 if misses.size else 0  # the first cycle from which every point repeats
        # ... and lies within the tolerance of the last period's points: a slow drift, each step below the
        # tolerance, does not pass as an orbit
        final = x[n - k :]
        off = np.any(np.abs(x - final[(np.arange(n) - (n - k)) % k]) > tol, axis=1)
        far = np.flatnonzero(off)
        start = max(start, int(far[-1]) + 1 if far.size else 0)
        if close.size - start >= periods * k:
            return k, start
    return NOT_PERIODIC, n


def judged_window(cycles: int, period: int, transient: int, min_cycles: int) -> tuple[int, int]:
    """The cycles (first, stop) on which a settled periodic state is judged: after the transient, a whole number
    of periods, at least ``min_cycles`` long and ending at the record's end; (cycles, cycles), an empty window,
    if the record is too short or the state is not periodic."""
    if period == NOT_PERIODIC or transient >= cycles:
        return cycles, cycles
    length = ((cycles - transient) // period) * period
    if length < max(min_cycles, period):
        return cycles, cycles
    return cycles - length, cycles


def thirds_agree(values, confidence: float) -> tuple[bool, float]:
    """(stationary?, the largest relative change) of per-cycle records ``values`` (rows x cycles, or cycles): the
    mean of the last third against the mean of the middle third, for every row.  A row agrees where the difference
    lies within its Welch t-interval (the thirds' own cycle-to-cycle scatter): a transient that drifts by more than
    the scatter cannot pass, however small the drift is relative to the mean.  Fewer than 6 cycles: not stationary."""
    from scipy.special import stdtrit

    x = np.atleast_2d(np.asarray(values, dtype=float))
    n = x.shape[-1] // 3
    if n < 2:
        return False, float("inf")
    ok, worst = True, 0.0
    for row in x:
        a, b = row[-2 * n : -n], row[-n:]
        diff = abs(float(b.mean() - a.mean()))
        va, vb = a.var(ddof=1) / n, b.var(ddof=1) / n
        total = va + vb
        if total > 0:
            dof = total**2 / (va**2 / (n - 1) + vb**2 / (n - 1)) if va > 0 and vb > 0 else n - 1
            half = float(stdtrit(dof, 0.5 + confidence / 2)) * np.sqrt(total)
        else:
            half = 0.0
        scale = abs(float(row[-2 * n :].mean())) or 1.0
        worst = max(worst, diff / scale)
        ok = ok and diff <= half
    return ok, worst


def truncation_point(values) -> int:
    """The transient to cut from per-cycle records ``values`` (rows x cycles, or cycles) by the MSER rule (White,
    1997: the truncation d <= n / 2 that minimises the squared standard error of the remaining mean,
    sum (x_i - mean)^2 / (n - d)^2), the largest over the rows."""
    x = np.atleast_2d(np.asarray(values, dtype=float))
    n = x.shape[-1]
    best = 0
    for row in x:
        stats = [np.sum((row[d:] - row[d:].mean()) ** 2) / (n - d) ** 2 for d in range(n // 2 + 1)]
        best = max(best, int(np.argmin(stats)))
    return best


#: How a settled record ends: a periodic orbit found, statistics stationary over enough cycles, or the cycle cap.
PERIODIC, STATIONARY, CAP = "periodic", "stationary", "cycle cap reached"


def settle(step, chunk: int, max_cycles: int, max_period: int, section_tol: float, periods: int, min_cycles: int,
           confidence: float, rows=None) -> dict:
    """Run a driven system chunk by chunk until its state is found.

    ``step(n)`` runs n more drive cycles and returns (section points (n, components) at each cycle's start,
    per-cycle measures (n, rows)).  After each chunk: if the section repeats with a period k <= ``max_period`` to
    ``section_tol`` (absolute, per component) over ``periods`` whole periods (``section_period``), the state is
    periodic and judged on the whole periods after the transient; otherwise the transient is cut by the MSER rule
    (``truncation_point``) and, once the cut is at most a third of the record and at least ``min_cycles`` cycles
    remain, the state is stationary if the remaining
    measures' last third agrees with their middle third (``thirds_agree``); it is judged on the cycles after the cut.
    ``max_cycles`` is a size guard: a record that reaches it ends with status CAP (its last two thirds shown as
    window, with no interval).  ``rows``: the measure rows the transient cut and the stationarity test read (all by
    default); every row is recorded and returned.

    Returns {status, period, transient, window (first, stop), points, measures, change}."""
    points, measures = [], []
    while True:
        done = sum(len(p) for p in points)
        pts, meas = step(min(chunk, max_cycles - done))
        points.append(np.atleast_2d(pts))
        measures.append(np.atleast_2d(meas))
        x, m = np.concatenate(points), np.concatenate(measures)
        n = x.shape[0]
        period, transient = section_period(x, max_period, 0.0, section_tol, periods)
        if period != NOT_PERIODIC:
            first, stop = judged_window(n, period, transient, period)
            return {
                "status": PERIODIC,
                "period": period,
                "transient": transient,
                "window": (first, stop),
                "points": x,
                "measures": m,
                "change": 0.0,
            }
        tested = m if rows is None else m[:, list(rows)]
        cut = truncation_point(tested.T)
        # a cut beyond a third of the record says the transient may still leave a bias in the window: not yet
        ok, change = (
            thirds_agree(tested[cut:].T, confidence)
            if n - cut >= min_cycles and cut <= n // 3
            else (False, float("inf"))
        )
        if ok or n >= max_cycles:
            cut = cut if ok else n // 3
            return {
                "status": STATIONARY if ok else CAP,
                "period": NOT_PERIODIC,
                "transient": cut,
                "window": (cut, n),
                "points": x,
                "measures": m,
                "change": thirds_agree(tested[cut:].T, confidence)[1],
            }
