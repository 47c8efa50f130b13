"""Bounded searches over the assumed inputs' box, per scenario: each value's minimum and maximum, and the best
consistent assumption set of a paper's rows.

The box is the unit cube of the continuous inputs (``Input.to_value`` maps a unit coordinate to the input's
range, log-uniformly where the range spans more than a decade).  A paper's model is one function of a point of
the box returning every compared quantity at once, so one cache serves every search.

* **Extremes.**  A value's interval over the assumed inputs is its minimum and maximum over the box.  Each search
  starts from the best of the samples (nominal, one at a time, corners, Latin hypercube) and of the *monotone
  corner* (every input at the end of its range that moved the value the wanted way when moved alone), then runs
  scipy's bounded Powell method for at most ``evaluations`` model evaluations.  The samples only start it.  A start
  at a vertex of the box where no input moved inwards improves the value ends the search there (one probe per
  input, shared by every value whose extreme sits at that vertex).
* **Consistent set.**  Per scenario and model variant, one point of the box under which the most rows match at
  once (a row matches at a point when its value lies in its acceptance region; numerical error bars are the
  comparison's, not the search's).  The count is maximised through a capped violation (each row's distance
  outside its region in units of its tolerance, at most 1), from the best starts.  A row that matches somewhere
  in the box but not at the best point is searched again with its own violation weighted: it belongs to a
  maximal consistent set only if that search matches as many rows with it.

Published values enter here only as the comparison's acceptance regions (``linkwork.pipeline.compare``).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from typing import Any

import numpy as np

#: A value the model could not compute (NaN) counts as this far from any target in a search.
FAR = 1e30
#: Weight of the one row a forced consistent-set search must match.
FORCE_WEIGHT = 100.0
#: Coordinates this many step tolerances from a face of the box are tried on the face after a search.
SNAP = 10.0
#: Starts of a consistent-set search: the best points evaluated so far (a forced search: the best one).
CONSISTENT_STARTS = 2


class Evaluator:
    """A cached model on the unit box: ``ev(u)`` -> every quantity's value at the point ``u`` (clipped to the box)."""

    def __init__(self, fun: Callable[[np.ndarray], np.ndarray], dim: int):
        self.fun, self.dim, self.cache = fun, dim, {}

    def __call__(self, u: np.ndarray) -> np.ndarray:
        u = np.clip(np.asarray(u, dtype=float).reshape(self.dim), 0.0, 1.0)
        key = tuple(np.round(u, 12))
        if key not in self.cache:
            self.cache[key] = np.asarray(self.fun(u), dtype=float)
        return self.cache[key]

    def seed(self, points: np.ndarray, values: np.ndarray) -> None:
        """Values already computed (the samples) enter the cache."""
        for u, v in zip(points, values, strict=True):
            self.cache.setdefault(tuple(np.round(np.clip(u, 0.0, 1.0), 12)), np.asarray(v, dtype=float))

    @property
    def evaluations(self) -> int:
        return len(self.cache)

    def points(self) -> tuple[np.ndarray, np.ndarray]:
        """Every point evaluated so far and its values (rows)."""
        keys = list(self.cache)
        return np.array(keys, dtype=float).reshape(len(keys), self.dim), np.array([self.cache[k] for k in keys])


def _powell(objective: Callable[[np.ndarray], float], start: np.ndarray, evaluations: int, xtol: float) -> None:
    """Run scipy's bounded Powell method on the unit box from ``start`` (the objective records what it sees)."""
    from scipy.optimize import Bounds, minimize

    if evaluations <= 0 or start.size == 0:
        return
    minimize(objective, start, method="Powell", bounds=Bounds(np.zeros(start.size), np.ones(start.size)),
             options={"maxfev": evaluations, "xtol": xtol, "ftol": 1e-10})


def monotone_corner(oat_low_u: np.ndarray, oat_high_u: np.ndarray, nominal_u: np.ndarray, sign: float) -> np.ndarray:
    """The corner that moves a value the ``sign`` way (+1: up) input by input: each input at the end of its range
    whose one-at-a-time value was larger (for +1), at its nominal unit coordinate where neither end moved it.

    ``oat_low_u``, ``oat_high_u``: the value with each input at the low and high end of its range, others nominal."""
    u = np.asarray(nominal_u, dtype=float).copy()
    up = sign * (np.asarray(oat_high_u) - np.asarray(oat_low_u))
    u[up > 0] = 1.0
    u[up < 0] = 0.0
    return u


def extreme(
    ev: Evaluator, q: int, sign: float, starts: Sequence[np.ndarray], evaluations: int, xtol: float
) -> tuple[float, np.ndarray]:
    """The largest (``sign`` = +1) or smallest (-1) value of quantity ``q`` over the box: the best of ``starts``,
    then a bounded Powell search from it.  Returns (value, unit point)."""
    best = {"f": -np.inf, "u": None}

    def objective(u: np.ndarray) -> float:
        v = ev(u)[q]
        if np.isfinite(v) and sign * v > best["f"]:
            best["f"], best["u"] = sign * v, np.clip(u, 0.0, 1.0)
        return -sign * v if np.isfinite(v) else FAR

    for u in starts:
        objective(np.asarray(u, dtype=float))
    if best["u"] is None:
        return np.nan, np.full(ev.dim, np.nan)
    if vertex_is_local_extreme(objective, best["u"], SNAP * xtol):
        return sign * best["f"], best["u"]
    _powell(objective, best["u"].copy(), evaluations, xtol)
    objective(snapped(best["u"], xtol))
    return sign * best["f"], best["u"]


def vertex_is_local_extreme(objective: Callable[[np.ndarray], float], u: np.ndarray, step: float) -> bool:
    """Whether ``u`` is a vertex of the unit box at which no input moved inwards by ``step`` lowers ``objective``
    (the first-order optimality condition at a vertex, checked by one probe per input).  Such a vertex ends the
    search: the extremes of a value monotone in each input lie at vertices, which the samples include, and the
    probes from one vertex are shared (cached) by every value whose extreme sits there."""
    u = np.asarray(u, dtype=float)
    if u.size == 0 or not np.all((u == 0.0) | (u == 1.0)):
        return False
    here = objective(u)
    for i in range(u.size):
        probe = u.copy()
        probe[i] = step if u[i] == 0.0 else 1.0 - step
        if objective(probe) < here:
            return False
    return True


def is_flat(values: np.ndarray, nominal: float, rtol: float) -> bool:
    """Whether a value's samples (nominal, one at a time, corners, Latin hypercube) spread by at most ``rtol`` of
    its magnitude: a value the assumed inputs do not move beyond rounding (a ratio in which they cancel), whose
    search would chase rounding noise.  Its interval stays the samples' range."""
    finite = values[np.isfinite(values)]
    return finite.size > 1 and float(np.ptp(finite)) <= rtol * max(abs(float(nominal)), np.finfo(float).tiny)


def snapped(u: np.ndarray, xtol: float) -> np.ndarray:
    """``u`` with every coordinate within SNAP x ``xtol`` of a face of the unit box moved onto it (a search that
    stops at its tolerance next to a corner then tries the corner itself)."""
    u = np.asarray(u, dtype=float).copy()
    u[u < SNAP * xtol] = 0.0
    u[u > 1.0 - SNAP * xtol] = 1.0
    return u


def violations(values: np.ndarray, lower: np.ndarray, upper: np.ndarray, scale: np.ndarray) -> np.ndarray:
    """Each row's distance outside its acceptance region [lower, upper], in units of ``scale`` (0 inside; a NaN
    value counts as 1)."""
    values = np.asarray(values, dtype=float)
    with np.errstate(invalid="ignore"):
        out = np.maximum.reduce([lower - values, values - upper, np.zeros_like(values)]) / scale
    return np.where(np.isfinite(values), out, 1.0)


def consistent_set(ev: Evaluator, rows: Sequence[int], lower: np.ndarray, upper: np.ndarray, scale: np.ndarray,
                   evaluations: int, xtol: float, force: int | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The point of the box under which most of ``rows`` (quantity indices) match at once.

    Maximises the count of rows inside their regions through the capped violation sum; with ``force`` (a
    position in ``rows``) that row's violation is weighted by FORCE_WEIGHT.  Returns (unit point, matched flags
    of ``rows`` there)."""
    rows = list(rows)
    weight = np.ones(len(rows))
    if force is not None:
        weight[force] = FORCE_WEIGHT

    def score(u: np.ndarray) -> tuple[int, float]:
        viol = violations(ev(u)[rows], lower, upper, scale)
        matched = viol == 0
        return (
            int(matched.sum()) + (0 if force is None or matched[force] else -len(rows) - 1),
            float(np.sum(weight * np.minimum(viol, 1.0))),
        )

    points, _ = ev.points()
    ranked = sorted(points, key=lambda u: (-score(u)[0], score(u)[1]))[:CONSISTENT_STARTS if force is None else 1]
    for start in ranked:
        _powell(lambda u: score(u)[1], np.asarray(start, dtype=float).copy(), evaluations, xtol)
    points, _ = ev.points()
    best = min(points, key=lambda u: (-score(u)[0], score(u)[1]))
    return best, violations(ev(best)[rows], lower, upper, scale) == 0


def acceptance_regions(published: Mapping[str, Any], keys: Sequence[str]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Per quantity key ('model|id'): the lower and upper end of its acceptance region and its tolerance (NaN
    for a key that is not a headline entry)."""
    from .compare import acceptance, tolerance_of

    entries = {e["id"]: e for e in published.get("quantities", []) if e.get("measure") is not None}
    lower, upper, tol = (np.full(len(keys), np.nan) for _ in range(3))
    for k, key in enumerate(keys):
        entry = entries.get(key.split("|", 1)[1])
        if entry is not None:
            t = tolerance_of(entry)
            lower[k], upper[k] = acceptance(float(entry["value"]), t, entry.get("relation", "eq"))
            tol[k] = max(t, 1e-12 * abs(float(entry["value"])), 1e-300)
    return lower, upper, tol


def _unit_points(ds: Any, inputs: Sequence[Any], rows: Sequence[int]) -> np.ndarray:
    """The unit coordinates of the given samples (rows of ``ds.input_value``)."""
    values = ds.input_value.values[list(rows)]
    return np.array([[inp.to_unit(x) for inp, x in zip(inputs, row, strict=True)] for row in values]).reshape(
        len(rows), len(inputs)
    )


def _end_values(
    ds: Any, labels: Sequence[str], prefix: str, inputs: Sequence[Any], end: str, fallback: np.ndarray
) -> np.ndarray:
    """Per continuous input (rows) the values with that input alone at one ``end`` ('low' or 'high') of its range."""
    out = np.tile(fallback, (len(inputs), 1))
    for k, inp in enumerate(inputs):
        label = f"{prefix}{inp.path} {end}"
        if label in labels:
            out[k] = ds.value.values[labels.index(label)]
    return out


def refine(ds: Any, cfg: Mapping[str, Any], published: Mapping[str, Any], inputs: Sequence[Any],
           results: Callable[[Mapping[str, Any]], Sequence[Any]], settings: Mapping[str, Any],
           held: Callable[[Any], set[str]] | None = None, workers: int = 1) -> Any:
    """The gathered study ``ds`` (linkwork.pipeline.uncertainty.summary) with each headline value's low and high
    replaced by its extremes over the box (bounded searches from the samples), where they were found, and per
    scenario and model variant the best consistent assumption set.  ``settings``: ``evaluations`` per search and
    ``xtol`` (unit-box step tolerance).  Table cells keep the samples' range (corners included).

    ``held(scenario)``: the input paths the paper declares its searched values do not read in that scenario (the
    search holds them at their nominal values and needs no evaluation to learn that they are flat).  ``workers``:
    processes that search the scenarios side by side (each scenario's searches are independent and deterministic,
    so the result does not depend on it)."""
    from .uncertainty import continuous, scenarios

    ranged, scens = continuous(inputs), scenarios(inputs)
    keys = [str(k) for k in ds.quantity.values]
    lower, upper, tol = acceptance_regions(published, keys)
    models = list(dict.fromkeys(k.split("|", 1)[0] for k in keys))
    held = held or (lambda _: set())
    tasks = [
        (ds, n, scen, cfg, published, ranged, results, settings, held(scen), models) for n, scen in enumerate(scens)
    ]
    found = _map(_search_task, tasks, workers)
    low, high = ds.low.values.copy(), ds.high.values.copy()
    shape_at = (len(scens), len(ranged), len(keys))
    low_at, high_at = np.full(shape_at, np.nan), np.full(shape_at, np.nan)
    matched_best, in_set = np.full((len(scens), len(keys)), np.nan), np.full((len(scens), len(keys)), np.nan)
    count, candidates = np.zeros((len(scens), len(models))), np.zeros((len(scens), len(models)))
    best_at = np.full((len(scens), len(models), len(ranged)), np.nan)
    evaluations = np.zeros(len(scens))
    for n, part in enumerate(found):
        if part is None:
            continue
        low[n], high[n], low_at[n], high_at[n] = part["low"], part["high"], part["low_at"], part["high_at"]
        matched_best[n], in_set[n], count[n], candidates[n] = (
            part["matched_best"], part["in_set"], part["count"], part["candidates"],
        )
        best_at[n], evaluations[n] = part["best_at"], part["evaluations"]
    return _with_search(
        ds, low, high, low_at, high_at, matched_best, in_set, count, candidates, best_at, evaluations, models, settings
    )


#: The tasks of the running ``_map``, inherited by its forked workers (they hold closures, which do not pickle).
_TASKS: list[Any] = []


def _run_forked(index: int) -> Any:
    fun, task = _TASKS[index]
    return fun(task)


def _map(fun: Callable[[Any], Any], tasks: Sequence[Any], workers: int) -> list[Any]:
    """``[fun(t) for t in tasks]``, in up to ``workers`` forked processes, in order."""
    if workers <= 1 or len(tasks) <= 1:
        return [fun(t) for t in tasks]
    import multiprocessing

    _TASKS[:] = [(fun, t) for t in tasks]
    try:
        with multiprocessing.get_context("fork").Pool(min(workers, len(tasks))) as pool:
            return pool.map(_run_forked, range(len(tasks)), chunksize=1)
    finally:
        _TASKS.clear()


def _search_task(task: tuple) -> dict[str, np.ndarray] | None:
    return _search_scenario(*task)


def _search_scenario(
    ds: Any,
    n: int,
    scen: Any,
    cfg: Mapping[str, Any],
    published: Mapping[str, Any],
    ranged: Sequence[Any],
    results: Callable[[Mapping[str, Any]], Sequence[Any]],
    settings: Mapping[str, Any],
    held: set[str],
    models: Sequence[str],
) -> dict[str, np.ndarray] | None:
    """The searches of one scenario (``refine``): extremes of each headline value and the consistent sets, over the
    inputs not ``held`` (held inputs stay nominal; their entries in the ``*_at`` points are their nominal values)."""
    from .uncertainty import _prefix, apply, evaluate

    keys = [str(k) for k in ds.quantity.values]
    labels, of = [str(x) for x in ds.sample.values], [str(x) for x in ds.sample_scenario.values]
    rows = [i for i, o in enumerate(of) if o == scen.label]
    if not rows:
        return None
    headline_only = {**published, "tables": []}
    lower, upper, tol = acceptance_regions(published, keys)
    headline = [q for q in range(len(keys)) if np.isfinite(tol[q])]
    free = [k for k, inp in enumerate(ranged) if inp.path not in held]
    sub = [ranged[k] for k in free]
    budget, xtol = int(settings["evaluations"]), float(settings["xtol"])

    def fun(u: np.ndarray) -> np.ndarray:  # the headline values only: table cells are not searched
        moved = {inp.path: inp.to_value(x) for inp, x in zip(sub, u, strict=True)}
        found = evaluate(headline_only, results(apply(cfg, {**scen.values, **moved})))
        return np.array([found.get(tuple(k.split("|", 1)), np.nan) for k in keys])

    def full(u: np.ndarray) -> np.ndarray:  # a point of the searched inputs as every input's value
        at = np.array([float(inp.nominal) for inp in ranged])
        at[free] = [inp.to_value(x) for inp, x in zip(sub, u, strict=True)]
        return at

    ev = Evaluator(fun, len(sub))
    ev.seed(_unit_points(ds, ranged, rows)[:, free], ds.value.values[rows])  # held inputs do not move these values
    prefix = _prefix(scen, n == 0)
    nominal_u = np.array([inp.to_unit(inp.nominal) for inp in sub])
    nominal_v = ds.nominal.values[n]
    ends = (
        _end_values(ds, labels, prefix, sub, "low", nominal_v),
        _end_values(ds, labels, prefix, sub, "high", nominal_v),
    )
    out = {
        "low": ds.low.values[n].copy(),
        "high": ds.high.values[n].copy(),
        "low_at": np.full((len(ranged), len(keys)), np.nan),
        "high_at": np.full((len(ranged), len(keys)), np.nan),
        "matched_best": np.full(len(keys), np.nan),
        "in_set": np.full(len(keys), np.nan),
        "count": np.zeros(len(models)),
        "candidates": np.zeros(len(models)),
        "best_at": np.full((len(models), len(ranged)), np.nan),
    }
    points, values = ev.points()
    flat = float(settings["flat_rtol"])
    for q in headline:
        if not np.isfinite(nominal_v[q]) or not sub or is_flat(values[:, q], nominal_v[q], flat):
            continue
        for sign, end in ((-1.0, "low"), (1.0, "high")):
            finite = np.isfinite(values[:, q])
            start = points[finite][np.argmax(sign * values[finite, q])] if finite.any() else nominal_u
            corner = monotone_corner(ends[0][:, q], ends[1][:, q], nominal_u, sign)
            v, u = extreme(ev, q, sign, [start, corner], budget, xtol)
            if np.isfinite(v):
                old = out[end][q]
                out[end][q] = v if not np.isfinite(old) else (min(v, old) if sign < 0 else max(v, old))
                out[f"{end}_at"][:, q] = full(u)
    for m, model in enumerate(models):
        rows_m = [q for q in headline if keys[q].startswith(f"{model}|") and np.isfinite(nominal_v[q])]
        # robust deviations (the whole interval outside the region) cannot join a consistent set
        rows_m = [q for q in rows_m if not (out["high"][q] < lower[q] or out["low"][q] > upper[q])]
        out["candidates"][m] = len(rows_m)
        if not rows_m:
            continue
        lo, hi, sc = lower[rows_m], upper[rows_m], tol[rows_m]
        best, ok = consistent_set(ev, rows_m, lo, hi, sc, budget if sub else 0, xtol)
        out["count"][m] = ok.sum()
        out["best_at"][m] = full(best)
        for j, q in enumerate(rows_m):
            out["matched_best"][q] = out["in_set"][q] = float(ok[j])
            if not ok[j] and sub:
                _, forced = consistent_set(ev, rows_m, lo, hi, sc, budget, xtol, force=j)
                out["in_set"][q] = float(forced[j] and forced.sum() >= ok.sum())
    out["evaluations"] = ev.evaluations
    return out


def _with_search(
    ds, low, high, low_at, high_at, matched_best, in_set, count, candidates, best_at, evaluations, models, settings
):
    """The study Dataset with the searches' results (see ``refine``)."""
    out = ds.copy()
    out["low"] = (
        ("scenario", "quantity"), low,
        {**ds.low.attrs, "long_name": "smallest value over the assumed inputs' box (bounded search from the samples)"},
    )
    out["high"] = (
        ("scenario", "quantity"), high,
        {**ds.high.attrs, "long_name": "largest value over the assumed inputs' box (bounded search from the samples)"},
    )
    out["low_at"] = (
        ("scenario", "input", "quantity"),
        low_at,
        {
            "units": "SI of the input",
            "long_name": "the inputs where the smallest value was found",
            "nan_meaning": "not searched (a table cell, or no continuous input)",
        },
    )
    out["high_at"] = (
        ("scenario", "input", "quantity"),
        high_at,
        {
            "units": "SI of the input",
            "long_name": "the inputs where the largest value was found",
            "nan_meaning": "not searched (a table cell, or no continuous input)",
        },
    )
    nan = {"nan_meaning": "not a candidate (a table cell, not reproducible, or a robust deviation)"}
    out["matched_in_best_set"] = (
        ("scenario", "quantity"), matched_best,
        {"units": "1", "long_name": "1 if the row matches under the scenario's best consistent assumption set", **nan},
    )
    out["in_consistent_set"] = (
        ("scenario", "quantity"), in_set,
        {"units": "1", "long_name": "1 if the row matches in some consistent set of as many rows as the best", **nan},
    )
    out["consistent_count"] = (
        ("scenario", "row_model"), count,
        {"units": "1", "long_name": "rows matched at once under the best consistent assumption set"},
    )
    out["consistent_candidates"] = (
        ("scenario", "row_model"), candidates,
        {"units": "1", "long_name": "headline rows that are not robust deviations"},
    )
    out["consistent_at"] = (
        ("scenario", "row_model", "input"), best_at,
        {"units": "SI of the input", "long_name": "the best consistent assumption set"},
    )
    out["evaluations"] = (
        ("scenario",), evaluations,
        {"units": "1", "long_name": "distinct model evaluations per scenario (samples and searches)"},
    )
    out = out.assign_coords(
        row_model=(
            "row_model", np.array(models, dtype=object),
            {"units": "1", "long_name": "model variant of the compared rows"},
        )
    )
    out.attrs["interval_method"] = (
        "headline values: minimum and maximum over the box by bounded Powell searches (at most"
        f" {int(settings['evaluations'])} evaluations each) started from the samples' extremes and the monotone corner;"
        " table cells: the samples (corners included)"
    )
    out.attrs["search_evaluations"] = int(settings["evaluations"])
    out.attrs["search_xtol"] = float(settings["xtol"])
    out.attrs["consistent_set_rule"] = (
        "a row matches at a point when its value lies in its acceptance region; the best set maximises the rows "
        "matched at once (capped violations, bounded Powell from the best points evaluated)"
    )
    return out


def searcher(
    cfg: Mapping[str, Any],
    published: Mapping[str, Any],
    inputs: Sequence[Any],
    results: Callable[[Mapping[str, Any]], Sequence[Any]],
    held: Callable[[Any], set[str]] | None = None,
) -> Callable[..., Any]:
    """The search step of a paper's gather (``linkwork.pipeline.uncertainty.gathered``'s ``search``, called with the
    Dataset and the number of worker processes); ``held``: see ``refine``."""
    return lambda ds, workers=1: refine(
        ds, cfg, published, inputs, results, cfg["uncertainty"]["search"], held, workers
    )
