"""The transplanter paper's accuracy study: elements per member and modes vs the error in tip deflection and
peak stress, and the solve time."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import xarray as xr

from ...pipeline.accuracy import summary_variables
from ...pipeline.timing import median_time, run_and_time
from ...units import angle_grid_deg
from .adapter import discretisation, material, mechanism
from .adapter import gravity as gravity_of
from .model import ked_modal
from .studies import solve

ROUNDING = 1e-16  # error entered for an exact method


def reference_angles(result, window: float, spread: int = 2) -> np.ndarray:
    """Crank angles (mask) where the peak |Uy| or the peak stress of ``result`` lies within ``window`` (a
    fraction) of its maximum, widened by ``spread`` grid steps either side: where a finer mesh's maxima are."""
    tip, stress = np.abs(result.tip[:, 1]), result.stress.max(axis=1)
    near = (tip >= (1 - window) * tip.max()) | (stress >= (1 - window) * stress.max())
    for _ in range(spread):
        near = near | np.roll(near, 1) | np.roll(near, -1)
    return near


def accuracy(cfg: Mapping[str, Any]) -> tuple[xr.Dataset, dict[str, Any]]:
    """Elements per member and modes vs error in tip deflection and peak stress, and solve time."""
    acc = cfg["accuracy"]
    d = np.array(cfg["initial_diameters_m"], dtype=float)
    theta = angle_grid_deg(cfg["fe"]["angle_step_deg"])
    base = np.array(cfg["fe"]["elements_per_member"])
    kinds, levels = acc["elements"], acc["refinements"]
    runs, times = {}, {}
    for kind in kinds:
        for level in levels:
            disc = discretisation(cfg, kind=kind, elements=tuple(base * level))
            runs[(kind, level)], times[f"{kind} x{level}"] = run_and_time(
                lambda disc=disc: solve(cfg, d, "quasi-static", theta, disc=disc), acc["repeats"]
            )
    # the reference (a much finer quintic mesh) only where the peaks are: near the finest studied mesh's maxima
    finest = runs[("quintic8", max(levels))] if "quintic8" in kinds else runs[(kinds[0], max(levels))]
    window = reference_angles(finest, acc["reference_window"])
    ref_r = solve(
        cfg, d, "quasi-static", theta[window],
        disc=discretisation(cfg, kind="quintic8", elements=tuple(base * acc["reference_refinement"])),
    )
    ref_tip, ref_stress = np.abs(ref_r.tip[:, 1]).max(), ref_r.stress.max()
    tip_err, stress_err, dofs = (np.empty((len(kinds), len(levels))) for _ in range(3))
    for i, kind in enumerate(kinds):
        for j, level in enumerate(levels):
            r = runs[(kind, level)]
            tip_err[i, j] = abs(np.abs(r.tip[:, 1]).max() - ref_tip) / ref_tip
            stress_err[i, j] = abs(r.stress.max() - ref_stress) / ref_stress
            dofs[i, j] = discretisation(cfg, kind=kind, elements=tuple(base * level)).mesh.dof_indices()[0]
    # mode superposition (the paper's route to K^-1 F): modes kept vs error, on the base mesh
    disc = discretisation(cfg)
    mech, mat, gravity = mechanism(cfg), material(cfg), gravity_of(cfg)
    modes = [n for n in acc["modes"] if n <= disc.mesh.dof_indices()[0]]
    full = solve(cfg, d, "quasi-static", theta, disc=disc)
    modal_tip, modal_stress = [], []
    for n in modes:
        tip, stress = ked_modal(mech, disc, d, mat, np.radians(theta), n, gravity)
        modal_tip.append(abs(np.abs(tip[:, 1]).max() - np.abs(full.tip[:, 1]).max()) / np.abs(full.tip[:, 1]).max())
        modal_stress.append(abs(stress.max() - full.stress.max()) / full.stress.max())
        times[f"{n} modes"] = median_time(
            lambda n=n: ked_modal(mech, disc, d, mat, np.radians(theta), n, gravity), 1, warmup=False
        )
    mesh_settings = [f"{kind} x{level}" for kind in kinds for level in levels]
    settings = mesh_settings + [f"{n} modes" for n in modes]
    errors = [*stress_err.ravel(), *np.maximum(modal_stress, ROUNDING)]
    ds = xr.Dataset(
        {
            "tip_error": (
                ("element", "refinement"), tip_err,
                {"units": "1", "long_name": "relative error of the peak |Uy| vs a fine quintic reference"},
            ),
            "stress_error": (
                ("element", "refinement"), stress_err,
                {"units": "1", "long_name": "relative error of the peak stress vs the reference"},
            ),
            "tip_error_max": (
                (), float(tip_err.max()),
                {"units": "1", "long_name": "largest relative error of the peak |Uy| over the meshes"},
            ),
            "dofs": (("element", "refinement"), dofs, {"units": "1", "long_name": "system coordinates"}),
            "modal_tip_error": (
                "modes", np.array(modal_tip),
                {"units": "1", "long_name": "relative error of the peak |Uy|, modes kept vs all (base mesh)"},
            ),
            "modal_stress_error": (
                "modes", np.array(modal_stress),
                {"units": "1", "long_name": "relative error of the peak stress, modes kept vs all"},
            ),
            **summary_variables("FE mesh and modes", settings, errors, f"{cfg['fe']['element']} x1"),
        },
        coords={
            "modes": ("modes", np.array(modes), {"units": "1", "long_name": "modes kept in the superposition"}),
            "element": ("element", np.array(kinds, dtype=object), {"units": "1", "long_name": "element type"}),
            "refinement": (
                "refinement", np.array(levels),
                {"units": "1", "long_name": "elements per member, multiple of the base mesh"},
            ),
        },
        attrs={
            "title": "Mesh and mode accuracy vs cost (transplanter)",
            "reference_refinement": acc["reference_refinement"],
            "base_mesh": str(list(base)),
            "reference_crank_angles": int(window.sum()),
        },
    )
    timings = {"method": f"median of {acc['repeats']} runs, time.perf_counter (modal: one run)", "summary_s": times}
    return ds, timings
