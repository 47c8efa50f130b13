# Parameter sweeps that fan out: the grid's points in jobs of `points_per_job`, gathered into one netCDF with the
# facts that interpret it (trends, threshold crossings, colour ranges).
from linkwork.pipeline.sweeps import batches as sweep_batches, grid as sweep_grid

SWEEPS = [s for s in config["sweeps"] if s != "grid"]


def sweep_axes(name):
    return config["sweeps"][name][config["sweeps"]["grid"]]


def sweep_jobs(name):
    """The grid's points, split into the sweep's jobs."""
    return sweep_batches(sweep_grid(sweep_axes(name)), config["sweeps"][name]["points_per_job"])


def sweep_cfg(name):
    """The paper's config values a point of this sweep reads (the paper's SWEEP entry; the swept values come as the
    point)."""
    return SWEEP[name]["cfg"]()


def sweep_reference(name):
    """The grid point the paragraph and the colour scale refer to: the paper's configured (nominal) values."""
    return SWEEP[name]["reference"]()


def sweep_spec(name):
    """What a sweep holds fixed (scene, variant, model, cycles): everything but its grids and job size."""
    return {k: v for k, v in config["sweeps"][name].items() if k not in ("small", "large", "points_per_job")}


def sweep_gather_inputs(wildcards):
    name = wildcards.sweep
    return {
        "points": expand("results/sweeps/{sweep}/job_{index}.nc", sweep=name, index=range(len(sweep_jobs(name)))),
        "code": code(f"linkwork.papers.{name}.sweep"),
        **SWEEP[name].get("gather_inputs", lambda: {})(),
    }


def sweep_args(wildcards):
    return {"points": sweep_jobs(wildcards.sweep)[int(wildcards.index)], "spec": sweep_spec(wildcards.sweep)}


rule sweep_point:
    input:
        code=lambda wildcards: code(f"linkwork.papers.{wildcards.sweep}.sweep"),
    output:
        "results/sweeps/{sweep}/job_{index}.nc",
    wildcard_constraints:
        sweep="|".join(SWEEPS),
        index=r"\d+",
    priority: LONG_JOB_PRIORITY
    params:
        study=lambda wildcards: f"linkwork.papers.{wildcards.sweep}.sweep:sweep",
        cfg=lambda wildcards: sweep_cfg(wildcards.sweep),
        args=sweep_args,
    script:
        STUDY


rule sweep_gather:
    input:
        unpack(sweep_gather_inputs),
    output:
        "results/sweeps/{sweep}.nc",
    wildcard_constraints:
        sweep="|".join(SWEEPS),
    priority: GATE_PRIORITY
    params:
        study=lambda wildcards: f"linkwork.papers.{wildcards.sweep}.sweep:gathered",
        cfg=lambda wildcards: {
            "grid": config["sweeps"]["grid"],
            "axes": sweep_axes(wildcards.sweep),
            "spec": sweep_spec(wildcards.sweep),
            "reference": sweep_reference(wildcards.sweep),
            **SWEEP[wildcards.sweep].get("gather_cfg", lambda: {})(),
        },
    script:
        STUDY
