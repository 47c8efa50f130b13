# Parameter sweeps that fan out: every grid point is an independent job, gathered into one netCDF.
from linkwork.pipeline.sweeps import grid as sweep_grid

SWEEPS = [s for s in config["sweeps"] if s != "grid"]


def sweep_axes(name):
    return config["sweeps"][name][config["sweeps"]["grid"]]


def sweep_cfg(name):
    """The paper's config values a point of this sweep reads (the swept values themselves come as the point)."""
    spec = config["sweeps"][name]
    if name == "clearance":
        scene = config["clearance"]["scenes"][spec["scene"]]
        keys = clearance_adapter.model_keys(config["clearance"], spec["variant"], spec["scene"])
        keys = [k for k in keys if k != "crank_speed_rad_s" and (k != "joints.journal_radius_m" or "lubrication" in scene["effects"])]
        return section("clearance", *keys, "numerics.points_per_cycle", f"integrators.{clearance_adapter.integrator_kind(scene)}")
    if name == "heald":
        swept = ("clearance_E", "clearance_F", "M_P")
        return section("heald", *(f"parameters.{p}" for p in config["heald"]["parameters"] if p not in swept), "excitation", "speeds")
    raise ValueError(f"no sweep named {name!r}")


def sweep_spec(name):
    """What a sweep holds fixed (scene, variant, model, cycles): everything but its grids."""
    return {k: v for k, v in config["sweeps"][name].items() if k not in ("small", "large")}


def sweep_args(wildcards):
    return {"point": sweep_grid(sweep_axes(wildcards.sweep))[int(wildcards.index)], "spec": sweep_spec(wildcards.sweep)}


rule sweep_point:
    input:
        code=lambda wildcards: code(f"linkwork.papers.{wildcards.sweep}.sweep"),
    output:
        "results/sweeps/{sweep}/point_{index}.nc",
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
    input:
        points=lambda wildcards: expand("results/sweeps/{sweep}/point_{index}.nc", sweep=wildcards.sweep, index=range(len(sweep_grid(sweep_axes(wildcards.sweep))))),
        code=code("linkwork.pipeline.sweeps"),
    output:
        "results/sweeps/{sweep}.nc",
    wildcard_constraints:
        sweep="|".join(SWEEPS),
    params:
        study="linkwork.pipeline.sweeps:gathered",
        cfg=lambda wildcards: {"name": wildcards.sweep, "grid": config["sweeps"]["grid"], "axes": sweep_axes(wildcards.sweep), "spec": sweep_spec(wildcards.sweep)},
    script:
        STUDY
