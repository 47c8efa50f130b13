"""Benchmark of what one crank turn of each clearance scene costs at the pipeline's integrator: the unit the settling
rule, the check reruns, the input samples and the sweep all pay in.

Run: python benchmarks/clearance_turns.py [--warm-turns 20] [--timed-turns 5]

Method: per variant and scene with clearance joints, a run at the pipeline's integrator (clearance.integrators)
from the centred start is continued --warm-turns turns (compilation and most of the transient), then --timed-turns
turns are timed one by one (time.perf_counter; the median per turn) sampled at numerics.points_per_cycle, and the
same number again sampled at 720 points a turn (what the peaks' sampling costs; the steps do not depend on the
outputs).  Dry scenes: also Dormand-Prince 5(4) at the same tolerance, whose steps land on every output (the
integrator the pipeline used before).  Accepted and rejected steps per turn are counted over the timed turns.
Figures go to benchmarks/measured/clearance_turns.json.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

import numpy as np
import yaml

PROJECT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(PROJECT / "lib"))
from linkwork.engines.multibody.simulate import Run  # noqa: E402
from linkwork.papers.clearance.fourbar import run as scene_run  # noqa: E402
from linkwork.papers.clearance.adapter import integrator_kind, parameters, scene_effects  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _project import write_figures  # noqa: E402

COARSE = 720


def timed_turns(run: Run, period: float, per: int, turns: int) -> dict[str, float]:
    """Continue ``run`` by ``turns`` turns sampled at ``per`` points each: median seconds a turn, steps a turn."""
    seconds, steps, rejected = [], run.steps, run.rejected
    for _ in range(turns):
        t = run.t + np.arange(per + 1) * period / per
        t0 = time.perf_counter()
        run.advance(t)
        seconds.append(time.perf_counter() - t0)
    return {
        "s_per_turn": statistics.median(seconds),
        "steps_per_turn": (run.steps - steps) / turns,
        "rejected_per_turn": (run.rejected - rejected) / turns,
    }


def scene_figures(section, variant: str, scene: str, warm: int, turns: int) -> dict[str, object]:
    p = parameters(section, variant, scene)
    joints, effects = scene_effects(section, scene)
    integ = section["integrators"][integrator_kind(section["scenes"][scene])]
    per = section["numerics"]["points_per_cycle"]
    period = 2 * np.pi / p.crank_speed
    out: dict[str, object] = {"integrator": f"{integ['method']} rtol={integ['rtol']:g}"}
    run = scene_run(p, joints, effects, integ)
    timed_turns(run, period, per, warm)
    out["pipeline"] = timed_turns(run, period, per, turns)
    out["coarse"] = timed_turns(run, period, COARSE, turns)
    if integ["method"] == "dop853":
        before = scene_run(p, joints, effects, {**integ, "method": "dopri5"})
        timed_turns(before, period, per, warm)
        out["dopri5"] = timed_turns(before, period, per, turns)
    return out


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--warm-turns", type=int, default=20)
    parser.add_argument("--timed-turns", type=int, default=5)
    args = parser.parse_args()
    section = yaml.safe_load((PROJECT / "config" / "config.yaml").read_text())["clearance"]
    scenes = {}
    for variant in section["variants"]:
        for scene, spec in section["scenes"].items():
            if not spec["clearance_joints"]:
                continue
            f = scene_figures(section, variant, scene, args.warm_turns, args.timed_turns)
            scenes[f"{variant}/{scene}"] = f
            line = (
                f"{variant}/{scene} ({f['integrator']}): {1e3 * f['pipeline']['s_per_turn']:.0f} ms a turn at"
                f" {section['numerics']['points_per_cycle']} points, {1e3 * f['coarse']['s_per_turn']:.0f} ms at"
                f" {COARSE}"
            )
            if "dopri5" in f:
                line += f"; dopri5 at the same rtol {1e3 * f['dopri5']['s_per_turn']:.0f} ms"
            print(line, flush=True)
    write_figures(
        "clearance_turns",
        {
            "points_per_cycle": section["numerics"]["points_per_cycle"],
            "coarse_points": COARSE,
            "warm_turns": args.warm_turns,
            "timed_turns": args.timed_turns,
            "scenes": scenes,
        },
        __doc__.split("Method:", 1)[1].split("Figures go")[0],
    )


if __name__ == "__main__":
    main()
