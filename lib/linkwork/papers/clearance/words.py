"""The clearance paper's code names in words, for everything a reader sees (answer, reports, tables, legends).

The one home of this mapping: the findings and the reports import it.  Kept apart from ``studies`` (where the
scenes are simulated) so that a change of wording reruns only the comparison and the reports, never a scene."""

from __future__ import annotations

import math
import re

JOINT_WORDS = {"1": "joint 1", "2": "joint 2", "both": "both joints"}
KIND_WORDS = {"dry": "dry clearance", "lubricated": "lubricated clearance"}
#: Scene code -> words ('dry_2' -> 'dry clearance at joint 2').
SCENE_WORDS = {"ideal": "ideal joints", **{f"{kind}_{joint}": f"{kw} at {jw}"
                                          for kind, kw in KIND_WORDS.items() for joint, jw in JOINT_WORDS.items()}}
#: Claim id -> words (the paper's three claims, in its order).
CLAIM_WORDS = {"acceleration_order": "claim 1 (rocker-acceleration order)",
               "torque_order": "claim 2 (crank-torque order)",
               "lubrication_close": "claim 3 (lubrication close to the ideal)"}
#: Deviation measure -> its short name in words (titles, labels).
MEASURE_WORDS = {"rms": "RMS", "peak": "peak", "ripple": "ripple"}
#: Compared response -> words.
QUANTITY_WORDS = {"rocker_acceleration": "rocker acceleration", "crank_torque": "crank torque"}
#: Symbols of the interval's description -> words.
SYMBOL_WORDS = {"n_b": "N", "s_b": "S"}
#: Integrator and contact-law names -> words.
METHOD_WORDS = {
    "dopri5": "Dormand–Prince 5(4)",
    "ndf": "variable-order BDF (compiled)",
    "bdf": "BDF (scipy)",
    "radau": "Radau IIA (scipy)",
    "rk4": "RK4",
    "pereira": "Pereira et al.",
    "hertz-sphere": "sphere law (eq. 9)",
}
WORDS = {**SCENE_WORDS, **CLAIM_WORDS, **QUANTITY_WORDS, **SYMBOL_WORDS, **METHOD_WORDS}
_NAMES = sorted((re.escape(k) for k in WORDS if "_" in k or k in METHOD_WORDS), key=len, reverse=True)
_CODE = re.compile(r"(?<![\w])(" + "|".join(_NAMES) + r")(?![\w])")


def in_words(text: str) -> str:
    """``text`` with every code name of this paper replaced by its words."""
    return _CODE.sub(lambda m: WORDS[m.group(1)], str(text))


#: The two parameter variants (sets of link inertias), as a clause of prose.
VARIANT_WORDS = {
    "slender": "with slender-rod inertias (our defensible reading)",
    "decoded": "with the inertias as decoded from the text",
}


def sample_in_words(label: str) -> str:
    """An uncertainty sample's label in words: 'joint length (low end)' for 'assumed.joint_length_m.value low'; another
    start's 'start off-centre | nominal' as 'nominal (start off-centre)'."""
    if " | " in label:
        scenario, rest = label.split(" | ", 1)
        return f"{sample_in_words(rest)} ({scenario})"
    key, _, end = label.rpartition(" ")
    if end not in ("low", "high"):
        return label
    name = key.removeprefix("assumed.").removesuffix(".value")
    for unit in ("_m_s", "_m", "_Pa_s", "_Pa"):
        name = name.removesuffix(unit)
    return f"{name.replace('_', ' ')} ({end} end)"


def at_most(x: float, digits: int = 2) -> str:
    """``x`` rounded up to ``digits`` significant digits: a bound that stays true when printed ('at most ...')."""
    if not math.isfinite(x) or x == 0.0:
        return f"{x:g}"
    scale = 10.0 ** (math.floor(math.log10(abs(x))) - digits + 1)
    return f"{math.ceil(x / scale - 1e-9) * scale:.{digits}g}"


def ripple_bounds(findings, variants) -> str:
    """The clause bounding the lubricated scenes' ripples and whole deviations by the ideal rocker acceleration's RMS,
    per variant (``findings``: the comparison's findings; ``ripple_over_ideal``, ``lubricated_deviation_over_ideal``),
    each bound rounded up."""
    ripple = " and ".join(f"{at_most(float(findings.ripple_over_ideal.sel(variant=v)))} ({v})" for v in variants)
    whole = " and ".join(at_most(float(findings.lubricated_deviation_over_ideal.sel(variant=v))) for v in variants)
    return (
        f"the ripples (means over the judged windows) are at most {ripple} of the ideal rocker acceleration's RMS, and"
        f" the whole lubricated deviation at most {whole} of it"
    )
