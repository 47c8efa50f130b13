# Input uncertainty, propagated: each paper's assumed inputs within their ranges, in batches that fan out.
import importlib

from linkwork.pipeline.uncertainty import batches as uncertainty_batches
from linkwork.pipeline.uncertainty import sample_count

UNCERTAIN_PAPERS = list(
    UNCERTAINTY
)  # each paper's rule file registers its study (common.smk); stiffness: every input is printed


def uncertainty_cfg(paper, index):
    """The config values batch ``index`` reads (the paper's UNCERTAINTY entry)."""
    return UNCERTAINTY[paper]["cfg"](index)


def uncertainty_args(paper, index):
    return UNCERTAINTY[paper].get("args", lambda i: {"index": i})(index)


def uncertainty_gather_cfg(paper):
    """The gather step reads the ranges (a paper may also judge its claims there)."""
    facts = UNCERTAINTY[paper]
    return facts["gather_cfg"]() if "gather_cfg" in facts else facts["cfg"](0)


def uncertainty_batch_count(paper):
    facts = UNCERTAINTY[paper]
    if "batch_count" in facts:
        return facts["batch_count"]()
    study = importlib.import_module(f"linkwork.papers.{paper}.uncertainty")
    settings = config[paper]["uncertainty"]
    count = sample_count(study.inputs(config[paper]), settings["lhs_points"], settings["search"]["corner_limit"])
    return len(uncertainty_batches(count, settings["batch_size"]))


def uncertainty_inputs(wildcards):
    facts = UNCERTAINTY[wildcards.paper]
    inputs = (
        facts["batch_inputs"](int(wildcards.index))
        if "batch_inputs" in facts
        else {"published": f"config/published/{wildcards.paper}.yaml"}
    )
    return {**inputs, "code": code(f"linkwork.papers.{wildcards.paper}.uncertainty")}


def uncertainty_gather_inputs(wildcards):
    batches = expand(
        "results/uncertainty/{paper}/batch_{index}.nc",
        paper=wildcards.paper,
        index=range(uncertainty_batch_count(wildcards.paper)),
    )
    extra = {"published": f"config/published/{wildcards.paper}.yaml"}  # the searches read the acceptance regions
    extra.update(UNCERTAINTY[wildcards.paper].get("gather_inputs", lambda: {})())
    return {"batches": batches, **extra, "code": code(f"linkwork.papers.{wildcards.paper}.uncertainty")}


rule uncertainty_batch:
    input:
        unpack(uncertainty_inputs),
    output:
        "results/uncertainty/{paper}/batch_{index}.nc",
    wildcard_constraints:
        paper="|".join(UNCERTAIN_PAPERS),
        index=r"\d+",
    priority: CHAIN_HEAD_PRIORITY
    params:
        study=lambda wildcards: f"linkwork.papers.{wildcards.paper}.uncertainty:batch",
        cfg=lambda wildcards: uncertainty_cfg(wildcards.paper, int(wildcards.index)),
        args=lambda wildcards: uncertainty_args(wildcards.paper, int(wildcards.index)),
    script:
        STUDY


rule uncertainty_gather:
    input:
        unpack(uncertainty_gather_inputs),
    output:
        "results/{paper}/uncertainty.nc",
    wildcard_constraints:
        paper="|".join(UNCERTAIN_PAPERS),
    # it starts as soon as its batches are in, on half the cores: on two cores a two-thread gather waited for both
    # to be free, which the clearance jobs never left them until the end (it then ran alone for 44 s)
    priority: CHAIN_HEAD_PRIORITY + 1
    # the scenarios' bounded searches run side by side (linkwork.pipeline.search.refine, one process per thread)
    threads: max(1, (workflow.cores or 2) // 2)
    params:
        study=lambda wildcards: f"linkwork.papers.{wildcards.paper}.uncertainty:gather",
        cfg=lambda wildcards: uncertainty_gather_cfg(wildcards.paper),
    script:
        STUDY
