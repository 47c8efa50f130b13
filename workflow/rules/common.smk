# Helpers shared by the rule files: the study script, narrow config values, code inputs from real imports.
import sys
from pathlib import Path

from linkwork.configformat import pick
from linkwork.papers import PAPERS
from linkwork.pipeline.deps import closure, relative

ROOT = Path(workflow.basedir)
LIB = ROOT / "lib"
STUDY = "../scripts/study.py"
RENDERER = "workflow/scripts/render_report.py"
# The interpreter Snakemake runs on: shell rules use it, so an unactivated .venv/bin/snakemake works.
PYTHON = sys.executable


def code(*entries):
    """Lib files in the import closure of the study script and the given modules or files (rule inputs)."""
    return relative(closure(ROOT / "workflow/scripts/study.py", LIB, extra=entries), ROOT)


def code_of(*entries):
    """Lib files (and sibling helpers) in the import closure of the given files or modules only."""
    first, *rest = entries
    return relative(closure(first, LIB, extra=tuple(rest)), ROOT)


def section(paper, *paths):
    """Exactly the given key paths of a paper's config section (a rule's params.cfg)."""
    return pick(config[paper], paths)
