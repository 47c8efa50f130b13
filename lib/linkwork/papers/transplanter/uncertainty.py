"""Input uncertainty of the transplanter paper: the material, gravity on the elastic model and [x_S1].

Young's modulus and the density of 5A06 within their data-sheet ranges, gravity off or on (a named choice, never
a sampled number), the unprinted
reference diameter [x_S1] around the initial 8 mm, which solution the paper's numbers are (quasi-static or
time-integrated) and the Rayleigh damping of the latter.  Each sample evaluates our model at the published
optimum and our own optimum; the latter by SLSQP on SY + SZ with explicit constraints, which agrees with the
paper's SUMT to 0.001 mm at the nominal inputs (optim.nc) and costs 40 times fewer evaluations.  Each
sample's SLSQP starts from the nominal SLSQP optimum in optim.nc (a perturbation of it), not from the initial
diameters: the same optimum (tests/test_uncertainty.py) in about half the evaluations.  Each sample also measures
the claims in words at the published optimum (claims.claim_measures), so that their verdicts see the assumptions.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from ...pipeline.search import searcher
from ...pipeline.uncertainty import Input, gathered, labelled_inputs, run_batch

PROPAGATED = (
    "youngs_modulus_Pa", "density_kg_m3", "gravity_m_s2", "reference_diameter_m", "compared_solution", "damping_ratio",
)


def inputs(cfg: Mapping[str, Any]) -> list[Input]:
    """The material of the selected name, gravity and [x_S1], with their ranges."""
    found = list(labelled_inputs(cfg))
    return [i for i in found if i.path.split(".")[-2] in PROPAGATED]


def results(
    cfg: Mapping[str, Any], published: Mapping[str, Any], start_m: Sequence[float], optimise: bool = True
) -> list[Any]:
    """Our optimum (SLSQP from the diameters ``start_m``, m; NaN without ``optimise``), our model at the published
    optimum and the claims' measures there (claims.claim_measures), at one sample."""
    import numpy as np
    import xarray as xr

    from ...engines.optimize import slsqp
    from .adapter import compared_solution
    from .claims import RESPONSES, claim_measures, response_values
    from .model import MEMBERS
    from .published_point import claim_variables
    from .studies import SUMMARY_ATTRS, optimise_on_report_grid, report_grid, solve, summary

    run = lambda prob, x: slsqp(prob, x, cfg["optimization"]["slsqp_ftol"])  # noqa: E731
    x = (
        optimise_on_report_grid(cfg, np.array(start_m, dtype=float), run, run)[0]
        if optimise
        else np.full(len(MEMBERS), np.nan)
    )
    published_m = np.array(published["optimum_diameters_mm"], dtype=float) / 1e3
    solved = solve(cfg, published_m, compared_solution(cfg), report_grid(cfg))
    at = summary(solved)
    data = {"d_opt": ("member", x * 1e3, {"units": "mm", "long_name": "optimal diameters (SLSQP)"})}
    data.update({k: ("case", [at[k]], {"units": u, "long_name": n}) for k, (u, n) in SUMMARY_ATTRS.items()})
    measures = claim_measures(cfg, published_m, compared_solution(cfg), response_values(solved), every_member=False)
    data.update(claim_variables(measures))  # the compared claims' measures (the governing members' elasticity)
    coords = {
        "member": ("member", np.array(MEMBERS, dtype=object)),
        "case": ("case", np.array(["baseline"], dtype=object)),
        "response": ("response", np.array(RESPONSES, dtype=object)),
    }
    return [xr.Dataset(data, coords=coords)]


def batch(cfg: Mapping[str, Any], published: Mapping[str, Any], index: int, optim: Any):
    """Rule study: one batch of samples, each optimised from the nominal SLSQP optimum (``optim.d_slsqp``, mm)."""
    start = optim.d_slsqp.values * 1e-3  # mm -> m
    return run_batch(cfg, published, index, inputs(cfg), lambda c: results(c, published, start))


#: The inputs the searched values (every one at the published optimum) do not read: [x_S1] enters only the optimiser
#: (our optimum, which the searches do not evaluate), and the damping ratio only the dynamic solution.
NOT_AT_THE_PUBLISHED_POINT = "optimization.reference_diameter_m.value"
DYNAMIC_ONLY = "fe.damping_ratio.value"


def held(scenario: Any) -> set[str]:
    """The inputs the bounded searches hold at their nominal values in ``scenario`` (they do not move its values:
    tests/test_transplanter.py checks this declaration against the model)."""
    out = {NOT_AT_THE_PUBLISHED_POINT}
    if scenario.values.get("fe.compared_solution.value") == "quasi-static":
        out.add(DYNAMIC_ONLY)
    return out


def gather(cfg: Mapping[str, Any], batches: Sequence[Any], published: Mapping[str, Any], optim: Any, workers: int = 1):
    """Rule study: every batch, with each headline value's extremes over the box per scenario and the consistent sets
    (bounded searches).  The searches evaluate the headline values only, all of them at the published optimum: the
    optimal diameters are not reproducible (no measure), so a search evaluation runs no optimiser."""
    ins, start = inputs(cfg), optim.d_slsqp.values * 1e-3
    search = searcher(cfg, published, ins, lambda c: results(c, published, start, optimise=False), held)
    return gathered(ins, batches, "Transplanter: material, gravity and [x_S1], propagated", search, workers)
