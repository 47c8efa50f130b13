"""The input the transplanter paper does not print: why its optimal diameters cannot be reproduced.

Under the inertia loads alone (the only loads the paper names) the rocker CD, pinned at both ends, carries
little more than its own inertia and the crank little bending, so both sit far below the allowable stress at
any diameter the paper prints; the objective SY + SZ then decreases with their diameters, and any optimiser
drives them to the 4 mm bound.  The printed optimum keeps them above it, so it implies a load we are not
told of.  Here (our inference, not the paper's): the inertia-only peak stress per member, and, per member,
the smallest constant tip force on the arm BE (config ``missing_load``: its directions) at which that member's
peak stress at the given diameters reaches the allowable, by a scan and Brent's method (a bounded 1-D solve).
SI units inside: N, Pa, m.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
from scipy.optimize import brentq

from .studies import inertia_only_peaks


def tip_force(magnitude_n: float, direction_deg: float) -> np.ndarray:
    """The tip force (N, global x and y) of ``magnitude_n`` at ``direction_deg`` (deg from +x, counter-clockwise)."""
    angle = np.radians(float(direction_deg))
    return magnitude_n * np.array([np.cos(angle), np.sin(angle)])


def inertia_only(cfg: Mapping[str, Any], diameters) -> np.ndarray:
    """Peak stress per member (Pa) under the inertia loads alone: no gravity, no external load."""
    return inertia_only_peaks(cfg, diameters)


def loads_making_active(cfg: Mapping[str, Any], diameters, allowable_pa: float,
                        direction_deg: float) -> dict[str, np.ndarray]:
    """Per member, the smallest tip force (N) on the arm, at ``direction_deg`` (deg), at which its peak stress at
    ``diameters`` (m) equals the allowable (NaN: none up to ``missing_load.max_N``), and every member's peak stress
    (Pa) under that force (member with the force, member stressed).

    One even scan of ``missing_load.scan_points`` forces over [0, max_N] finds each member's first sign change of
    (peak - allowable); Brent's method refines it to ``missing_load.xtol_N``.  The four forces agree only if one
    tip load of this direction could make the four diameters stress-active together; their spread is the evidence."""
    settings = cfg["missing_load"]
    peaks = lambda p: inertia_only_peaks(cfg, diameters, tip_force(p, direction_deg))  # noqa: E731
    grid = np.linspace(0.0, float(settings["max_N"]), int(settings["scan_points"]))
    excess = np.array([peaks(p) for p in grid]) - allowable_pa  # (scan, member)
    n = excess.shape[1]
    loads = np.full(n, np.nan)
    for i in range(n):
        change = np.flatnonzero(np.sign(excess[:-1, i]) != np.sign(excess[1:, i]))
        if change.size:
            k = int(change[0])
            loads[i] = brentq(lambda p, i=i: peaks(p)[i] - allowable_pa, grid[k], grid[k + 1],
                              xtol=float(settings["xtol_N"]))
    stresses = np.array([peaks(p) if np.isfinite(p) else np.full(n, np.nan) for p in loads])
    return {"load": loads, "stress": stresses}


def inferred_loads(cfg: Mapping[str, Any], diameters, allowable_pa: float) -> dict[str, np.ndarray]:
    """``loads_making_active`` for every direction of ``missing_load.directions_deg``: load (direction, member) in N,
    stress (direction, member with the force, member stressed) in Pa."""
    runs = [loads_making_active(cfg, diameters, allowable_pa, a) for a in cfg["missing_load"]["directions_deg"]]
    return {"load": np.array([r["load"] for r in runs]), "stress": np.array([r["stress"] for r in runs])}
