"""Parameter sweeps that fan out: independent jobs over a grid, gathered into one Dataset with the facts
that interpret it.

A sweep is named after its paper (``sweeps.<paper>`` in config): its grid (``small`` or ``large``)
maps two axis names to value lists; the grid's points are split into jobs of ``points_per_job`` points
(a point costs a fraction of a second, a job's start about a second and a half).  The paper's
``sweep`` module computes the outputs at the points of one job (``SWEEP_OUTPUTS`` gives their units
and long names) and gathers the jobs with ``gather`` and ``interpret``: how each output changes along
each axis, where a claim's threshold is crossed, and a colour range that shows relative change.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

#: Units and long names of the axes any sweep may use.
AXES = {
    "clearance_m": ("m", "radial clearance of the swept joints"),
    "crank_speed_rad_s": ("rad s-1", "crank speed"),
    "heald_mass_kg": ("kg", "heald-frame mass M_P"),
    "reaction_ratio_EF": ("1", "assumed reaction ratio |R_E| / |R_F| (|R_F| fixed)"),
}

#: The colour range of a map is never narrower than COLOUR_FLOOR_FACTOR below to COLOUR_FLOOR_FACTOR above its
#: centre (log scale): a 5 % change then takes at most log(1.05) / log(4) = 3.5 % of the colour bar.
COLOUR_FLOOR_FACTOR = 2.0

#: What a NaN threshold crossing means.
NO_CROSSING = "the output does not cross the threshold along this line of the grid"


def grid(axes: Mapping[str, Sequence[float]]) -> list[dict[str, float]]:
    """Every point of the grid: the product of the axes, first axis slowest."""
    names = list(axes)
    return [dict(zip(names, values, strict=True)) for values in itertools.product(*(axes[n] for n in names))]


def batches(points: Sequence[Mapping[str, float]], per_job: int) -> list[list[Mapping[str, float]]]:
    """The grid's points in consecutive jobs of at most ``per_job`` points, as evenly filled as that allows."""
    if per_job < 1:
        raise ValueError(f"points_per_job must be at least 1, not {per_job}")
    jobs = max(1, math.ceil(len(points) / per_job))
    return [list(part) for part in np.array_split(np.array(points, dtype=object), jobs)]


def point_dataset(point: Mapping[str, float], values: Mapping[str, float], outputs: Mapping[str, tuple[str, str]]):
    """One grid point: its coordinates and its outputs as scalar variables with units."""
    import xarray as xr

    data = {k: ((), v, {"units": outputs[k][0], "long_name": outputs[k][1]}) for k, v in values.items()}
    data.update({a: ((), v, {"units": AXES[a][0], "long_name": AXES[a][1]}) for a, v in point.items()})
    return xr.Dataset(data)


def points_dataset(
    points: Sequence[Mapping[str, float]], values: Sequence[Mapping[str, float]], outputs: Mapping[str, tuple[str, ...]]
):
    """The points of one job along a ``point`` dimension: coordinates and outputs with units (an output's optional
    third field says what its NaN means)."""
    import xarray as xr

    data = {
        k: (
            "point", [v[k] for v in values],
            {"units": spec[0], "long_name": spec[1], **({"nan_meaning": spec[2]} if len(spec) > 2 else {})},
        )
        for k, spec in outputs.items()
    }
    data.update(
        {a: ("point", [p[a] for p in points], {"units": AXES[a][0], "long_name": AXES[a][1]}) for a in points[0]}
    )
    return xr.Dataset(data)


def _each_point(datasets: Sequence[Any]):
    for ds in datasets:
        if "point" in ds.dims:
            yield from (ds.isel(point=i) for i in range(ds.sizes["point"]))
        else:
            yield ds


def gather(axes: Mapping[str, Sequence[float]], points: Sequence[Any]):
    """All points (single-point or job datasets) on the (axis 1, axis 2) grid; every cell is filled exactly once."""
    import xarray as xr

    a, b = list(axes)
    av, bv = np.array(axes[a], dtype=float), np.array(axes[b], dtype=float)
    variables = [k for k in points[0].data_vars if k not in (a, b)]
    out = {k: np.full((av.size, bv.size), np.nan) for k in variables}
    filled = np.zeros((av.size, bv.size), dtype=int)
    for ds in _each_point(points):
        i, j = int(np.argmin(np.abs(av - float(ds[a])))), int(np.argmin(np.abs(bv - float(ds[b]))))
        filled[i, j] += 1
        for k in variables:
            out[k][i, j] = float(ds[k])
    if not (filled == 1).all():
        raise ValueError(f"sweep points do not fill the {a} x {b} grid once each (counts {filled.tolist()})")
    return xr.Dataset(
        {k: ((a, b), v, points[0][k].attrs) for k, v in out.items()},
        coords={
            a: (a, av, {"units": AXES[a][0], "long_name": AXES[a][1]}),
            b: (b, bv, {"units": AXES[b][0], "long_name": AXES[b][1]}),
        },
    )


def _nearest(values: np.ndarray, target: float) -> int:
    """Index of the grid value nearest ``target`` (on a log scale when all are positive)."""
    if (values > 0).all() and target > 0:
        return int(np.argmin(np.abs(np.log(values) - np.log(target))))
    return int(np.argmin(np.abs(values - target)))


def crossings(x: np.ndarray, y: np.ndarray, threshold: float) -> float:
    """First x at which y crosses ``threshold`` between neighbouring grid values (linear in log x where x > 0,
    else linear); NaN if it does not cross.  A grid value exactly at the threshold is a crossing there."""
    s = y - threshold
    for k in range(x.size - 1):
        if s[k] == 0.0:
            return float(x[k])
        if s[k] * s[k + 1] < 0:
            u = np.log(x[k : k + 2]) if (x[k : k + 2] > 0).all() else x[k : k + 2]
            f = s[k] / (s[k] - s[k + 1])
            v = u[0] + f * (u[1] - u[0])
            return float(np.exp(v) if (x[k : k + 2] > 0).all() else v)
    return float(x[-1]) if s[-1] == 0.0 else float("nan")


def trend(values: np.ndarray) -> dict[str, float]:
    """Along axis 0 of ``values`` (axis 0 the swept axis, axis 1 the other): the relative change from the first to
    the last grid value on each line (smallest and largest over the lines), and the fraction of lines on
    which every step moves the way the line's overall change does (monotone lines)."""
    change = values[-1] / values[0] - 1.0
    steps = np.diff(values, axis=0)
    monotone = np.all(steps * np.sign(values[-1] - values[0]) >= 0, axis=0)
    return {
        "change_low": float(change.min()),
        "change_high": float(change.max()),
        "monotone_fraction": float(monotone.mean()),
    }


def resolved_trend(values: np.ndarray, spread: np.ndarray) -> dict[str, float]:
    """Along axis 0 of ``values`` (each cell a mean over recorded cycles, ``spread`` its cycle-to-cycle spread,
    largest - smallest): the fraction of lines whose first-to-last change exceeds the sum of the two end cells'
    spreads, upwards and downwards, and the fraction of neighbouring steps (over all lines) that do.

    A mean lies inside its cycles' range, so a change larger than the sum of the spreads separates the two
    ranges: only such a change is a trend rather than the scatter of the cycles."""
    change = values[-1] - values[0]
    resolved = np.abs(change) > spread[-1] + spread[0]
    steps = np.abs(np.diff(values, axis=0)) > spread[1:] + spread[:-1]
    return {
        "resolved_up": float(np.mean(resolved & (change > 0))),
        "resolved_down": float(np.mean(resolved & (change < 0))),
        "resolved_steps": float(np.mean(steps)),
    }


#: What the lines of a grid say about an output's change along an axis, given its cycle-to-cycle spread.
TREND_CLASSES = {
    "grows": "grows beyond the cycle scatter on every line",
    "falls": "falls beyond the cycle scatter on every line",
    "partly": "changes beyond the cycle scatter on some lines only (no trend over the whole grid)",
    "none": "changes beyond the cycle scatter on no line (no trend)",
}


def trend_class(resolved_up: float, resolved_down: float) -> str:
    """The key of TREND_CLASSES for the fractions of lines resolved upwards and downwards (``resolved_trend``)."""
    if resolved_up == 1.0:
        return "grows"
    if resolved_down == 1.0:
        return "falls"
    return "none" if resolved_up == 0.0 and resolved_down == 0.0 else "partly"


def interpret(
    ds,
    reference: Mapping[str, float],
    thresholds: Mapping[str, Mapping[str, Any]],
    scatter: Mapping[str, str] | None = None,
):
    """The facts a sweep's paragraph states, added to the gathered Dataset ``ds`` (two axes, nonzero outputs):

    * per output and axis: the relative change from the first to the last value of the axis (smallest and
      largest over the other axis) and the fraction of monotone lines (``trend``);
    * per output: its value at the reference point (the grid point nearest ``reference``), its relative span
      (max - min) / reference value, and a colour range on a log scale centred on the threshold (if the output
      has one) or the reference value, symmetric, at least COLOUR_FLOOR_FACTOR either side;
    * per output with a threshold (``thresholds[output]``: ``value``, ``along`` (an axis), ``label``): the fraction
      of grid cells at or above it and, for every value of the other axis, where the output crosses it along
      ``along``;
    * per output with a cycle-to-cycle spread (``scatter[output]``: the name of the spread output): the fractions
      of lines and steps along each axis whose change exceeds the spread (``resolved_trend``), and the spread
      relative to the output (at the reference point, smallest and largest over the grid).
    """
    import xarray as xr

    a, b = [d for d in ds[next(iter(ds.data_vars))].dims]
    outputs = list(ds.data_vars)
    ia, ib = _nearest(ds[a].values, reference[a]), _nearest(ds[b].values, reference[b])
    n_out = len(outputs)
    change_low, change_high, monotone = (np.full((n_out, 2), np.nan) for _ in range(3))
    ref_value, span, c_low, c_high, t_value, t_holds = (np.full(n_out, np.nan) for _ in range(6))
    scatter = dict(scatter or {})
    res_up, res_down, res_steps = (np.full((n_out, 2), np.nan) for _ in range(3))
    rel_ref, rel_low, rel_high = (np.full(n_out, np.nan) for _ in range(3))
    classes = np.full((n_out, 2), "", dtype=object)
    new: dict[str, Any] = {}
    for o, name in enumerate(outputs):
        v = ds[name].transpose(a, b).values
        for k, axis in enumerate((a, b)):
            t = trend(v if axis == a else v.T)
            change_low[o, k], change_high[o, k], monotone[o, k] = (
                t["change_low"], t["change_high"], t["monotone_fraction"],
            )
        ref_value[o] = v[ia, ib]
        if name in scatter:
            sv = ds[scatter[name]].transpose(a, b).values
            for k, axis in enumerate((a, b)):
                r = resolved_trend(v, sv) if axis == a else resolved_trend(v.T, sv.T)
                res_up[o, k], res_down[o, k], res_steps[o, k] = (
                    r["resolved_up"], r["resolved_down"], r["resolved_steps"],
                )
                classes[o, k] = TREND_CLASSES[trend_class(r["resolved_up"], r["resolved_down"])]
            rel = sv / np.abs(v)
            rel_ref[o], rel_low[o], rel_high[o] = rel[ia, ib], rel.min(), rel.max()
        span[o] = (v.max() - v.min()) / abs(ref_value[o])
        spec = thresholds.get(name)
        centre = float(spec["value"]) if spec else float(ref_value[o])
        if v.min() > 0 and centre > 0:  # else no log colour range (NaN): the report colours the range linearly
            factor = max(COLOUR_FLOOR_FACTOR, float(v.max() / centre), float(centre / v.min()))
            c_low[o], c_high[o] = centre / factor, centre * factor
        if spec:
            along = spec["along"]
            other = b if along == a else a
            w = ds[name].transpose(other, along).values
            t_value[o] = float(spec["value"])
            t_holds[o] = float(np.mean(w >= spec["value"]))
            cross = [crossings(ds[along].values, w[i], spec["value"]) for i in range(w.shape[0])]
            new[f"{name}_threshold_crossing"] = (
                other,
                cross,
                {
                    "units": ds[along].attrs["units"],
                    "long_name": (
                        f"{ds[along].attrs['long_name']} at which {name} crosses its threshold ({spec['label']})"
                    ),
                    "nan_meaning": NO_CROSSING,
                    "threshold": float(spec["value"]),
                    "along": along,
                },
            )
            side = np.where((w >= spec["value"]).all(axis=1), 1, np.where((w < spec["value"]).all(axis=1), -1, 0))
            new[f"{name}_threshold_side"] = (
                other,
                side,
                {
                    "units": "1",
                    "long_name": (
                        f"{name} along {along}: 1 at or above its threshold "
                        "on the whole line, -1 below it on the whole line, 0 on both sides"
                    ),
                },
            )
    no_log = {"nan_meaning": "the output is not positive everywhere: no log colour range"}
    thresh_nan = {"nan_meaning": "the output has no claim threshold"}
    scatter_nan = {"nan_meaning": "the output has no cycle-to-cycle spread"}
    new.update(
        {
            "trend_change_low": (
                ("output", "axis"),
                change_low,
                {
                    "units": "1",
                    "long_name": "smallest relative change (last / first - 1) along the axis, over the other axis",
                },
            ),
            "trend_change_high": (
                ("output", "axis"),
                change_high,
                {
                    "units": "1",
                    "long_name": "largest relative change (last / first - 1) along the axis, over the other axis",
                },
            ),
            "trend_monotone_fraction": (
                ("output", "axis"), monotone,
                {"units": "1", "long_name": "fraction of grid lines along the axis on which the output is monotone"},
            ),
            "reference_value": (
                "output", ref_value, {"units": "SI of the output", "long_name": "output at the reference point"},
            ),
            "relative_span": (
                "output", span, {"units": "1", "long_name": "(max - min) over the grid / value at the reference point"},
            ),
            "colour_low": (
                "output", c_low,
                {"units": "SI of the output", "long_name": "lower end of the colour range (log scale)", **no_log},
            ),
            "colour_high": (
                "output", c_high,
                {"units": "SI of the output", "long_name": "upper end of the colour range (log scale)", **no_log},
            ),
            "threshold_value": (
                "output", t_value,
                {"units": "SI of the output", "long_name": "claim threshold of the output", **thresh_nan},
            ),
            "threshold_holds_fraction": (
                "output", t_holds,
                {"units": "1", "long_name": "fraction of grid cells at or above the threshold", **thresh_nan},
            ),
            "trend_resolved_up_fraction": (
                ("output", "axis"),
                res_up,
                {
                    "units": "1",
                    "long_name": (
                        "fraction of grid lines along the axis on which "
                        "the output grows from first to last by more than the sum of the two cells' cycle spreads"
                    ),
                    **scatter_nan,
                },
            ),
            "trend_resolved_down_fraction": (
                ("output", "axis"),
                res_down,
                {
                    "units": "1",
                    "long_name": (
                        "fraction of grid lines along the axis on "
                        "which the output falls from first to last by more than the sum of the two cells' cycle spreads"
                    ),
                    **scatter_nan,
                },
            ),
            "trend_resolved_step_fraction": (
                ("output", "axis"),
                res_steps,
                {
                    "units": "1",
                    "long_name": (
                        "fraction of neighbouring grid steps along "
                        "the axis whose change exceeds the sum of the two cells' cycle spreads"
                    ),
                    **scatter_nan,
                },
            ),
            "trend_resolved_class": (
                ("output", "axis"),
                classes,
                {
                    "units": "1",
                    "long_name": (
                        "what the grid lines say about the change along "
                        "the axis, given the cycle spread ('' for an output without one)"
                    ),
                },
            ),
            "relative_scatter_reference": (
                "output", rel_ref,
                {"units": "1", "long_name": "cycle spread / output at the reference point", **scatter_nan},
            ),
            "relative_scatter_low": (
                "output", rel_low,
                {"units": "1", "long_name": "smallest cycle spread / output over the grid", **scatter_nan},
            ),
            "relative_scatter_high": (
                "output", rel_high,
                {"units": "1", "long_name": "largest cycle spread / output over the grid", **scatter_nan},
            ),
        }
    )
    labels = [thresholds[n]["label"] if n in thresholds else "" for n in outputs]
    out = ds.assign(**{k: xr.Variable(*spec) for k, spec in new.items()}).assign_coords(
        output=("output", np.array(outputs, dtype=object), {"units": "1", "long_name": "sweep output"}),
        axis=("axis", np.array([a, b], dtype=object), {"units": "1", "long_name": "sweep axis"}),
        threshold_label=(
            "output", np.array(labels, dtype=object),
            {"units": "1", "long_name": "what the threshold is ('' for none)"},
        ),
    )
    out.attrs.update({f"reference_{a}": float(ds[a].values[ia]), f"reference_{b}": float(ds[b].values[ib]),
                      "colour_floor_factor": COLOUR_FLOOR_FACTOR})
    return out


def gathered(cfg: Mapping[str, Any], points: Sequence[Any]):
    """The points of one sweep (``cfg``: its name, grid size and axes) on their grid, without interpretation."""
    ds = gather(cfg["axes"], points)
    ds.attrs["title"] = f"{cfg['name']} sweep ({cfg['grid']} grid)"
    return ds
