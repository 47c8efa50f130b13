# Input uncertainty, propagated: each paper's assumed inputs within their ranges, in batches that fan out.
import importlib

from linkwork.pipeline.uncertainty import batches as uncertainty_batches
from linkwork.pipeline.uncertainty import sample_count

UNCERTAIN_PAPERS = ["beatup", "heald", "transplanter", "clearance"]  # stiffness: every input is printed


def uncertainty_cfg(paper):
    """The config values a batch reads: the paper's model, the ranges and the study's settings."""
    if paper == "beatup":
        return section("beatup", "sixbar", "printed_rounding", "grids", "numerics.scan_points", "numerics.root_xtol_rad", "uncertainty")
    if paper == "heald":
        return section("heald", *HEALD_MODEL, "models", "uncertainty")
    if paper == "transplanter":
        return section("transplanter", *TRANSPLANTER_PROBLEM, *TRANSPLANTER_COMPARED, "initial_diameters_m", "fe.angle_step_deg", "optimization.slsqp_ftol", "uncertainty")
    keys = {k for v in CLEARANCE_VARIANTS for s in CLEARANCE_SCENES for k in clearance_adapter.scene_keys(CLEARANCE, v, s)}
    return section("clearance", *sorted(keys), "claims", "assumed", "uncertainty")


def uncertainty_batch_count(paper):
    study = importlib.import_module(f"linkwork.papers.{paper}.uncertainty")
    settings = config[paper]["uncertainty"]
    return len(uncertainty_batches(sample_count(study.inputs(config[paper]), settings["lhs_points"]), settings["batch_size"]))


def uncertainty_inputs(wildcards):
    extra = {}
    if wildcards.paper == "clearance":  # the nominal runs; a sample reruns only the scenes its input enters
        extra = {"scenes": rules.clearance_claims.input.scenes, "tight": rules.clearance_claims.input.tight}
    return {"published": f"config/published/{wildcards.paper}.yaml", "code": code(f"linkwork.papers.{wildcards.paper}.uncertainty"), **extra}


rule uncertainty_batch:
    input:
        unpack(uncertainty_inputs),
    output:
        "results/uncertainty/{paper}/batch_{index}.nc",
    wildcard_constraints:
        paper="|".join(UNCERTAIN_PAPERS),
        index=r"\d+",
    params:
        study=lambda wildcards: f"linkwork.papers.{wildcards.paper}.uncertainty:batch",
        cfg=lambda wildcards: uncertainty_cfg(wildcards.paper),
        args=lambda wildcards: {"index": int(wildcards.index)},
    script:
        STUDY


rule uncertainty_gather:
    input:
        batches=lambda wildcards: expand("results/uncertainty/{paper}/batch_{index}.nc", paper=wildcards.paper, index=range(uncertainty_batch_count(wildcards.paper))),
        code=lambda wildcards: code(f"linkwork.papers.{wildcards.paper}.uncertainty"),
    output:
        "results/{paper}/uncertainty.nc",
    wildcard_constraints:
        paper="|".join(UNCERTAIN_PAPERS),
    params:
        study=lambda wildcards: f"linkwork.papers.{wildcards.paper}.uncertainty:gather",
        cfg=lambda wildcards: uncertainty_cfg(wildcards.paper),
    script:
        STUDY
