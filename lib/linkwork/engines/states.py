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
    later (``repeats_after``) over at least ``periods`` whole periods up to the end of the record; the tolerance
    of a component is ``rtol`` times its spread over the last half of the record plus ``atol``.  The transient is
    that t (cycles before the orbit).  A record with no such k: (NOT_PERIODIC, number of cycles).

    The test is on the change over one period, not on the distance to the orbit: a state that approaches its orbit
    contracting by a factor rho per period lies within tol / (1 - rho) of it once it repeats to tol."""
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
