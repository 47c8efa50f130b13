"""The heald sweep (joint clearance x assumed reaction ratio |R_E|/|R_F|) on a chain model: per point the E/F
force ratio the first claim is judged on and the peak joint forces, then the gathered grid with the facts
that interpret it (where the ratio crosses the claim's threshold).

Both axes act on the E and F branches.  The reaction axis is model A's assumed input: model B takes its reactions from
its own kinetostatics (``model.model_b_parameters``), so the sweep runs model A.  The heald-frame mass M_P (and the warp
stiffness k_O) are not swept: in model B the E and F branches hang on the driven node, whose velocity the drive
prescribes, so Q_E and Q_F do not depend on the warp branch at all (``warp_branch_independence`` shows it, and the
gathered sweep records it at the reference point); in model A M_P scales the peak forces but not the smallest E/F ratio,
which is set at low frequency by the joint stiffnesses.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import xarray as xr

from ...pipeline.sweeps import gather, interpret, points_dataset
from .adapter import amplitude, omega_grid, parameters
from .dynamics import joint_forces


def point_parameters(cfg: Mapping[str, Any], point: Mapping[str, float]) -> dict[str, float]:
    """The model parameters at a point: clearance_m in both joints, |R_E| = reaction_ratio_EF x |R_F| (|R_F| as in
    config)."""
    p = parameters(cfg)
    return {
        **p,
        "clearance_E": point["clearance_m"],
        "clearance_F": point["clearance_m"],
        "reaction_E": point["reaction_ratio_EF"] * p["reaction_F"],
    }


def sweep_point(cfg: Mapping[str, Any], point: Mapping[str, float], spec: Mapping[str, Any]) -> dict[str, float]:
    """Smallest |Q_E|/|Q_F| and peak |Q_E|, |Q_F| over the speed band at one (clearance, reaction ratio) point
    (``spec``: the sweep's chain model)."""
    _, q_e, q_f, _ = joint_forces(
        spec["model"], point_parameters(cfg, point), "elastic", omega_grid(cfg["speeds"]), amplitude(cfg)
    )
    return {
        "ratio_EF_min": float((np.abs(q_e) / np.abs(q_f)).min()),
        "peak_Q_E": float(np.abs(q_e).max()),
        "peak_Q_F": float(np.abs(q_f).max()),
    }


def warp_branch_independence(
    cfg: Mapping[str, Any], point: Mapping[str, float], model: str, changes: Mapping[str, float]
) -> float:
    """Largest relative change of |Q_E| and |Q_F| over the speed band at a sweep point when the parameters in
    ``changes`` (e.g. M_P, k_O) take the given values: round-off in model B for any warp-branch parameter, not in
    model A."""
    w, amp = omega_grid(cfg["speeds"]), amplitude(cfg)
    p = point_parameters(cfg, point)
    _, e0, f0, _ = joint_forces(model, p, "elastic", w, amp)
    _, e1, f1, _ = joint_forces(model, {**p, **changes}, "elastic", w, amp)
    return float(max(np.max(np.abs(e1 - e0) / np.abs(e0)), np.max(np.abs(f1 - f0) / np.abs(f0))))


#: Units and long names of the sweep outputs.
SWEEP_OUTPUTS = {
    "ratio_EF_min": ("1", "min |Q_E|/|Q_F| over the speed band"),
    "peak_Q_E": ("N", "peak |Q_E| over the speed band"),
    "peak_Q_F": ("N", "peak |Q_F| over the speed band"),
}


def thresholds(published: Mapping[str, Any]) -> dict[str, dict[str, Any]]:
    """The first claim's threshold ('many times' read as at least 3x, from the published file) on the E/F ratio."""
    claim = next(q for q in published["quantities"] if q["id"] == "force_E_many_times_F")
    return {"ratio_EF_min": {"value": float(claim["value"]), "along": "reaction_ratio_EF",
                             "label": f"claim: |Q_E|/|Q_F| at least {claim['value']:g} over the whole band"}}


def sweep(cfg: Mapping[str, Any], points: Sequence[Mapping[str, float]], spec: Mapping[str, Any]) -> xr.Dataset:
    """Rule study: the points of one job of the heald sweep as a Dataset (coordinates and outputs)."""
    ds = points_dataset(points, [sweep_point(cfg, p, spec) for p in points], SWEEP_OUTPUTS)
    ds.attrs["title"] = f"heald sweep, {len(points)} point(s)"
    return ds


#: The warp-branch parameters whose independence the gathered sweep records, and the factor each is changed by.
WARP_BRANCH_CHANGES = {"M_P": 2.0, "k_O": 2.0}


def gathered(cfg: Mapping[str, Any], points: Sequence[xr.Dataset], published: Mapping[str, Any]) -> xr.Dataset:
    """Rule study: the heald sweep's jobs on their grid with the facts that interpret it (trends, where the E/F
    ratio crosses the claim's threshold, colour ranges) and why the warp branch is not swept (the change of
    Q_E, Q_F when M_P or k_O doubles, per model); ``cfg``: grid size, axes, the sweep's spec, reference point and
    the paper's values a point reads (``paper``)."""
    ds = interpret(gather(cfg["axes"], points), cfg["reference"], thresholds(published))
    p = parameters(cfg["paper"])
    models = ["A", "B"]
    change = [
        [
            warp_branch_independence(cfg["paper"], cfg["reference"], m, {k: f * p[k]})
            for k, f in WARP_BRANCH_CHANGES.items()
        ]
        for m in models
    ]
    ds["warp_branch_change"] = (
        ("model", "warp_parameter"),
        np.array(change),
        {
            "units": "1",
            "long_name": (
                "largest relative change of |Q_E|, |Q_F| over the band when the parameter is multiplied by its factor"
            ),
        },
    )
    ds = ds.assign_coords(
        model=(
            "model", np.array(models, dtype=object),
            {"units": "1", "long_name": "A: physical linkage; B: chain of the form of eq. (2)"},
        ),
        warp_parameter=(
            "warp_parameter", np.array(list(WARP_BRANCH_CHANGES), dtype=object),
            {"units": "1", "long_name": "warp-branch parameter"},
        ),
        warp_factor=(
            "warp_parameter", np.array(list(WARP_BRANCH_CHANGES.values())),
            {"units": "1", "long_name": "factor the parameter is multiplied by"},
        ),
    )
    ds.attrs.update(title=f"heald sweep ({cfg['grid']} grid)", model=cfg["spec"]["model"])
    return ds
