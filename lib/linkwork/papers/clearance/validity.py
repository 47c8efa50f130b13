"""Where a clearance scene leaves the range of its own models (recorded on the scene, shown in the report).

Two limits, both dimensionless:

* the Hertz law of the dry contact (eq. 9) is a small-deformation law; a penetration deeper than
  ``PENETRATION_LIMIT`` times the radial clearance c (here 0.05 mm, so 50 um of steel-on-steel
  indentation) is far outside it, and the forces it gives are no longer contact physics;
* the short-bearing film is capped at the eccentricity ratio 1 - e0/c (the film/dry transition): a scene
  that spends time beyond the cap is carried by the dry contact there, not by the film it names.
"""

from __future__ import annotations

import numpy as np

#: A dry penetration deeper than this fraction of the radial clearance puts the Hertz law far outside its range.
PENETRATION_LIMIT = 1.0


def penetration_ratio(penetration: np.ndarray, clearance: float) -> float:
    """Largest penetration (|e| - c, m) over the radial clearance c (m); NaN where no joint has clearance."""
    finite = penetration[np.isfinite(penetration)]
    return float(finite.max() / clearance) if finite.size else float("nan")


def beyond_cap_fraction(eccentricity: np.ndarray, clearance: float, cap: float) -> float:
    """Fraction of the recorded samples at which some joint's |e|/c exceeds the film cap (``eccentricity``: joint x time, m)."""
    ratio = np.where(np.isfinite(eccentricity), eccentricity / clearance, 0.0)
    return float(np.mean((ratio > cap).any(axis=0)))


def warnings(penetration_over_c: float, beyond_cap: float | None) -> str:
    """The scene's validity warnings as one sentence each ('' when it stays inside both models)."""
    out = []
    if np.isfinite(penetration_over_c) and penetration_over_c > PENETRATION_LIMIT:
        out.append(f"dry penetration reaches {penetration_over_c:.3g} times the radial clearance (limit {PENETRATION_LIMIT:g}): "
                   "outside Hertz contact")
    if beyond_cap:
        out.append(f"eccentricity beyond the film cap during {100 * beyond_cap:.3g} % of the recorded time: the dry contact, "
                   "not the film, carries the journal there")
    return "; ".join(out)


def attributes(penetration: np.ndarray, eccentricity: np.ndarray, clearance: float, cap: float | None) -> dict[str, object]:
    """The scene attributes: the two measures, the limit they are judged by, and the warnings."""
    pen = penetration_ratio(penetration, clearance)
    beyond = beyond_cap_fraction(eccentricity, clearance, cap) if cap is not None else None
    label, value = contact_extent(pen)
    attrs: dict[str, object] = {"validity_penetration_over_clearance": pen, "validity_penetration_limit": PENETRATION_LIMIT,
                                "validity_contact_label": label, "validity_contact_value": value,
                                "validity_warnings": warnings(pen, beyond)}
    if beyond is not None:
        attrs["validity_beyond_film_cap_fraction"] = beyond
    return attrs


def contact_extent(penetration_over_c: float) -> tuple[str, float]:
    """How a joint's deepest (|e| - c)/c reads: ('max penetration / c', value) where the journal entered the
    bushing (>= 0), ('min gap / c', -value) where it never touched (< 0: the smallest gap left)."""
    if np.isfinite(penetration_over_c) and penetration_over_c < 0:
        return "min gap / c", float(-penetration_over_c)
    return "max penetration / c", float(penetration_over_c)
