"""Config adapter of the beat-up paper: the six-bar and the parametric four-bar from config (lengths in m,
angles in degrees converted here)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from ...configformat import labelled
from .model import FourBarBeatup, SixBar


def six_bar(sixbar: Mapping[str, Any], crank_m: float | None = None) -> SixBar:
    """SixBar from a ``sixbar`` section (l1_m..l7_m, theta4_deg, theta7_deg, branches); optionally another crank (m)."""
    crank = float(sixbar["l1_m"]) if crank_m is None else float(crank_m)
    lengths = [crank] + [float(sixbar[f"l{i}_m"]) for i in range(2, 8)]
    return SixBar(
        *lengths,
        theta4=float(np.radians(sixbar["theta4_deg"])),
        theta7=float(np.radians(sixbar["theta7_deg"])),
        branch_rocker=int(sixbar["branch_rocker"]),
        branch_sley=int(sixbar["branch_sley"]),
    )


def four_bar_beatup(fourbar: Mapping[str, Any], arm_to_crank: float | None = None) -> FourBarBeatup:
    """FourBarBeatup from a ``fourbar`` section of labelled entries; optionally another L/R."""
    ratio = labelled(fourbar["arm_to_crank"]) if arm_to_crank is None else float(arm_to_crank)
    crank = labelled(fourbar["crank_m"])
    return FourBarBeatup(
        crank=crank, arm=ratio * crank, sword_radius=labelled(fourbar["sword_radius_m"]),
        offset=labelled(fourbar["offset_m"]),
    )


def rounding_half_units(printed_rounding: Mapping[str, float]) -> dict[str, float]:
    """Half a unit of each printed parameter's last digit in SI (m or rad), keyed by SixBar field."""
    return {
        key.rsplit("_", 1)[0]: float(np.radians(v)) if key.endswith("_deg") else float(v)
        for key, v in printed_rounding.items()
    }


def crank_sense(sixbar: Mapping[str, Any]) -> str:
    """The crank sense of the scenario (``sixbar.crank_sense``, a labelled choice): 'decreasing' or 'increasing'
    theta1."""
    from .model import CRANK_SENSES

    value = str(sixbar["crank_sense"]["value"])
    if value not in CRANK_SENSES:
        raise ValueError(f"crank sense must be one of {sorted(CRANK_SENSES)}, got {value!r}")
    return value


def sense_labels(sixbar: Mapping[str, Any]) -> dict[str, str]:
    """Readable name of each crank sense (the entry's choice_labels), keyed by choice."""
    entry = sixbar["crank_sense"]
    return dict(zip(entry["choices"], entry.get("choice_labels", entry["choices"]), strict=True))
