# Two entry points for a fresh machine with Python 3.11:
#   make reproduce   set up .venv if needed, then run the whole reproduction (bare `snakemake`) and compare the
#                    README's findings with it
#   make test        set up .venv if needed, then run the tests
PYTHON ?= python3
VENV   ?= .venv
BIN    := $(abspath $(VENV))/bin
STAMP  := $(VENV)/.installed

.PHONY: setup reproduce test browser bench readme crosscheck slurm slurm-proof clean

setup: $(STAMP)

$(STAMP): pyproject.toml constraints.txt
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -c constraints.txt -e '.[test]'
	touch $@

# the run, then one line: whether the README's findings are this run's
reproduce: $(STAMP)
	PATH="$(BIN):$$PATH" snakemake
	$(BIN)/python -c "import sys; sys.path.insert(0, 'lib'); from pathlib import Path; from linkwork.project.readme import check; check(Path('.'))"

# two workers, one test file each at a time (a file's module fixtures are built once), in collection order (the
# workflow files first: tests/conftest.py), so the workflow tests' snakemake run starts at once and the other files
# share the second core; the slowest tests are listed at the end (where CI time goes)
test: $(STAMP) browser
	PATH="$(BIN):$$PATH" python -m pytest -n 2 --dist loadfile --no-loadscope-reorder --durations=15

# The browser the report test drives: Debian's chromium (installed if missing and apt-get is at hand).
browser:
	@command -v chromium >/dev/null || command -v chromium-browser >/dev/null || \
	  { command -v apt-get >/dev/null && (apt-get update -qq && apt-get install -y -qq chromium >/dev/null) ; } || \
	  { echo "make test needs Chromium for the report test: install Debian's chromium (apt-get install chromium)"; exit 1; }

# Exudyn beside linkwork: the optional extra (also in the test extra), then the reproduction with the cross-check
# in the clearance report (results/clearance/crosscheck/).  A later bare `snakemake` renders the report without it.
crosscheck: $(STAMP)
	$(BIN)/python -m pip install --quiet -c constraints.txt -e '.[crosscheck]'
	PATH="$(BIN):$$PATH" snakemake --config crosscheck=True

# The DAG on SLURM (profiles/slurm/README.md): the slurm extra, then the run. SITE_PROFILE=<folder> adds a profile
# of your own (partition, account, status command) after the shipped one; nothing tracked is edited.
SITE_PROFILE ?=
slurm: $(STAMP)
	$(BIN)/python -m pip install --quiet -c constraints.txt -e '.[slurm]'
	PATH="$(BIN):$$PATH" snakemake --profile profiles/slurm $(if $(SITE_PROFILE),--profile $(SITE_PROFILE)) --cores 1

# Proof on a real scheduler (root, Debian): a single-node SLURM stood up and torn down by the script, the full DAG
# through profiles/slurm beside a local run, byte for byte; it prints the figures (RECORD=1: also into
# benchmarks/measured/slurm.json, rendered into docs/measured.md).
RECORD ?=
slurm-proof: $(STAMP)
	$(BIN)/python benchmarks/slurm_single_node.py $(if $(RECORD),--record)
	$(if $(RECORD),$(BIN)/python benchmarks/readme.py)

# the README's findings from the results of these sources, stamped with their fingerprint (a test compares it)
readme: $(STAMP)
	$(BIN)/snakemake results/readme_findings.md
	$(BIN)/python -c "import sys; sys.path.insert(0, 'lib'); from pathlib import Path; from linkwork.project.readme import update; update(Path('.'))"

# The main benchmarks (about 40 minutes on 2 cores; the pipeline one dominates), then the measured figures (docs/measured.md);
# the others (benchmarks/*.py) run alone, each writing its own file.
# BASELINE=<git revision> also times that revision's full reproduction beside ours.
BASELINE ?=
bench: $(STAMP) browser
	PATH="$(BIN):$$PATH" python benchmarks/foundation.py
	PATH="$(BIN):$$PATH" python benchmarks/chains.py
	PATH="$(BIN):$$PATH" python benchmarks/transplanter.py
	PATH="$(BIN):$$PATH" python benchmarks/clearance.py
	PATH="$(BIN):$$PATH" python benchmarks/tests.py
	PATH="$(BIN):$$PATH" python benchmarks/pipeline.py $(if $(BASELINE),--baseline $(BASELINE))
	$(BIN)/python benchmarks/readme.py

clean:
	rm -rf results .snakemake
