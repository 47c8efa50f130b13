"""Benchmark of the clearance engine against a pure-Python right-hand side in scipy's solve_ivp.

Run: python benchmarks/clearance.py [--scene dry_both] [--variant slender]

Method: one dry two-joint scene, settling plus two recorded cycles.  Ours: the compiled right-hand
side and Dormand-Prince 5(4) at the benchmark's own setting (rtol 1e-6, atol 1e-9, the pipeline's first and
largest step; the pipeline itself runs DOP853 at rtol 1e-9, benchmarks/clearance_turns.py), so that the baseline
finishes in a minute.  Baseline: the *same* generated source and
kernels executed as plain Python (numba's decorator replaced by the identity), integrated by
scipy's RK45 solver class (what solve_ivp runs: the same Dormand-Prince 5(4) pair), stepped so that the impact
velocity can be latched.  Wall clock,
time.perf_counter; ours is the median of 5 runs after a warm-up (compilation excluded), the
baseline one run.  Also reported: the time of every scene of the pipeline and the peak memory (RSS)
of this process.  Figures go to benchmarks/measured/clearance.json.
"""

from __future__ import annotations

import argparse
import resource
import sys
import time
from pathlib import Path

import numpy as np
import yaml

PROJECT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(PROJECT / "lib"))
from linkwork.configformat import pick  # noqa: E402
from linkwork.engines.multibody import kernels  # noqa: E402
from linkwork.engines.multibody.model import compile_scene, generate_source, pack  # noqa: E402
from linkwork.papers.clearance.fourbar import initial_state, integrate, scene  # noqa: E402
from linkwork.papers.clearance.adapter import parameters, scene_keys  # noqa: E402
from linkwork.papers.clearance.studies import output_times  # noqa: E402
from linkwork.papers.clearance.studies import scene as scene_dataset  # noqa: E402
from linkwork.pipeline.timing import median_time  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _project import write_figures  # noqa: E402


def pure_python_rhs(linkage, gravity):
    """The scene's right-hand side with every function executed by the Python interpreter."""
    identity = lambda *a, **k: (lambda f: f)  # noqa: E731
    ns: dict = {"np": np, "njit": identity}
    kernel_src = Path(kernels.__file__).read_text().replace("from numba import njit", "")
    exec(compile(kernel_src, "kernels_py", "exec"), ns)
    scene_src = generate_source(linkage, gravity)
    scene_src = "\n".join(
        line
        for line in scene_src.splitlines()
        if not line.startswith(("from numba", "from linkwork", "    hertz_damping_factor, friction_coefficient, film"))
    )
    exec(compile(scene_src, "scene_py", "exec"), ns)
    return ns["rhs"], ns["N_DIAG"]


def baseline_run(rhs_py, n_diag, joints, y0, params, t, setting):
    """scipy's RK45 (the Dormand-Prince 5(4) pair of solve_ivp) stepped with the same latching as ours."""
    from scipy.integrate import RK45

    latched, counts, diag = np.zeros(len(joints)), np.zeros(4, dtype=np.int64), np.zeros(n_diag)
    was = np.zeros(len(joints), dtype=bool)
    fun = lambda tt, y: rhs_py(tt, y, params, latched, counts, diag)  # noqa: E731
    solver = RK45(
        fun, t[0], y0, t[-1], rtol=setting["rtol"], atol=setting["atol"], max_step=setting["max_step_s"],
        first_step=setting["first_step_s"],
    )
    out = np.empty(t.size)
    out[0] = fun(t[0], y0)[17]
    i = 1
    while solver.status == "running":
        solver.step()
        fun(solver.t, solver.y)
        for k in range(len(joints)):  # latch the impact velocity at accepted steps, as ours does
            now = diag[4 + 6 * k + 1] > 0.0
            if now and not was[k]:
                latched[k] = abs(diag[4 + 6 * k + 2])
            was[k] = now
        if i < t.size and t[i] <= solver.t:
            dense = solver.dense_output()
            while i < t.size and t[i] <= solver.t + 1e-15:
                out[i] = fun(t[i], dense(t[i]))[17]
                i += 1
    return out, solver.nfev


#: The integrator both sides run (the baseline's RK45 is this pair); first and largest step from the pipeline's setting.
BENCH_SETTING = {"method": "dopri5", "rtol": 1e-6, "atol": 1e-9}


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--scene", default="dry_both")
    parser.add_argument("--variant", default="slender")
    args = parser.parse_args()
    section = yaml.safe_load((PROJECT / "config" / "config.yaml").read_text())["clearance"]
    p = parameters(section, args.variant, args.scene)
    spec = section["scenes"][args.scene]
    joints, effects = tuple(spec["clearance_joints"]), tuple(spec["effects"])
    t, _ = output_times(section["numerics"], p)
    early = t <= 0.5 * 2 * np.pi / p.crank_speed  # accuracy is compared before the impact sequences diverge
    setting = {**section["integrators"]["explicit"], **BENCH_SETTING}
    ref = integrate(p, joints, effects, t, {**setting, "rtol": 1e-11, "atol": 1e-14, "first_step_s": 1e-8})[1][early, 0]
    scale = np.abs(ref).max()
    lk, gravity = scene(p, joints, effects)
    compile_scene(lk, gravity)
    ours = integrate(p, joints, effects, t, setting)[1][:, 0]
    ours_err = np.abs(ours[early] - ref).max() / scale
    ours_time = median_time(lambda: integrate(p, joints, effects, t, setting), 5)
    print(
        f"ours (compiled dopri5, rtol={setting['rtol']:g}): {ours_time:.3f} s; error over the first half cycle"
        f" {ours_err:.2e}",
        flush=True,
    )

    rhs_py, n_diag = pure_python_rhs(lk, gravity)
    y0 = initial_state(p, joints)
    params, _ = pack(lk)
    t0 = time.perf_counter()
    base, nfev = baseline_run(rhs_py, n_diag, joints, y0, params, t, setting)
    base_time = time.perf_counter() - t0
    base_err = np.abs(base[early] - ref).max() / scale
    print(
        f"pure Python + scipy RK45 (same rtol, atol, latching): {base_time:.1f} s, {nfev} evaluations; error"
        f" {base_err:.2e}",
        flush=True,
    )
    speedup = base_time / ours_time
    print(f"speed-up at equal accuracy: {speedup:.0f}x (target >= 20x)", flush=True)
    baseline = {"time_s": base_time, "error": base_err, "nfev": int(nfev), "rtol": setting["rtol"]}
    scene_times = {}
    for variant in section["variants"]:
        for name in section["scenes"]:
            t0 = time.perf_counter()
            scene_dataset(pick(section, scene_keys(section, variant, name)), variant, name)
            scene_times[f"{variant}/{name}"] = time.perf_counter() - t0
    worst = max(scene_times.values())
    peak_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(
        f"slowest pipeline scene: {worst:.2f} s (target <= 10 s); peak RSS of this process {peak_mb:.0f} MB (target <="
        " 1 GB)"
    )
    write_figures(
        "clearance",
        {
            "scene": f"{args.variant}/{args.scene}",
            "ours_time_s": ours_time,
            "ours_error": ours_err,
            "baseline": baseline,
            "speedup": speedup,
            "scene_times_s": scene_times,
            "peak_rss_mb": peak_mb,
            "targets": {"speedup": 20, "slowest_scene_s": 10, "peak_rss_mb": 1024},
        },
        __doc__.split("Method:", 1)[1].split("Figures go")[0],
    )
    if speedup < 20 or worst > 10 or peak_mb > 1024:
        sys.exit("a clearance benchmark missed its target")


if __name__ == "__main__":
    main()
