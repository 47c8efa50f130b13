# Parameter sweeps that fan out: every grid point is an independent job, gathered into one netCDF.

SWEEP_CODE = {
    "clearance": lib("sweeps", "multibody/kernels", "multibody/model", "clearance_dataset", "kinematics", "results"),
    "heald": lib("sweeps", "chains", "heald", "heald_dataset", "results"),
}


def sweep_points(name):
    import itertools

    spec = config["sweeps"][name][config["sweeps"]["grid"]]
    return range(len(list(itertools.product(*spec.values()))))


rule sweep_point:
    input:
        code=lambda wildcards: SWEEP_CODE[wildcards.sweep],
    output:
        "results/sweeps/{sweep}/point_{index}.nc",
    wildcard_constraints:
        sweep="clearance|heald",
        index=r"\d+",
    params:
        config=lambda wildcards: {wildcards.sweep: config[wildcards.sweep]},
        sweeps=config["sweeps"],
    script:
        "../scripts/sweep_point.py"


rule sweep_gather:
    input:
        points=lambda wildcards: expand("results/sweeps/{sweep}/point_{index}.nc", sweep=wildcards.sweep, index=sweep_points(wildcards.sweep)),
        code=lib("sweeps", "results"),
    output:
        "results/sweeps/{sweep}.nc",
    wildcard_constraints:
        sweep="clearance|heald",
    params:
        sweeps=config["sweeps"],
    script:
        "../scripts/sweep_gather.py"
