"""Input uncertainty of the beat-up paper: the rounding of its printed parameters.

The six-bar's l4, l7, theta4 and theta7 are printed to 0.01 (mm, deg); each moves within half a unit of
that digit (``printed_rounding``).  The assumed 1511M four-bar only enters the weft-window numbers, which
the paper does not give enough to reproduce, so it is not propagated.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from ...pipeline.search import searcher
from ...pipeline.uncertainty import Input, gathered, run_batch


def inputs(cfg: Mapping[str, Any]) -> list[Input]:
    """Each printed parameter within half a unit of its last printed digit."""
    return [
        Input(
            f"sixbar.{key}", float(cfg["sixbar"][key]), float(cfg["sixbar"][key]) - half,
            float(cfg["sixbar"][key]) + half, "printed to the last digit given; half a unit either side",
            kind="rounding",
        )
        for key, half in cfg["printed_rounding"].items()
    ]


def results(cfg: Mapping[str, Any]) -> list[Any]:
    """The six-bar motion and headline numbers at one sample."""
    from .studies import motion

    return [motion(cfg)[0]]


def batch(cfg: Mapping[str, Any], published: Mapping[str, Any], index: int):
    """Rule study: one batch of samples of the rounding study."""
    return run_batch(cfg, published, index, inputs(cfg), results)


def gather(cfg: Mapping[str, Any], batches: Sequence[Any], published: Mapping[str, Any], workers: int = 1):
    """Rule study: every batch, with each headline value's extremes over the rounding box (bounded searches)."""
    ins = inputs(cfg)
    return gathered(
        ins, batches, "Beat-up: rounding of the printed parameters, propagated", searcher(cfg, published, ins, results),
        workers,
    )
