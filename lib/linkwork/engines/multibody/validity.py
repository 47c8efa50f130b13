"""Where a scene with clearance joints leaves the range of its own models (recorded on the scene: the clearance paper's
scenes and sweeps, a linkage of your own).

Two limits, both dimensionless:

* the dry contact's elastic law has a range (``penetration_limit``): eq. (9)'s sphere law holds while the contact
  arc is short (``elastic_law_validity``, a fraction of the clearance); beyond it its forces are not contact physics;
* the film is capped at the eccentricity ratio 1 - e0/c (the film/dry transition): a scene that spends time beyond
  the cap is carried there by the capped film force, set by the assumed e0, until the dry contact takes over at e = c.

Each elastic law of the dry contact has its own range (``elastic_law_validity``): the sphere law holds while the
contact arc is short enough for its parabolic profiles, the conformal law of Pereira et al. over the radial
clearances for which its coefficients are given.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ...units import DEG_PER_RAD
from .linkage import ELASTIC_LAWS, PEREIRA_CLEARANCE_RANGE_M


def penetration_ratio(penetration: np.ndarray, clearance: float) -> float:
    """Largest penetration (|e| - c, m) over the radial clearance c (m); NaN where no joint has clearance."""
    finite = penetration[np.isfinite(penetration)]
    return float(finite.max() / clearance) if finite.size else float("nan")


def beyond_cap_fraction(eccentricity: np.ndarray, clearance: float, cap: float) -> float:
    """Fraction of the recorded samples at which some joint's |e|/c exceeds the film cap (``eccentricity``: joint x
    time, m)."""
    ratio = np.where(np.isfinite(eccentricity), eccentricity / clearance, 0.0)
    return float(np.mean((ratio > cap).any(axis=0)))


def penetration_limit(law: str, r_journal: float, r_bearing: float) -> float:
    """The deepest penetration over the radial clearance inside the elastic law's range (inf where its source sets
    no bound on the penetration)."""
    limit = elastic_law_validity(law, r_journal, r_bearing).limits["max_penetration_over_clearance"]
    return float(limit) if np.isfinite(limit) else float("inf")


def warnings(penetration_over_c: float, beyond_cap: float | None, limit: float) -> str:
    """The scene's validity warnings as one sentence each ('' when it stays inside both models); ``limit``: the
    elastic law's penetration limit over the clearance."""
    out = []
    if np.isfinite(penetration_over_c) and penetration_over_c > limit:
        out.append(
            f"dry penetration reaches {penetration_over_c:.3g} times the radial clearance (the elastic law's limit:"
            f" {limit:.3g}): outside its contact law"
        )
    if beyond_cap:
        out.append(
            f"eccentricity beyond the film cap during {100 * beyond_cap:.3g} % of the time shown: the film force is"
            " held there at its capped value, set by the assumed e0"
        )
    return "; ".join(out)


def attributes(
    penetration: np.ndarray, eccentricity: np.ndarray, clearance: float, cap: float | None, limit: float
) -> dict[str, object]:
    """The scene attributes: the two measures, the limit they are judged by, and the warnings."""
    pen = penetration_ratio(penetration, clearance)
    beyond = beyond_cap_fraction(eccentricity, clearance, cap) if cap is not None else None
    label, value = contact_extent(pen)
    attrs: dict[str, object] = {"validity_penetration_over_clearance": pen, "validity_penetration_limit": limit,
                                "validity_contact_label": label, "validity_contact_value": value,
                                "validity_warnings": warnings(pen, beyond, limit)}
    if beyond is not None:
        attrs["validity_beyond_film_cap_fraction"] = beyond
    return attrs


def contact_extent(penetration_over_c: float) -> tuple[str, float]:
    """How a joint's deepest (|e| - c)/c reads: ('max penetration / c', value) where the journal entered the
    bushing (>= 0), ('min gap / c', -value) where it never touched (< 0: the smallest gap left)."""
    if np.isfinite(penetration_over_c) and penetration_over_c < 0:
        return "min gap / c", float(-penetration_over_c)
    return "max penetration / c", float(penetration_over_c)


# --- the elastic laws' ranges ---------------------------------------------------------------------------

#: The sphere law (Hertz) takes both profiles as parabolas.  Over a contact half-angle theta the parabola
#: theta^2 / 2 overstates the circle's 1 - cos(theta) by theta^2 / 12 (relative, leading order); the law is taken
#: to hold while that error stays below this tolerance (our criterion, not a published one).
PARABOLIC_PROFILE_TOLERANCE = 0.01


class LawValidity(NamedTuple):
    """An elastic law's range: ``condition`` in words (built from the numbers), ``limits`` in numbers.

    limits: max_half_angle_rad (contact half-angle, rad), max_penetration_m (m), max_penetration_over_clearance (-),
    min_clearance_m, max_clearance_m (radial clearance, m), clearance_in_range (1.0 or 0.0); NaN where the law's
    source sets no such bound.
    """

    condition: str
    limits: dict[str, float]


def contact_half_angle(penetration: float, r_journal: float, r_bearing: float) -> float:
    """Half-angle (rad) of the arc over which the undeformed journal overlaps its bushing, seen from the bushing's
    centre, when the centres are c + ``penetration`` apart (c = r_bearing - r_journal; all lengths m); 0 when the
    journal does not reach the bushing.  From r_journal^2 = r_bearing^2 + e^2 - 2 r_bearing e cos(theta)."""
    c = r_bearing - r_journal
    e = c + max(penetration, 0.0)
    cos_theta = (c * (2.0 * r_bearing - c) + e * e) / (2.0 * r_bearing * e)
    return float(np.arccos(np.clip(cos_theta, -1.0, 1.0)))


def penetration_at_half_angle(half_angle: float, r_journal: float, r_bearing: float) -> float:
    """Penetration (m) at which ``contact_half_angle`` reaches ``half_angle`` (rad, below pi/2): the smaller root of
    e^2 - 2 r_bearing cos(theta) e + c (2 r_bearing - c) = 0, minus c (lengths m)."""
    c = r_bearing - r_journal
    rc = r_bearing * np.cos(half_angle)
    return float(rc - np.sqrt(rc * rc - c * (2.0 * r_bearing - c)) - c)


def parabolic_half_angle_limit(tolerance: float = PARABOLIC_PROFILE_TOLERANCE) -> float:
    """Largest contact half-angle (rad) at which a parabola errs from the circle by ``tolerance`` (relative, -):
    sqrt(12 tolerance), the leading order of theta^2 / 12 = tolerance."""
    return float(np.sqrt(12.0 * tolerance))


def elastic_law_validity(law: str, r_journal: float, r_bearing: float,
                         tolerance: float = PARABOLIC_PROFILE_TOLERANCE) -> LawValidity:
    """The range of the elastic law ``law`` (a key of ELASTIC_LAWS) for a journal of radius r_journal in a bushing of
    radius r_bearing (m).

    hertz-sphere: contact half-angle up to ``parabolic_half_angle_limit(tolerance)``, i.e. a penetration small against
    the clearance; no bound on the clearance.  pereira: radial clearance within PEREIRA_CLEARANCE_RANGE_M (where its
    coefficient Y is given); no bound on the penetration or the load from its source.
    """
    if law not in ELASTIC_LAWS:
        raise ValueError(f"unknown elastic law {law!r}; known: {sorted(ELASTIC_LAWS)}")
    c = r_bearing - r_journal
    nan = float("nan")
    if law == "hertz-sphere":
        theta = parabolic_half_angle_limit(tolerance)
        pen = penetration_at_half_angle(theta, r_journal, r_bearing)
        limits = {"max_half_angle_rad": theta, "max_penetration_m": pen, "max_penetration_over_clearance": pen / c,
                  "min_clearance_m": nan, "max_clearance_m": nan, "clearance_in_range": 1.0}
        condition = (f"contact half-angle below {theta * DEG_PER_RAD:.3g} deg (parabolic profiles within "
                     f"{100 * tolerance:.3g} %): penetration below {pen / c:.3g} times the radial clearance")
        return LawValidity(condition, limits)
    low, high = PEREIRA_CLEARANCE_RANGE_M
    limits = {"max_half_angle_rad": nan, "max_penetration_m": nan, "max_penetration_over_clearance": nan,
              "min_clearance_m": low, "max_clearance_m": high, "clearance_in_range": float(low <= c <= high)}
    condition = f"radial clearance between {low:.3g} and {high:.3g} m (here {c:.3g} m)"
    return LawValidity(condition, limits)
