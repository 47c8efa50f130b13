"""Input uncertainty of the heald paper: every assumed chain parameter within its range.

The paper prints no parameter, so every mass, stiffness, damping, clearance, reaction and lever ratio
is assumed with a range (config).  The drive amplitude is not propagated: the chains are linear, and
every compared quantity (force ratio, growth, resonance) is independent of it.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from ...pipeline.search import searcher
from ...pipeline.uncertainty import Input, gathered, labelled_inputs, run_batch


def inputs(cfg: Mapping[str, Any]) -> list[Input]:
    """The assumed chain parameters with their ranges, and the drive-frequency choice (a scenario)."""
    return [*labelled_inputs(cfg["parameters"], "parameters."), *labelled_inputs(cfg["drive"], "drive.")]


def results(cfg: Mapping[str, Any]) -> list[Any]:
    """The claims' measures of both chain models at one sample (the grid-refinement error bar is the
    nominal run's: the comparison reads it from there)."""
    from .studies import claims

    return [claims(cfg, refinement=False)]


def batch(cfg: Mapping[str, Any], published: Mapping[str, Any], index: int):
    """Rule study: one batch of samples."""
    return run_batch(cfg, published, index, inputs(cfg), results)


def gather(cfg: Mapping[str, Any], batches: Sequence[Any], published: Mapping[str, Any], workers: int = 1):
    """Rule study: every batch, with each headline value's extremes over the box and the consistent sets (bounded
    searches)."""
    ins = inputs(cfg)
    return gathered(
        ins, batches, "Heald: assumed chain parameters, propagated", searcher(cfg, published, ins, results), workers
    )


def model_inputs(cfg: Mapping[str, Any], model: str) -> list[Input]:
    """The inputs that model ``model`` reads (the others do not move its quantities: a test checks it), for the
    per-model input tables: the drive choice and the parameters the model's chain takes."""
    from .model import MODEL_INPUTS

    keep = {f"parameters.{n}.value" for n in MODEL_INPUTS[model]}
    return [i for i in inputs(cfg) if i.path in keep or not i.path.startswith("parameters.")]
