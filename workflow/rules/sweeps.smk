# Parameter sweeps that fan out: the grid's points in jobs of `points_per_job`, gathered into one netCDF with the
# facts that interpret it (trends, threshold crossings, colour ranges).
from linkwork.pipeline.sweeps import batches as sweep_batches, grid as sweep_grid

SWEEPS = [s for s in config["sweeps"] if s != "grid"]
# What a sweep's gather reads besides its points: the published file where the map's threshold is a claim's.
SWEEP_GATHER_INPUTS = {"heald": {"published": "config/published/heald.yaml"}}
# ... and the paper's values it reads itself (the heald gather shows that the warp branch cannot change Q_E, Q_F in model B).
SWEEP_GATHER_CFG = {"heald": lambda: {"paper": sweep_cfg("heald")}}


def sweep_axes(name):
    return config["sweeps"][name][config["sweeps"]["grid"]]


def sweep_jobs(name):
    """The grid's points, split into the sweep's jobs."""
    return sweep_batches(sweep_grid(sweep_axes(name)), config["sweeps"][name]["points_per_job"])


def sweep_cfg(name):
    """The paper's config values a point of this sweep reads (the swept values themselves come as the point)."""
    spec = config["sweeps"][name]
    if name == "clearance":
        scene = config["clearance"]["scenes"][spec["scene"]]
        keys = clearance_adapter.model_keys(config["clearance"], spec["variant"], spec["scene"])
        keys = [k for k in keys if k != "crank_speed_rad_s" and (k != "joints.journal_radius_m" or "lubrication" in scene["effects"])]
        return section("clearance", *keys, "numerics.points_per_cycle", f"integrators.{clearance_adapter.integrator_kind(scene)}", "states", "statistics", "claims.ripple_cutoff_hz")
    if name == "heald":
        swept = ("clearance_E", "clearance_F", "reaction_E")
        return section("heald", *(f"parameters.{p}" for p in config["heald"]["parameters"] if p not in swept), "excitation", "speeds")
    raise ValueError(f"no sweep named {name!r}")


def sweep_reference(name):
    """The grid point the paragraph and the colour scale refer to: the paper's configured (nominal) values."""
    if name == "clearance":
        joints = config["clearance"]["joints"]
        return {"clearance_m": joints["bearing_radius_m"] - joints["journal_radius_m"], "crank_speed_rad_s": config["clearance"]["crank_speed_rad_s"]}
    if name == "heald":
        p = config["heald"]["parameters"]
        return {"clearance_m": p["clearance_E"]["value"], "reaction_ratio_EF": p["reaction_E"]["value"] / p["reaction_F"]["value"]}
    raise ValueError(f"no sweep named {name!r}")


def sweep_spec(name):
    """What a sweep holds fixed (scene, variant, model, cycles): everything but its grids and job size."""
    return {k: v for k, v in config["sweeps"][name].items() if k not in ("small", "large", "points_per_job")}


def sweep_gather_inputs(wildcards):
    name = wildcards.sweep
    return {"points": expand("results/sweeps/{sweep}/job_{index}.nc", sweep=name, index=range(len(sweep_jobs(name)))),
            "code": code(f"linkwork.papers.{name}.sweep"), **SWEEP_GATHER_INPUTS.get(name, {})}


def sweep_args(wildcards):
    return {"points": sweep_jobs(wildcards.sweep)[int(wildcards.index)], "spec": sweep_spec(wildcards.sweep)}


rule sweep_point:
    priority: LONG_JOB_PRIORITY
    input:
        code=lambda wildcards: code(f"linkwork.papers.{wildcards.sweep}.sweep"),
    output:
        "results/sweeps/{sweep}/job_{index}.nc",
    wildcard_constraints:
        sweep="|".join(SWEEPS),
        index=r"\d+",
    params:
        study=lambda wildcards: f"linkwork.papers.{wildcards.sweep}.sweep:sweep",
        cfg=lambda wildcards: sweep_cfg(wildcards.sweep),
        args=sweep_args,
    script:
        STUDY


rule sweep_gather:
    priority: GATE_PRIORITY
    input:
        unpack(sweep_gather_inputs),
    output:
        "results/sweeps/{sweep}.nc",
    wildcard_constraints:
        sweep="|".join(SWEEPS),
    params:
        study=lambda wildcards: f"linkwork.papers.{wildcards.sweep}.sweep:gathered",
        cfg=lambda wildcards: {"grid": config["sweeps"]["grid"], "axes": sweep_axes(wildcards.sweep), "spec": sweep_spec(wildcards.sweep),
                               "reference": sweep_reference(wildcards.sweep), **SWEEP_GATHER_CFG.get(wildcards.sweep, lambda: {})()},
    script:
        STUDY
