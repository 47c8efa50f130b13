"""The transplanter paper's claims in words, each given a measure.

* Purpose and result: the optimum is a "minimum-mass design" whose members' mass "is reduced substantially"
  (Sec. 2 and the results' comment): the mass of the four solid round bars, rho pi/4 sum(l d^2), at the
  published optimum over that at the initial 8 mm diameters.
* "When the members' mass is reduced substantially, the arm works with a large distortion" (results' comment):
  the largest elastic tip displacement at the published optimum over that at the initial diameters.
* Conclusion: "the sections of the planting arm and of the coupler are the important factors of the members'
  largest dynamic stress and of the arm tip's elastic deformation": the elasticity d ln y / d ln d_i of the
  peak stress and of the largest tip displacement to each member's diameter at the published optimum, by
  central finite differences; "an important factor" is read (in the published numbers' file) as a 1 % change of its
  diameter moving the response by at least a set fraction of 1 %, for the arm and the coupler alike
  (``governing_elasticity``: the smaller of their two |elasticities|).
SI units inside (kg, m, Pa); the compared solution (quasi-static or dynamic) is the config's.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from typing import Any

import numpy as np

from .adapter import member_lengths
from .adapter import material as material_of
from .model import MEMBERS, bar_mass
from .studies import report_grid, solve

RESPONSES = ("peak stress", "largest tip displacement")
#: The members the conclusion names: their diameters are "the important factors" (``governing_elasticity``).
GOVERNING = ("arm", "coupler")


def elasticities(
    response: Callable[[np.ndarray], np.ndarray], x, rel_step: float, inputs: Sequence[int] | None = None
) -> np.ndarray:
    """d ln y_j / d ln x_i (responses j x inputs i) by central differences in ln x with the step ``rel_step``;
    ``inputs``: the indices i differentiated, in this order (default: every one), two evaluations each."""
    x = np.asarray(x, dtype=float)
    out = []
    for i in range(x.size) if inputs is None else inputs:
        up, down = x.copy(), x.copy()
        up[i] *= np.exp(rel_step)
        down[i] *= np.exp(-rel_step)
        out.append((np.log(response(up)) - np.log(response(down))) / (2.0 * rel_step))
    return np.array(out).T


def governing_elasticity(e: np.ndarray, governing=GOVERNING, members=MEMBERS) -> np.ndarray:
    """Per response (rows of ``e``, whose columns are ``members``), the smallest |elasticity| among the ``governing``
    members: each of them moves the response by at least this many per cent per per cent of its diameter."""
    inside = [list(members).index(m) for m in governing]
    return np.abs(np.atleast_2d(e))[:, inside].min(axis=1)


def response_values(r) -> np.ndarray:
    """Peak eq. (8) stress (Pa) and largest elastic tip displacement (m) of one solution ``r`` (a KedResult)."""
    return np.array([r.stress.max(), np.hypot(r.tip[:, 0], r.tip[:, 1]).max()])


def responses(cfg: Mapping[str, Any], diameters, solution: str) -> np.ndarray:
    """Peak eq. (8) stress (Pa) and largest elastic tip displacement (m) over the report grid."""
    return response_values(solve(cfg, np.asarray(diameters, dtype=float), solution, report_grid(cfg)))


def claim_measures(
    cfg: Mapping[str, Any], published_m, solution: str, at_published=None, every_member: bool = True
) -> dict[str, Any]:
    """The claims' measures at the published optimum ``published_m`` (m) against the initial diameters, in the
    ``solution``: masses (kg), distortions (m), their ratios, the elasticities (response, member) and the
    governing members' smallest |elasticity| per response.  ``at_published``: the responses there
    (``response_values``) where the caller has solved that point already.  Without ``every_member`` only the
    governing members are differentiated (what the compared measure reads: four solves instead of eight) and the
    elasticity matrix is left out."""
    initial = np.array(cfg["initial_diameters_m"], dtype=float)
    published = np.asarray(published_m, dtype=float)
    lengths, density = member_lengths(cfg), material_of(cfg).density
    at_published = (
        responses(cfg, published, solution) if at_published is None else np.asarray(at_published, dtype=float)
    )
    at_initial = responses(cfg, initial, solution)
    members = MEMBERS if every_member else GOVERNING
    e = elasticities(
        lambda d: responses(cfg, d, solution), published, float(cfg["claims"]["elasticity_step"]),
        [MEMBERS.index(m) for m in members],
    )
    out = {
        "mass_initial": bar_mass(lengths, initial, density),
        "mass_published": bar_mass(lengths, published, density),
        "mass_ratio": bar_mass(lengths, published, density) / bar_mass(lengths, initial, density),
        "distortion_initial": float(at_initial[1]),
        "distortion_published": float(at_published[1]),
        "distortion_ratio": float(at_published[1] / at_initial[1]),
        "stress_initial": float(at_initial[0]),
        "governing_elasticity": governing_elasticity(e, GOVERNING, members),
    }
    return {**out, "elasticity": e} if every_member else out
