"""Statistics of the clearance claims: the mean of a per-cycle measure with its confidence interval on a state that
is not periodic, and orderings that hold only beyond both the statistical and the numerical margin.

When a scene settles into a state that is not periodic (see ``settling``), each judged cycle gives one value of a
claim's measure (RMS or peak deviation from the ideal curve over that cycle).  Consecutive cycles can be correlated (an
impact pattern that repeats every few turns), so the confidence interval of the mean is a batch-means t-interval: the
recorded cycles are cut into batches of ``batch`` consecutive cycles, and the interval is mean +- t_(1 - (1 -
confidence)/2, n_b - 1) s_b / sqrt(n_b) over the n_b batch means (s_b their sample standard deviation).  With ``batch =
1`` it is the ordinary t-interval.

An ordering a > b (or a linear combination) is *decided* only where the difference of the means exceeds both
its statistical margin (the t-interval of the difference, Welch-Satterthwaite degrees of freedom) and its
numerical error (the sum of the scenes' numerical errors).  A claim made of several orderings holds where all
hold decidedly, fails where one fails decidedly, and is undetermined otherwise.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

DECISION_RULE = (
    "an ordering is decided where |difference of the means| exceeds both its confidence half-width and the sum of the"
    " scenes' numerical errors"
)
UNDETERMINED, FAILS, HOLDS = -1, 0, 1


def _t_quantile(confidence: float, dof: float) -> float:
    """The two-sided ``confidence`` quantile of Student's t with ``dof`` (real) degrees of freedom: the value
    scipy.stats.t.ppf(0.5 + confidence / 2, dof) returns, from scipy.special (importing scipy.stats costs a
    scene job about a second)."""
    from scipy.special import stdtrit

    return float(stdtrit(dof, 0.5 + confidence / 2))


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


def difference(
    terms: Sequence[tuple[float, float, float, float, float]], confidence: float
) -> tuple[float, float, float]:
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
