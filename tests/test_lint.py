"""The linter in the test run: ruff with the project's settings (pyproject.toml: pyflakes, syntax errors and lines of
at most 120 columns) over every Python file of the project, and the same line length for the Snakemake files, which
ruff cannot read."""

from __future__ import annotations

import subprocess
import sys
import tomllib
from pathlib import Path

PROJECT = Path(__file__).resolve().parents[1]
#: The folders of Python code the linter reads (every one the project has).
PYTHON_FOLDERS = ("lib", "reports", "tests", "benchmarks", "workflow/scripts")


def _ruff(*args: str, cwd: Path = PROJECT) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "ruff", *args], cwd=cwd, capture_output=True, text=True)


def _line_length() -> int:
    return tomllib.loads((PROJECT / "pyproject.toml").read_text())["tool"]["ruff"]["line-length"]


def test_ruff_finds_nothing():
    run = _ruff("check", "--output-format", "concise", *PYTHON_FOLDERS)
    assert run.returncode == 0, run.stdout + run.stderr


def test_ruff_refuses_a_long_line_and_an_unused_import(tmp_path):
    """The project's settings select the rules the first test relies on: a line one column too long and an unused
    import are both reported."""
    (tmp_path / "pyproject.toml").write_text((PROJECT / "pyproject.toml").read_text())
    width = _line_length()
    (tmp_path / "bad.py").write_text("import os\n\nx = " + "1" * (width - 3) + "\n")
    run = _ruff("check", "--output-format", "concise", "--no-cache", "bad.py", cwd=tmp_path)
    assert run.returncode == 1
    assert "E501" in run.stdout and "F401" in run.stdout, run.stdout


def test_snakemake_files_keep_the_line_length():
    width = _line_length()
    files = [PROJECT / "Snakefile", *sorted((PROJECT / "workflow" / "rules").glob("*.smk"))]
    long = [
        f"{path.relative_to(PROJECT)}:{number}: {len(line)} columns"
        for path in files
        for number, line in enumerate(path.read_text().splitlines(), start=1)
        if len(line) > width
    ]
    assert files[1:], "no rule files found"
    assert not long, "\n".join(long)
