"""Parameter sweeps that fan out: one independent job per grid point, gathered into one Dataset.

A sweep is named after its paper (``sweeps.<paper>`` in config): its grid (``small`` or ``large``)
maps two axis names to value lists; the paper's ``studies.sweep_point(cfg, point, spec)`` computes
the outputs at one point and its ``SWEEP_OUTPUTS`` gives their units and long names.
"""

from __future__ import annotations

import itertools
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

#: Units and long names of the axes any sweep may use.
AXES = {
    "clearance_m": ("m", "radial clearance of the swept joints"),
    "crank_speed_rad_s": ("rad s-1", "crank speed"),
    "heald_mass_kg": ("kg", "heald-frame mass M_P"),
}


def grid(axes: Mapping[str, Sequence[float]]) -> list[dict[str, float]]:
    """Every point of the grid: the product of the axes, first axis slowest."""
    names = list(axes)
    return [dict(zip(names, values, strict=True)) for values in itertools.product(*(axes[n] for n in names))]


def point_dataset(point: Mapping[str, float], values: Mapping[str, float], outputs: Mapping[str, tuple[str, str]]):
    """One grid point: its coordinates and its outputs as scalar variables with units."""
    import xarray as xr

    data = {k: ((), v, {"units": outputs[k][0], "long_name": outputs[k][1]}) for k, v in values.items()}
    data.update({a: ((), v, {"units": AXES[a][0], "long_name": AXES[a][1]}) for a, v in point.items()})
    return xr.Dataset(data)


def gather(axes: Mapping[str, Sequence[float]], points: Sequence[Any]):
    """All points on the (axis 1, axis 2) grid; every cell is filled exactly once."""
    import xarray as xr

    a, b = list(axes)
    av, bv = np.array(axes[a], dtype=float), np.array(axes[b], dtype=float)
    variables = [k for k in points[0].data_vars if k not in (a, b)]
    out = {k: np.full((av.size, bv.size), np.nan) for k in variables}
    filled = np.zeros((av.size, bv.size), dtype=int)
    for ds in points:
        i, j = int(np.argmin(np.abs(av - float(ds[a])))), int(np.argmin(np.abs(bv - float(ds[b]))))
        filled[i, j] += 1
        for k in variables:
            out[k][i, j] = float(ds[k])
    if not (filled == 1).all():
        raise ValueError(f"sweep points do not fill the {a} x {b} grid once each (counts {filled.tolist()})")
    return xr.Dataset(
        {k: ((a, b), v, points[0][k].attrs) for k, v in out.items()},
        coords={a: (a, av, {"units": AXES[a][0], "long_name": AXES[a][1]}), b: (b, bv, {"units": AXES[b][0], "long_name": AXES[b][1]})},
    )


def gathered(cfg: Mapping[str, Any], points: Sequence[Any]):
    """Rule study: the points of one sweep (``cfg``: its name, grid size and axes) on their grid."""
    ds = gather(cfg["axes"], points)
    ds.attrs["title"] = f"{cfg['name']} sweep ({cfg['grid']} grid)"
    return ds
