"""Statistics of the clearance claims: when a scene has settled, the mean of a per-cycle measure with its
confidence interval, and orderings that hold only beyond both the statistical and the numerical margin.

The dry response never becomes exactly periodic, so each recorded cycle gives one value of a claim's measure
(RMS or peak deviation from the ideal curve over that cycle).  A scene is *settled* at the first cycle k at
which the running mean over the last ``window`` cycles differs from the mean over the ``window`` cycles before
them by at most ``tolerance`` times the latter, for every quantity; the cycles after k are recorded.

Consecutive cycles can be correlated (an impact pattern that repeats every few turns), so the confidence
interval of the mean is a batch-means t-interval: the recorded cycles are cut into batches of ``batch``
consecutive cycles, and the interval is mean +- t_(1 - (1 - confidence)/2, n_b - 1) s_b / sqrt(n_b) over the
n_b batch means (s_b their sample standard deviation).  With ``batch = 1`` it is the ordinary t-interval.

A settled scene can still drift or switch regime over its record (a slowly growing deviation, an impact pattern
that changes halfway).  The record is *stationary* where, for every quantity, the means of its first and second
half differ by at most ``tolerance`` times the mean of the whole record or by no more than the Welch t-interval of
that difference (per-cycle values); a record that is not stationary is treated like an unsettled scene.

An ordering a > b (or a linear combination) is *decided* only where the difference of the means exceeds both
its statistical margin (the t-interval of the difference, Welch-Satterthwaite degrees of freedom) and its
numerical error (the sum of the scenes' numerical errors).  A claim made of several orderings holds where all
hold decidedly, fails where one fails decidedly, and is undetermined otherwise.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

#: The method of the confidence interval, recorded in the result's attributes.
CI_METHOD = ("batch-means t-interval: recorded cycles cut into batches of consecutive cycles; mean +- t(n_b - 1) s_b / sqrt(n_b) "
             "over the n_b batch means; a difference of two scenes by Welch-Satterthwaite")
DECISION_RULE = "an ordering is decided where |difference of the means| exceeds both its confidence half-width and the sum of the scenes' numerical errors"
UNDETERMINED, FAILS, HOLDS = -1, 0, 1


def _t_quantile(confidence: float, dof: float) -> float:
    """The two-sided ``confidence`` quantile of Student's t with ``dof`` (real) degrees of freedom: the value
    scipy.stats.t.ppf(0.5 + confidence / 2, dof) returns, from scipy.special (importing scipy.stats costs a
    scene job about a second)."""
    from scipy.special import stdtrit

    return float(stdtrit(dof, 0.5 + confidence / 2))


def running_change(values: np.ndarray, window: int) -> np.ndarray:
    """Per cycle k (1-based position k - 1): |mean(x[k-w+1..k]) - mean(x[k-2w+1..k-w])| / |mean(x[k-2w+1..k-w])|;
    NaN where fewer than 2w cycles precede (``values``: (..., cycle))."""
    x = np.asarray(values, dtype=float)
    out = np.full(x.shape, np.nan)
    for k in range(2 * window - 1, x.shape[-1]):
        last = x[..., k - window + 1 : k + 1].mean(axis=-1)
        before = x[..., k - 2 * window + 1 : k - window + 1].mean(axis=-1)
        with np.errstate(divide="ignore", invalid="ignore"):
            out[..., k] = np.abs(last - before) / np.abs(before)
    return out


def settle_point(values: np.ndarray, window: int, tolerance: float, latest: int) -> tuple[int, bool]:
    """(number of cycles discarded, settled?): the first cycle count k <= ``latest`` at which the running change
    of every row of ``values`` ((rows, cycle) or (cycle,)) is at most ``tolerance``; (latest, False) if none."""
    change = np.atleast_2d(running_change(values, window))
    for k in range(1, min(latest, change.shape[-1]) + 1):
        col = change[:, k - 1]
        if np.all(np.isfinite(col)) and np.all(col <= tolerance):
            return k, True
    return latest, False


def mean_ci(values: np.ndarray, batch: int, confidence: float) -> tuple[float, float, float, float]:
    """(mean, confidence half-width, standard error of the mean, degrees of freedom) of the per-cycle ``values``
    by batch means (see the module docstring); a trailing incomplete batch is left out of the spread only."""
    x = np.asarray(values, dtype=float)
    x = x[np.isfinite(x)]
    n_b = x.size // batch
    if n_b < 2:
        return float(x.mean()) if x.size else float("nan"), float("inf"), float("inf"), 0.0
    means = x[: n_b * batch].reshape(n_b, batch).mean(axis=1)
    se = float(means.std(ddof=1) / np.sqrt(n_b))
    dof = float(n_b - 1)
    return float(x.mean()), float(_t_quantile(confidence, dof) * se), se, dof


def half_change(values: np.ndarray, confidence: float) -> tuple[float, float]:
    """(|mean of the second half - mean of the first half| / |mean|, Welch t half-width of that difference / |mean|)
    of a per-cycle record (an odd middle cycle is left out of both halves); NaN for fewer than 4 cycles."""
    x = np.asarray(values, dtype=float)
    x = x[np.isfinite(x)]
    h = x.size // 2
    if h < 2:
        return float("nan"), float("nan")
    a, b = x[:h], x[-h:]
    scale = abs(float(x.mean()))
    va, vb = a.var(ddof=1) / h, b.var(ddof=1) / h
    total = va + vb
    if total == 0.0:
        half = 0.0
    else:
        dof = total**2 / (va**2 / (h - 1) + vb**2 / (h - 1))
        half = float(_t_quantile(confidence, dof) * np.sqrt(total))
    if scale == 0.0:
        return (0.0, 0.0) if float(b.mean() - a.mean()) == 0.0 and half == 0.0 else (float("inf"), float("inf"))
    return abs(float(b.mean() - a.mean())) / scale, half / scale


def stationary(values: np.ndarray, tolerance: float, confidence: float) -> tuple[bool, np.ndarray]:
    """(stationary?, relative half change per row) of a record ((rows, cycle) or (cycle,)): a row fails where its
    half change exceeds both ``tolerance`` and its own Welch half-width (see the module docstring)."""
    rows = np.atleast_2d(np.asarray(values, dtype=float))
    changes = np.array([half_change(r, confidence) for r in rows])
    ok = all(not (np.isfinite(c) and c > tolerance and c > w) for c, w in changes)
    return bool(ok), changes[:, 0]


def lag1_autocorrelation(values: np.ndarray) -> float:
    """Lag-1 autocorrelation of a per-cycle series (NaN for a constant series)."""
    x = np.asarray(values, dtype=float)
    x = x[np.isfinite(x)] - np.nanmean(x)
    denom = float(np.sum(x * x))
    return float(np.sum(x[1:] * x[:-1]) / denom) if denom > 0 else float("nan")


def difference(terms: Sequence[tuple[float, float, float, float, float]], confidence: float) -> tuple[float, float, float]:
    """(difference, statistical half-width, numerical error) of sum_i c_i m_i over ``terms`` (c_i, mean m_i,
    standard error, degrees of freedom, numerical error): the half-width uses Welch-Satterthwaite degrees of
    freedom; an infinite standard error (too few cycles) gives an infinite half-width."""
    d = sum(c * m for c, m, *_ in terms)
    var = [(c * se) ** 2 for c, _, se, _, _ in terms]
    num = sum(abs(c) * e for c, *_, e in terms)
    total = sum(var)
    if not np.isfinite(total):
        return float(d), float("inf"), float(num)
    if total == 0.0:
        return float(d), 0.0, float(num)
    dof = total**2 / sum(v**2 / f for v, (_, _, _, f, _) in zip(var, terms, strict=True) if v > 0)
    return float(d), float(_t_quantile(confidence, dof) * np.sqrt(total)), float(num)


def decide(diff: float, stat_margin: float, numerical_error: float) -> int:
    """HOLDS if diff > 0 and FAILS if diff < 0, where |diff| exceeds both margins; UNDETERMINED otherwise."""
    if abs(diff) > stat_margin and abs(diff) > numerical_error:
        return HOLDS if diff > 0 else FAILS
    return UNDETERMINED


def conjunction(outcomes: Sequence[int]) -> int:
    """All of several orderings: FAILS if one fails decidedly, HOLDS if all hold decidedly, else UNDETERMINED."""
    if any(o == FAILS for o in outcomes):
        return FAILS
    return HOLDS if all(o == HOLDS for o in outcomes) else UNDETERMINED
