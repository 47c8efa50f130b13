# Helpers shared by the rule files: the study script, narrow config values, code inputs from real imports.
import sys
from functools import lru_cache
from pathlib import Path

from linkwork.configformat import DESIGN_FIELDS, labelled_entries, narrow
from linkwork.papers import PAPERS
from linkwork.pipeline.deps import closure, relative

ROOT = Path(workflow.basedir)
LIB = ROOT / "lib"
STUDY = "../scripts/study.py"
RENDERER = "workflow/scripts/render_report.py"
# The long jobs (work-precision, sweep points) start before the short ones: left to the end, one of them runs
# alone on a core while its report waits (job times: .snakemake/metadata, benchmarks/pipeline.py,
# benchmarks/job_resources.py).
LONG_JOB_PRIORITY = 10
# Before them the heads of the long chains: the clearance scenes (every clearance sample, the contact-law
# sensitivity and the longest report wait for them), the sensitivity (one 36-s job), the transplanter optimum and
# the uncertainty batches (the transplanter gather, one 63-s job, waits for them), and each gather as soon as its
# batches are in.  Behind the sweep points, the sensitivity and the transplanter gather ran alone at the end.
CHAIN_HEAD_PRIORITY = 20
# Before everything the short links that gate the longest report (the clearance one, 10 s, waits for its paper's
# assumptions, the claims, the comparison, the work-precision study and the gathered sweep), and that report itself:
# at priority 0 they waited behind every sweep point and the small jobs, and the clearance report then ran alone at
# the end (benchmarks/job_resources.py's per-job times).
GATE_PRIORITY = CHAIN_HEAD_PRIORITY + 2
# The interpreter Snakemake runs on: shell rules use it, so an unactivated .venv/bin/snakemake works.
PYTHON = sys.executable


@lru_cache(maxsize=None)
def code_of(*entries):
    """Lib files (and sibling helpers) in the import closure of the given files or modules (rule inputs)."""
    first, *rest = entries
    return relative(closure(first, LIB, extra=tuple(rest)), ROOT)


def code(*entries):
    """Lib files in the import closure of the study script and the given modules or files (rule inputs)."""
    return code_of(ROOT / "workflow/scripts/study.py", *entries)


# What each paper tells the shared rule files, filled in by the paper's own rule file (the shared files name no paper):
# UNCERTAINTY[paper]: its input-uncertainty study (uncertainty.smk): "cfg" (batch index -> the config values a batch
#   reads) and, where they differ from the default, "args" (index -> the batch's arguments; default {"index": index}),
#   "gather_cfg" (() -> the gather's values; default: batch 0's), "batch_count" (() -> batches; default: from the
#   design's sample count), "batch_inputs" (index -> named inputs; default: the published numbers), "gather_inputs"
#   (() -> named inputs besides the batches and the published numbers).  A paper without an entry has no assumed input.
# SWEEP[name]: its sweep (sweeps.smk): "cfg" (() -> the paper's values a point reads), "reference" (() -> the grid
#   point the paragraph refers to), optionally "gather_inputs" and "gather_cfg" (() -> what the gather also reads).
# REPORT_PRIORITY[report]: a report that must not wait in the tail (default 0).
# REPORT_INPUTS[report]: the files a report reads, by the names the report uses (a paper: ``paper_report``; the
#   renderer passes them by name, reports.smk adds the reports across papers).
# ACCURACY_REPORT_INPUTS: what the accuracy report also reads (a paper's extra work-precision study).
UNCERTAINTY = {}
SWEEP = {}
REPORT_PRIORITY = {}
REPORT_INPUTS = {}
ACCURACY_REPORT_INPUTS = {}


def paper_report(paper, **results):
    """A paper report's inputs: its results by name, and the files every paper report reads (call it after the paper's
    UNCERTAINTY entry)."""
    uncertainty = {"uncertainty": f"results/{paper}/uncertainty.nc"} if paper in UNCERTAINTY else {}
    return {
        **results,
        **uncertainty,
        "comparison": f"results/{paper}/comparison.csv",
        "findings": f"results/{paper}/findings.nc",
        "published": f"config/published/{paper}.yaml",
        "assumptions": f"results/{paper}/assumptions.nc",
    }


def comparison_table(paper):
    """A paper's comparison table as a rule output, shown with its caption in Snakemake's report
    (snakemake --report)."""
    return report(
        f"results/{paper}/comparison.csv",
        caption="../report/comparison.rst",
        category="Published numbers beside ours",
        labels={"paper": paper, "file": "comparison.csv"},
    )


def section(paper, *paths, design=False):
    """Exactly the given key paths of a paper's config section (a rule's params.cfg), each labelled entry reduced to
    its value unless a path names a label field itself; ``design``: every entry keeps its range and choices too (the
    uncertainty design).  Reasons reach only the assumptions rule, so a reason edit reruns no study."""
    return narrow(config[paper], paths, DESIGN_FIELDS if design else ())


def assumptions_cfg(paper):
    """Every labelled entry of a paper's section, whole (the assumptions rule: the reports' reasons and ranges)."""
    return labelled_entries(config.get(paper, {}))  # a paper without a config section has no labelled entry


# On a cluster (profiles/slurm) these run on the submitting host: each reads finished results and computes for
# about a second (benchmarks/measured/job_resources.json), less than a submission costs. Locally: no effect.
localrules:
    all,
    readme_findings,
    accuracy_summary,
    sweep_gather,
    clearance_claims,
    clearance_crosscheck_summary,
    stiffness_compare,
    beatup_compare,
    heald_compare,
    transplanter_compare,
    clearance_compare,
    assumptions,
