# linkwork: one DAG re-deriving five planar-linkage papers.
# Bare `snakemake` reads profiles/default/profile.yaml (all cores).
import sys
from pathlib import Path

import yaml
from snakemake.utils import min_version

min_version("9.0")

sys.path.insert(0, str(Path(workflow.basedir) / "lib"))
from linkwork.config import validate_config  # noqa: E402

configfile: "config/config.yaml"

# Schema (types, ranges, unknown keys) and physical checks, before any job.
with open(Path(workflow.basedir) / "config" / "schema.yaml") as fh:
    validate_config(config, yaml.safe_load(fh))

include: "workflow/rules/common.smk"
include: "workflow/rules/stiffness.smk"
include: "workflow/rules/beatup.smk"
include: "workflow/rules/heald.smk"
include: "workflow/rules/transplanter.smk"
include: "workflow/rules/clearance.smk"
include: "workflow/rules/accuracy.smk"
include: "workflow/rules/sweeps.smk"
include: "workflow/rules/reports.smk"


rule all:
    input:
        "results/stiffness/stiffness.nc",
        "results/beatup/sixbar.nc",
        "results/beatup/window.nc",
        "results/beatup/accuracy.nc",
        "results/heald/chain.nc",
        "results/heald/accuracy.nc",
        "results/transplanter/ked.nc",
        "results/transplanter/optim.nc",
        "results/transplanter/accuracy.nc",
        expand("results/clearance/{variant}/{scene}.nc", variant=CLEARANCE_VARIANTS, scene=CLEARANCE_SCENES),
        "results/clearance/claims.nc",
        "results/clearance/accuracy.nc",
        expand("results/reports/{paper}.html", paper=BUILT_PAPERS),
        "results/accuracy/summary.nc",
        "results/sweeps/clearance.nc",
        "results/sweeps/heald.nc",
        "results/reports/accuracy.html",
        "results/reports/sweeps.html",
        "results/reports/index.html",
