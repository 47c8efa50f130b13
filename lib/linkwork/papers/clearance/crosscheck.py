"""The clearance paper's ideal four-bar in an established engine (Exudyn) beside linkwork's inverse dynamics.

For each parameter variant and each Exudyn step, the largest difference of the crank torque and of the
rocker's angular acceleration from linkwork's ideal scene (inverse dynamics at the same times), relative
to the largest value of ours, over ``crosscheck.cycles`` crank turns from the dead point.  The two engines
agree if the difference at the finest step is below ``crosscheck.agreement`` and shrinks as the step does
(the difference is then Exudyn's discretisation error, not a difference of the models).  The dry and
lubricated clearance scenes are not yet modelled in Exudyn.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import xarray as xr

from ...engines.multibody.model import inverse_dynamics
from .adapter import parameters
from .studies import QUANTITIES


def relative_difference(theirs: np.ndarray, ours: np.ndarray) -> float:
    """max |theirs - ours| / max |ours| (1)."""
    return float(np.max(np.abs(theirs - ours)) / np.max(np.abs(ours)))


def observed_orders(steps: np.ndarray, differences: np.ndarray) -> np.ndarray:
    """log(d_i / d_(i+1)) / log(h_i / h_(i+1)) between successive steps (steps in decreasing order)."""
    return np.log(differences[:-1] / differences[1:]) / np.log(steps[:-1] / steps[1:])


def ideal(cfg: Mapping[str, Any]) -> xr.Dataset:
    """Rule study: the ideal scene of every variant in Exudyn at every step of ``crosscheck.steps_s``."""
    from ...engines.multibody.exudyn_route import ideal_run

    check = cfg["crosscheck"]
    variants = list(cfg["variants"])
    steps = np.array(sorted(check["steps_s"], reverse=True), dtype=float)
    diff = np.empty((len(variants), len(QUANTITIES), steps.size))
    wall = np.empty((len(variants), steps.size))
    version = ""
    for i, variant in enumerate(variants):
        p = parameters(cfg, variant, "ideal")
        end = check["cycles"] * 2 * np.pi / p.crank_speed
        for k, step in enumerate(steps):
            run = ideal_run(p, end, float(step), check["newton_tolerance"], gravity=True)
            ours = inverse_dynamics(p, run["t"], True)
            for q, quantity in enumerate(QUANTITIES):
                diff[i, q, k] = relative_difference(run[quantity], ours[quantity])
            wall[i, k] = run["wall_s"]
            version = run["version"]
            print(f"clearance_crosscheck: {variant} ideal, Exudyn step {step:.0e} s: torque {diff[i, 1, k]:.1e}, "
                  f"rocker acceleration {diff[i, 0, k]:.1e} (relative), {wall[i, k]:.1f} s", flush=True)
    orders = np.stack([[observed_orders(steps, diff[i, q]) for q in range(len(QUANTITIES))] for i in range(len(variants))])
    agree = (diff[..., -1] <= check["agreement"]) & np.all(diff[..., 1:] < diff[..., :-1], axis=-1)
    return xr.Dataset(
        {
            "relative_difference": (("variant", "quantity", "step"), diff, {"units": "1", "long_name": "max |Exudyn - linkwork| / max |linkwork|"}),
            "observed_order": (("variant", "quantity", "refinement"), orders, {"units": "1", "long_name": "observed order of the difference between successive steps"}),
            "exudyn_wall_s": (("variant", "step"), wall, {"units": "s", "long_name": "Exudyn's solver wall time (time.perf_counter, one run)"}),
            "agree": (("variant", "quantity"), agree, {"units": "1", "long_name": "difference below the agreement bound at the finest step and shrinking with the step"}),
        },
        coords={
            "variant": ("variant", np.array(variants, dtype=object), {"units": "1", "long_name": "parameter variant"}),
            "quantity": ("quantity", np.array(QUANTITIES, dtype=object), {"units": "1", "long_name": "compared response"}),
            "step": ("step", steps, {"units": "s", "long_name": "Exudyn's fixed time step"}),
            "refinement": ("refinement", np.arange(1, steps.size), {"units": "1", "long_name": "from step i-1 to step i"}),
        },
        attrs={
            "title": "Clearance paper, ideal scene: Exudyn beside linkwork's inverse dynamics",
            "engine": f"Exudyn {version}, Newmark (trapezoidal) with index-2 constraints",
            "cycles": check["cycles"],
            "agreement": check["agreement"],
            "newton_tolerance": check["newton_tolerance"],
        },
    )
