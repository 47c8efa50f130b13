# Two entry points for a fresh machine with Python 3.11:
#   make reproduce   set up .venv if needed, then run the whole reproduction (bare `snakemake`)
#   make test        set up .venv if needed, then run the tests
PYTHON ?= python3
VENV   ?= .venv
BIN    := $(abspath $(VENV))/bin
STAMP  := $(VENV)/.installed

.PHONY: setup reproduce test bench clean

setup: $(STAMP)

$(STAMP): pyproject.toml constraints.txt
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -c constraints.txt -e '.[test]'
	touch $@

reproduce: $(STAMP)
	PATH="$(BIN):$$PATH" snakemake

test: $(STAMP)
	PATH="$(BIN):$$PATH" python -m pytest

bench: $(STAMP)
	PATH="$(BIN):$$PATH" python benchmarks/foundation.py

clean:
	rm -rf results .snakemake
