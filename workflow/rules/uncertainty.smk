# Input uncertainty, propagated: each paper's assumed inputs within their ranges, in batches that fan out.
import importlib

from linkwork.pipeline.uncertainty import batches as uncertainty_batches
from linkwork.pipeline.uncertainty import sample_count

UNCERTAIN_PAPERS = ["beatup", "heald", "transplanter", "clearance"]  # stiffness: every input is printed
CLEARANCE_UNCERTAINTY = importlib.import_module("linkwork.papers.clearance.uncertainty").batch_jobs(CLEARANCE)


def uncertainty_cfg(paper, index):
    """The config values batch ``index`` reads: the paper's model, the ranges and the study's settings; for the
    clearance paper only the keys of the scenes its sample moves."""
    if paper == "beatup":
        return section("beatup", "sixbar", "printed_rounding", "grids", "numerics.scan_points", "numerics.root_xtol_rad", "uncertainty", design=True)
    if paper == "heald":
        return section("heald", *HEALD_MODEL, "models", "uncertainty", design=True)
    if paper == "transplanter":
        return section("transplanter", *TRANSPLANTER_PROBLEM, *TRANSPLANTER_COMPARED, "initial_diameters_m", "fe.angle_step_deg", "optimization.slsqp_ftol", "uncertainty", design=True)
    job = CLEARANCE_UNCERTAINTY[index]
    keys = {k for s in job["scenes"] for k in clearance_adapter.scene_keys(CLEARANCE, job["variant"], s) if not k.startswith("check_integrators.")}
    return section("clearance", *sorted(keys))  # a sample's runs make no check reruns: they take the nominal error bar


def uncertainty_args(paper, index):
    if paper == "clearance":  # the sample's moved values travel as arguments: a range edit reruns its batches
        job = CLEARANCE_UNCERTAINTY[index]
        return {"samples": job["samples"], "variant": job["variant"]}
    return {"index": index}


def uncertainty_gather_cfg(paper):
    """The gather step reads the ranges; the clearance paper also judges its claims there (threshold, variants)."""
    if paper == "clearance":
        return section("clearance", "claims", "assumed", "uncertainty", "states.starts", "statistics.confidence", *(f"variants.{v}" for v in CLEARANCE_VARIANTS), design=True)
    return uncertainty_cfg(paper, 0)


def uncertainty_batch_count(paper):
    if paper == "clearance":
        return len(CLEARANCE_UNCERTAINTY)
    study = importlib.import_module(f"linkwork.papers.{paper}.uncertainty")
    settings = config[paper]["uncertainty"]
    count = sample_count(study.inputs(config[paper]), settings["lhs_points"], settings["search"]["corner_limit"])
    return len(uncertainty_batches(count, settings["batch_size"]))


def uncertainty_inputs(wildcards):
    code_ = code(f"linkwork.papers.{wildcards.paper}.uncertainty")
    if wildcards.paper == "clearance":  # a sample reruns only the scenes its input enters, continuing from their nominal states
        job = CLEARANCE_UNCERTAINTY[int(wildcards.index)]
        return {"nominal": [f"results/clearance/{job['variant']}/{s}.nc" for s in job["scenes"]], "code": code_}
    extra = {"optim": "results/transplanter/optim.nc"} if wildcards.paper == "transplanter" else {}  # its samples start from our optimum
    return {"published": f"config/published/{wildcards.paper}.yaml", **extra, "code": code_}


def uncertainty_gather_inputs(wildcards):
    batches = expand("results/uncertainty/{paper}/batch_{index}.nc", paper=wildcards.paper, index=range(uncertainty_batch_count(wildcards.paper)))
    extra = {"published": f"config/published/{wildcards.paper}.yaml"}  # the searches read the acceptance regions
    if wildcards.paper == "clearance":  # the nominal deviations; the claims are judged here, so a threshold edit reruns no scene
        extra["claims"] = "results/clearance/claims.nc"
    if wildcards.paper == "transplanter":  # the searches' evaluations start from our optimum, as the samples do
        extra["optim"] = "results/transplanter/optim.nc"
    return {"batches": batches, **extra, "code": code(f"linkwork.papers.{wildcards.paper}.uncertainty")}


rule uncertainty_batch:
    priority: CHAIN_HEAD_PRIORITY
    input:
        unpack(uncertainty_inputs),
    output:
        "results/uncertainty/{paper}/batch_{index}.nc",
    wildcard_constraints:
        paper="|".join(UNCERTAIN_PAPERS),
        index=r"\d+",
    params:
        study=lambda wildcards: f"linkwork.papers.{wildcards.paper}.uncertainty:batch",
        cfg=lambda wildcards: uncertainty_cfg(wildcards.paper, int(wildcards.index)),
        args=lambda wildcards: uncertainty_args(wildcards.paper, int(wildcards.index)),
    script:
        STUDY


rule uncertainty_gather:
    # it starts as soon as its batches are in, on half the cores: on two cores a two-thread gather waited for both
    # to be free, which the clearance jobs never left them until the end (it then ran alone for 44 s)
    priority: CHAIN_HEAD_PRIORITY + 1
    # the scenarios' bounded searches run side by side (linkwork.pipeline.search.refine, one process per thread)
    threads: max(1, (workflow.cores or 2) // 2)
    input:
        unpack(uncertainty_gather_inputs),
    output:
        "results/{paper}/uncertainty.nc",
    wildcard_constraints:
        paper="|".join(UNCERTAIN_PAPERS),
    params:
        study=lambda wildcards: f"linkwork.papers.{wildcards.paper}.uncertainty:gather",
        cfg=lambda wildcards: uncertainty_gather_cfg(wildcards.paper),
    script:
        STUDY
