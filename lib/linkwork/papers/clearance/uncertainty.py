"""Input uncertainty of the clearance paper: the assumed joint length, friction thresholds and film cap.

Each input is moved alone to both ends of its range; a sample reruns only the scenes whose effects read
that input (both parameter variants, the pipeline's tolerance) and judges the claims again with the
nominal runs of every other scene.  The joint length and the film cap e0 enter the lubricated scenes,
the friction thresholds v0 and v1 the dry ones.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from ...pipeline.uncertainty import Input, gathered, labelled_inputs, run_batch


def inputs(cfg: Mapping[str, Any]) -> list[Input]:
    """The assumed inputs of the clearance section (``assumed``) with their ranges."""
    return list(labelled_inputs(cfg["assumed"], "assumed."))


def _affected(cfg: Mapping[str, Any], variant: str, scene: str, moved: set[str]) -> bool:
    from .adapter import model_keys

    keys = model_keys(cfg, variant, scene)
    return any(path.rsplit(".value", 1)[0] in keys for path in moved)


def results(cfg: Mapping[str, Any], nominal: Mapping[str, Any], scenes: Sequence[Any], tight: Sequence[Any]) -> list[Any]:
    """The claims at one sample: the scenes that read a moved input are run again, the others are the nominal runs."""
    from .studies import claims, scene

    moved = {path for path in (p for p, _ in _differences(nominal, cfg))}
    runs = []
    for run in scenes:
        variant, name = run.attrs["variant"], run.attrs["scene"]
        runs.append(scene(cfg, variant, name, "pipeline") if moved and _affected(cfg, variant, name, moved) else run)
    return [claims(cfg, runs, tight)]


def _differences(a: Mapping[str, Any], b: Mapping[str, Any], prefix: str = ""):
    for key, value in b.items():
        path = f"{prefix}{key}"
        if isinstance(value, Mapping):
            yield from _differences(a.get(key, {}), value, path + ".")
        elif a.get(key) != value:
            yield path, value


def batch(cfg: Mapping[str, Any], published: Mapping[str, Any], index: int, scenes: Sequence[Any], tight: Sequence[Any]):
    """Rule study: one sample (the nominal runs are inputs; the affected scenes are run again)."""
    return run_batch(cfg, published, index, inputs(cfg), lambda c: results(c, cfg, scenes, tight))


def gather(cfg: Mapping[str, Any], batches: Sequence[Any]):
    """Rule study: every sample, with the ranges."""
    return gathered(inputs(cfg), batches, "Clearance: assumed joint length, friction thresholds and film cap, propagated")
