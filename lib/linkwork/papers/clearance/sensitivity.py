"""How the clearance verdicts depend on the model: the other elastic law of the dry contact, and the contact memory of
the Lankarani-Nikravesh damping.

* **The elastic law.** Every compared scene with contact is continued from each start's nominal state under the
  other law (``clearance.sensitivity.elastic_law``, the conformal law of Pereira et al.) and settled and judged as an
  input-uncertainty sample is (``uncertainty.batch`` with the law as the moved value).
* **The contact memory.** The hysteresis damping divides by the impact velocity latched at a journal's first contact.
  A journal that stays pressed into its bushing keeps that value until a new impact, so two runs can differ in nothing
  but the latched value, and settle into different states.  Each dry scene's state from the second start is continued
  with the first start's latched velocities (and the reverse): if the measure follows the latched value, the starts'
  states differ by that memory alone.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from .fourbar import N_STATE
from .uncertainty import batch, sample_judgement

#: The dry scenes whose contact memory is swapped between the first two starts.
SWAPPED = ("dry_1", "dry_2", "dry_both")


def latched_slice(joints: int) -> slice:
    """Where a run state (``Run.memory()``: t, y, latched velocities, contact flags) keeps the latched velocities."""
    return slice(1 + N_STATE, 1 + N_STATE + joints)


def swapped_memory(memory: np.ndarray, donor: np.ndarray, joints: int) -> np.ndarray:
    """``memory`` with the latched impact velocities of ``donor`` (both run states of the same scene)."""
    out = np.array(memory, dtype=float)
    out[latched_slice(joints)] = np.asarray(donor, dtype=float)[latched_slice(joints)]
    return out


def model_sensitivity(cfg: Mapping[str, Any], variant: str, law: str, nominal: Sequence[Any] = ()):
    """Rule study: the compared scenes with contact under ``law`` from every start's nominal state, and the dry
    scenes' states with the other start's contact memory (the judged measure per scene and direction)."""

    from .studies import MEASURES, QUANTITIES, scene

    runs = {str(r.attrs["scene"]): r for r in nominal}
    starts = [str(x) for x in next(iter(runs.values())).start.values]
    ds = batch(
        cfg, [{"label": f"elastic law {law}", "values": {"joints.elastic_law": law}}], variant, nominal=nominal,
        all_starts=True,
    )
    names = [n for n in SWAPPED if n in runs]
    swap = np.full((len(names), 2, len(MEASURES), len(QUANTITIES)), np.nan)
    latched = np.full((len(names), 2, 2), np.nan)  # scene, start, joint
    if len(starts) > 1:
        for k, name in enumerate(names):
            base = runs[name]
            nj = len(str(base.attrs["clearance_joints"]).split(","))
            memories = base.window_memory.values
            latched[k, :, :nj] = memories[:2, latched_slice(nj)]
            for direction, (to, donor) in enumerate(((1, 0), (0, 1))):  # start 2 with start 1's memory, and the reverse
                run = scene(
                    cfg, variant, name, first_start_only=True, check=False,
                    memory=swapped_memory(memories[to], memories[donor], nj),
                )
                swap[k, direction] = run.judged_mean.values[0]
    ds["swap_mean"] = (
        ("swapped_scene", "direction", "measure", "quantity"),
        swap,
        {
            "units": "SI of the quantity",
            "long_name": "the claims' measure on the state continued with the other start's latched impact velocities",
            "nan_meaning": "one start only: nothing to swap",
        },
    )
    ds["latched_velocity"] = (
        ("swapped_scene", "start_index", "joint_index"),
        latched,
        {
            "units": "m s-1",
            "long_name": "impact velocity latched at the start of the judged window",
            "nan_meaning": "the scene has fewer clearance joints, or one start only",
        },
    )
    ds = ds.assign_coords(
        swapped_scene=("swapped_scene", np.array(names, dtype=object), {"units": "1", "long_name": "dry scene"}),
        direction=(
            "direction",
            np.array(
                [f"{starts[-1]} state, {starts[0]} memory", f"{starts[0]} state, {starts[-1]} memory"][:2], dtype=object
            ),
            {"units": "1", "long_name": "whose state, whose latched velocities"},
        ),
    )
    ds.attrs["title"] = f"clearance model sensitivity: variant {variant}, elastic law {law}, contact memory swapped"
    return ds


def law_judgement(nominal: Any, sensitivity: Any, ratio: float, confidence: float, start: int = 0) -> dict[str, Any]:
    """The claims of one variant under the other elastic law from start ``start`` (``sensitivity``:
    ``model_sensitivity``'s result), the nominal numerical errors kept: ``studies.judge``'s verdict."""
    verdict, _ = sample_judgement(
        nominal, sensitivity.isel(start=start, sample=0, variant=0), ratio, confidence, start=start
    )
    return verdict



def memory_free(cfg: Mapping[str, Any], variant: str, velocities: Sequence[float], nominal: Sequence[Any] = ()):
    """Rule study: each compared scene with contact continued from every start's nominal state under a memory-free
    damping, once per fixed impact velocity (m/s) in ``velocities``: the damping divides by that velocity at every
    impact instead of the one latched at the last impact, so the starts can no longer differ by it.  Each run settles
    by the scenes' rule and carries its own numerical error bar (the check reruns; a different state from the nominal
    one has its own).  A scene whose nominal runs never touched is the nominal run (the velocity enters only in
    contact)."""
    import xarray as xr

    from .adapter import COMPARED
    from .studies import MEASURES, QUANTITIES, scene
    from .uncertainty import SAMPLE_STATISTICS, apply

    runs = {str(r.attrs["scene"]): r for r in nominal}
    starts = [str(x) for x in next(iter(runs.values())).start.values]
    shape = (len(velocities), len(starts), len(COMPARED))
    stats = np.full((*shape, len(MEASURES), len(QUANTITIES), len(SAMPLE_STATISTICS)), np.nan)
    error = np.full((*shape, len(MEASURES), len(QUANTITIES)), np.nan)
    status = np.full(shape, "", dtype=object)
    for i, v in enumerate(velocities):
        local = apply(cfg, {"joints.fixed_impact_velocity_m_s": float(v)})
        for k in range(len(starts)):
            for m, name in enumerate(COMPARED):
                if name not in runs:
                    continue
                base = runs[name]
                if base.attrs["evaluations_contact"] == 0:
                    run, at = base, k
                else:
                    run, at = scene(
                        local, variant, name, first_start_only=True, check=True, memory=base.window_memory.values[k]
                    ), 0
                stats[i, k, m] = np.stack([run[x].values[at] for x in SAMPLE_STATISTICS], axis=-1)
                error[i, k, m] = run.numerical_error.values[at]
                status[i, k, m] = str(run.state_status.values[at])
                print(
                    f"memory-free {variant} {name} at {v:g} m/s from start {starts[k]}: {status[i, k, m]}", flush=True
                )
    dims = ("fixed_impact_velocity", "start", "scene")
    return xr.Dataset(
        {
            "judged": (
                (*dims, "measure", "quantity", "statistic"), stats,
                {
                    "units": "SI of the quantity", "long_name": "the claims' measure on the state and its interval",
                    "nan_meaning": "as the scene run stores it: no interval or degrees of freedom where there is none",
                },
            ),
            "numerical_error": (
                (*dims, "measure", "quantity"), error,
                {
                    "units": "SI of the quantity", "long_name": "the state's own numerical error bar (check reruns)",
                    "nan_meaning": "every check rerun failed",
                },
            ),
            "state_status": (dims, status.astype(str), {"units": "1", "long_name": "how the state was found"}),
        },
        coords={
            "fixed_impact_velocity": (
                "fixed_impact_velocity", np.asarray(velocities, dtype=float),
                {"units": "m s-1", "long_name": "the impact velocity the memory-free damping divides by"},
            ),
            "start": ("start", np.array(starts, dtype=object), {"units": "1", "long_name": "the start continued"}),
            "scene": ("scene", np.array(COMPARED, dtype=object), {"units": "1", "long_name": "scene"}),
            "measure": ("measure", np.array(MEASURES, dtype=object), {"units": "1", "long_name": "deviation measure"}),
            "quantity": (
                "quantity", np.array(QUANTITIES, dtype=object), {"units": "1", "long_name": "compared response"},
            ),
            "statistic": (
                "statistic", np.array(SAMPLE_STATISTICS, dtype=object), {"units": "1", "long_name": "statistic"},
            ),
        },
        attrs={"title": f"clearance model sensitivity: variant {variant}, memory-free contact damping",
               "variant": variant},
    )
