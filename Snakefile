# linkwork: one DAG re-deriving five planar-linkage papers.
# Bare `snakemake` reads profiles/default/profile.yaml (all cores).
import os
import sys
from pathlib import Path

from snakemake.utils import min_version

min_version("9.0")

sys.path.insert(0, str(Path(workflow.basedir) / "lib"))
from linkwork import compilecache  # noqa: E402
from linkwork.pipeline.errors import ConfigError  # noqa: E402
from linkwork.pipeline.results import final_result_problem, unwritable  # noqa: E402
from linkwork.pipeline.scheduler import daemon_timers  # noqa: E402
from linkwork.papers import PAPERS  # noqa: E402
from linkwork.project.validate import coerce_overrides, load_yaml, merge_overrides, validate_once  # noqa: E402

# One BLAS thread per job unless the caller chose otherwise: Snakemake keeps every core busy with jobs, and OpenBLAS
# (numpy's and scipy's, one pool each) would start a thread per core in every job, threads that then wait against the
# other jobs: on n cores, n jobs of n threads each.  No job here has matrices large enough to gain from threads.
# Measured on 2 cores: the transplanter's gather beside a busy core took 85 s with the default and 70 s with one thread,
# the same results to the bit; a whole forced run showed no difference beyond its run-to-run spread.  The jobs inherit
# it; on a cluster each job's Snakemake reads this file again.
for _blas in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_blas, "1")

# The scheduler sleeps between jobs (the default profile's job-rate limit; linkwork.pipeline.scheduler): its pending
# re-evaluations must not keep this process alive once the run is done.
daemon_timers()

# Read config/config.yaml ourselves (duplicate keys and syntax errors named with file and line), let
# --config/--configfile values override it (--config's text read as the numbers the schema asks for; a --configfile
# read again for duplicate keys), then validate everything before any job: schema (types,
# ranges, unknown keys), each paper's physical checks and the published-numbers files (config/published.schema.yaml).
# Errors are one line per problem.  A config that passed with the same schema, published files and checking code is
# not checked again (.snakemake/linkwork-validated).
_root = Path(workflow.basedir)
try:
    if compilecache.problem():  # the jobs compile into it: a file in its place or no write permission, named now
        raise ConfigError(compilecache.problem())
    if not workflow.dryrun and unwritable(_root / "results"):  # Snakemake removes a result before rewriting it
        raise ConfigError(unwritable(_root / "results"))
    coerce_overrides(config, workflow.config_settings.config, load_yaml(_root / "config" / "schema.yaml"))
    for (
        _file
    ) in (
        workflow.config_settings.configfiles
    ):  # Snakemake keeps a duplicated key's last value: refuse it, with its line
        load_yaml(_file)
    merge_overrides(config, load_yaml(_root / "config" / "config.yaml"))
    validate_once(
        config,
        _root / "config" / "schema.yaml",
        _root / "lib",
        _root / ".snakemake" / "linkwork-validated",
        _root / "config" / "published",
    )
    # the final results no job reads (linkages of your own, the reports): a damaged one is named before planning
    for _final in sorted((_root / "results" / "linkages").glob("*.nc")) + sorted(
        (_root / "results" / "reports").glob("*.html")
    ):
        if final_result_problem(_final):
            raise ConfigError(final_result_problem(_final))
except ConfigError as exc:
    sys.exit(f"linkwork: {exc}")


# `snakemake --report results/report.html` after a reproduction: the reports and the comparison tables with captions,
# the jobs' run times and the workflow's graph (workflow/report/).
report: "workflow/report/workflow.rst"


include: "workflow/rules/common.smk"


for _paper in PAPERS:  # each paper's own rules; it registers what the shared files below need (common.smk)

    include: f"workflow/rules/{_paper}.smk"


include: "workflow/rules/accuracy.smk"
include: "workflow/rules/sweeps.smk"
include: "workflow/rules/uncertainty.smk"
include: "workflow/rules/reports.smk"
include: "workflow/rules/linkages.smk"


# Every report (together they read every result) and the README's findings: the whole reproduction.
rule all:
    input:
        expand("results/reports/{report}.html", report=REPORT_INPUTS),
        "results/readme_findings.md",
        expand("results/linkages/{name}.nc", name=LINKAGES),
