"""The Snakemake workflow on temporary copies of the project: real runs, dry runs, reruns, bad input.

The `built` fixture runs the whole pipeline once on a copy, at the tests' scale (tests/ci_scale.yaml: shorter
records, the same jobs), with every Python process recording which linkwork modules it loaded
(tests/tracing/sitecustomize.py).  The rerun tests then edit that copy and
compare what a dry run schedules with the specification (tests/rerun_spec.yaml for config keys; the
declared code inputs, checked against the recorded imports, for lib modules).
"""

import fnmatch
import hashlib
import json
import os
import re
import select
import shutil
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest
import yaml

from conftest import PROJECT

pytestmark = pytest.mark.workflow

COPIED = ["Snakefile", "config", "workflow", "lib", "reports", "profiles"]
TRACING = Path(__file__).resolve().parent / "tracing"
OUTPUTS = [
    "results/stiffness/stiffness.nc",
    "results/beatup/sixbar.nc",
    "results/beatup/window.nc",
    "results/heald/chain.nc",
    "results/transplanter/ked.nc",
    "results/transplanter/optim.nc",
    "results/clearance/slender/dry_both.nc",
    "results/clearance/claims.nc",
    "results/accuracy/summary.nc",
    "results/sweeps/clearance.nc",
    "results/sweeps/heald.nc",
]
REPORTS = ("stiffness", "beatup", "heald", "transplanter", "clearance", "accuracy", "sweeps", "index")
ALL_JOBS = {
    "all": 1,
    "stiffness": 1,
    "stiffness_accuracy": 1,
    "stiffness_compare": 1,
    "beatup_sixbar": 1,
    "beatup_window": 1,
    "beatup_accuracy": 1,
    "beatup_compare": 1,
    "beatup_sley_pin": 1,
    "heald_chain": 1,
    "heald_accuracy": 1,
    "heald_compare": 1,
    "heald_contact": 1,
    "transplanter_optim": 1,
    "transplanter_ked": 1,
    "transplanter_at_published": 1,
    "transplanter_accuracy": 1,
    "transplanter_compare": 1,
    "clearance_scene": 14,
    "clearance_contact_law": 2,
    "clearance_memory_free": 2,
    "clearance_claims": 1,
    "clearance_work_precision": 1,
    "clearance_compare": 1,
    "accuracy_summary": 1,
    "sweep_point": 6,
    "sweep_gather": 2,
    "report": 8,
    "uncertainty_batch": 17,
    "uncertainty_gather": 4,
    "readme_findings": 1,  # 1 + 2 + 4 + 10 (clearance: one per variant and input)
    "assumptions": 5,  # one per paper: the labelled entries, whole (the reports' reasons)
    "linkage": 1,  # one per linkage of your own (config linkages)
}


def _env(root: Path, trace: Path | None = None) -> dict[str, str]:
    env = dict(os.environ)
    env["PATH"] = f"{Path(sys.executable).parent}{os.pathsep}{env.get('PATH', '')}"
    paths = ([str(TRACING)] if trace else []) + [str(root / "lib")]  # the copy's lib, not the installed one
    env["PYTHONPATH"] = os.pathsep.join(paths)
    for blas in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):  # the Snakefile's default, not ours
        env.pop(blas, None)
    env["LINKWORK_CHECK_FIGURES"] = "1"  # every rendered figure must draw inside its canvas (render_report)
    if trace:
        env["LINKWORK_TRACE_DIR"] = str(trace)
    return env


#: A guard against a hung run, not a timing check (benchmarks/ time the pipeline): the module's full build from an
#: empty compile cache, sharing two cores with the other test worker, took over 900 s on a machine that ran the whole
#: reproduction about three times slower than usual.
RUN_GUARD_S = 1800


def snakemake(root: Path, *args: str, check: bool = True, trace: Path | None = None) -> subprocess.CompletedProcess:
    proc = subprocess.run(
        [sys.executable, "-m", "snakemake", *args], cwd=root, env=_env(root, trace), capture_output=True, text=True,
        timeout=RUN_GUARD_S,
    )
    if check and proc.returncode != 0:
        raise AssertionError(f"snakemake {' '.join(args)} failed:\n{proc.stdout[-5000:]}\n{proc.stderr[-5000:]}")
    return proc


#: The dry-run server (``DryRuns``): imports Snakemake (and numpy, numba, xarray; never linkwork) once, then forks
#: one child per request (a JSON line: the copy, the arguments, the file for the child's output) and answers with the
#: child's exit code.
DRY_RUN_SERVER = """
import json, logging, os, sys, traceback
import numba, numpy, xarray  # third-party modules the config's validation imports: the same in every child
import snakemake.cli as cli
cli.get_argument_parser()
for line in sys.stdin:
    request = json.loads(line)
    pid = os.fork()
    if pid == 0:
        out = os.open(request["out"], os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
        os.dup2(os.open(os.devnull, os.O_RDONLY), 0)
        os.dup2(out, 1)
        os.dup2(out, 2)
        os.chdir(request["cwd"])
        code = 1
        try:
            cli.main(request["args"])
        except SystemExit as exc:  # as the interpreter ends: an exit code that is not a number is printed, status 1
            code = exc.code if isinstance(exc.code, int) else int(exc.code is not None)
            if exc.code is not None and not isinstance(exc.code, int):
                print(exc.code, file=sys.stderr)
        except BaseException:  # as the interpreter ends on an uncaught exception: its traceback, status 1
            traceback.print_exc()
        finally:
            logging.shutdown()
            sys.stdout.flush()
            sys.stderr.flush()
            os._exit(code)
    print(json.dumps(os.waitstatus_to_exitcode(os.waitpid(pid, 0)[1])), flush=True)
"""


class DryRuns:
    """Dry runs of one copy, each in a child forked from a process that has imported Snakemake once: the child parses
    the Snakefile and builds the DAG as `python -m snakemake` would, without paying Snakemake's imports again (about
    half of a dry run's time; the edit tests make over a hundred).  Use it as a context manager, from one thread."""

    def __init__(self, root: Path):
        self.root, self.count = root, 0
        self.server = subprocess.Popen(
            [sys.executable, "-c", DRY_RUN_SERVER], cwd=root, env=_env(root), stdin=subprocess.PIPE,
            stdout=subprocess.PIPE, text=True,
        )

    def __call__(self, *args: str) -> str:
        """The output of `snakemake -n *args` in the copy; a failed run raises with its output."""
        code, text = self.run(*args)
        if code != 0:
            raise AssertionError(f"snakemake -n {' '.join(args)} failed:\n{text[-5000:]}")
        return text

    def run(self, *args: str, cwd: Path | None = None) -> tuple[int, str]:
        """(exit code, stdout and stderr) of `snakemake -n *args` in the copy, or in ``cwd``: another copy of the same
        lib (the server's imports are the same)."""
        self.count += 1
        where = cwd or self.root
        out = self.root / f".dry-run-{self.count}.txt"
        self.server.stdin.write(json.dumps({"cwd": str(where), "args": ["-n", *args], "out": str(out)}) + "\n")
        self.server.stdin.flush()
        ready, _, _ = select.select([self.server.stdout], [], [], RUN_GUARD_S)
        assert ready, f"a dry run of {where} took over {RUN_GUARD_S} s"
        code, text = json.loads(self.server.stdout.readline()), out.read_text()
        out.unlink()
        return code, text

    def __enter__(self) -> "DryRuns":
        return self

    def __exit__(self, *exc) -> None:
        self.server.stdin.close()
        self.server.wait(timeout=60)


def job_listing(root: Path, *args: str, dry: DryRuns | None = None) -> dict[str, dict[str, list[str]]]:
    """Jobs of a dry run (by ``dry`` if given): id ('rule' or 'rule:wildcard/values') -> {'input': [...],
    'output': [...]}."""
    out = dry(*args) if dry else snakemake(root, "-n", *args).stdout
    jobs, current = {}, None
    for line in out.splitlines():
        head = re.match(r"^(?:local)?rule (\w+):$", line)
        if head:
            current = {"rule": head.group(1), "input": [], "output": [], "wildcards": ""}
            jobs[id(current)] = current
            continue
        field = re.match(r"^    (input|output|wildcards): (.*)$", line)
        if field and current is not None:
            value = field.group(2)
            if field.group(1) == "wildcards":
                current["wildcards"] = "/".join(part.split("=", 1)[1] for part in value.split(", "))
            else:
                current[field.group(1)] = [v.strip() for v in value.split(", ") if v.strip()]
    return {(j["rule"] + (f":{j['wildcards']}" if j["wildcards"] else "")): j for j in jobs.values()}


def planned_jobs(root: Path) -> dict[str, int]:
    """Rules a dry run would execute, with counts (from Snakemake's job-stats table)."""
    out = snakemake(root, "-n", "--quiet", "rules").stdout
    jobs = {}
    for line in out.splitlines():
        m = re.match(r"^(\S+)\s+(\d+)$", line.strip())
        if m and m.group(1) != "total":
            jobs[m.group(1)] = int(m.group(2))
    return jobs


def copy_project(dest: Path) -> Path:
    dest.mkdir(parents=True, exist_ok=True)
    for name in COPIED:
        src = PROJECT / name
        if src.is_dir():
            shutil.copytree(src, dest / name, ignore=shutil.ignore_patterns("__pycache__", "*.egg-info"))
        else:
            shutil.copy2(src, dest / name)
    return dest


def clone_of(built: Path, dest: Path) -> Path:
    shutil.copytree(built, dest, symlinks=True, ignore=shutil.ignore_patterns("trace"))
    return dest


#: Put in front of every ``reason`` of the built copy's config: config text that reaches a report must arrive escaped.
POISON = "<script>alert('linkwork')</script><b>"


#: The workflow tests' scale (shorter records, fewer points; the same jobs): see the file's header.
CI_SCALE = yaml.safe_load((Path(__file__).resolve().parent / "ci_scale.yaml").read_text())


def scale_for_ci(cfg: Path) -> None:
    """Write ``CI_SCALE`` into a copy's config file (each key must exist there)."""
    data = yaml.safe_load(cfg.read_text())
    for key, value in CI_SCALE.items():
        *parents, last = key.split(".")
        node = data
        for part in parents:
            node = node[part]
        assert last in node, key
        node[last] = value
    cfg.write_text(yaml.safe_dump(data, sort_keys=False), encoding="utf-8")


@pytest.fixture(scope="module")
def built(tmp_path_factory) -> Path:
    """A copy of the project, at the workflow tests' scale (``CI_SCALE``), on which bare `snakemake`
    (profiles/default) has run once, imports traced."""
    root = copy_project(tmp_path_factory.mktemp("built"))
    cfg = root / "config/config.yaml"
    cfg.write_text(cfg.read_text().replace('reason: "', f'reason: "{POISON} '), encoding="utf-8")
    scale_for_ci(cfg)
    assert planned_jobs(root) == ALL_JOBS
    trace = root / "trace"
    trace.mkdir()
    snakemake(root, trace=trace)
    return root


@pytest.fixture(scope="module")
def declared(built) -> dict[str, dict[str, list[str]]]:
    """Every job of the built copy with its declared inputs and outputs (a forced dry run)."""
    return job_listing(built, "--forceall")


@pytest.fixture()
def clone(built, tmp_path) -> Path:
    """An independent copy of the built project (results and .snakemake metadata included)."""
    return clone_of(built, tmp_path / "clone")


def test_config_text_reaches_the_reports_escaped(built):
    """Every reason in the built copy's config starts with a <script> tag: no report carries it live, and the
    reports that show the reasons carry it escaped (so the test sees the text arrive)."""
    shown = []
    for name in REPORTS:
        html = (built / f"results/reports/{name}.html").read_text()
        assert "<script>alert(" not in html and "<b>" not in html, name
        shown += [name] if "&lt;script&gt;alert(" in html else []
    assert {"beatup", "heald", "transplanter", "clearance"} <= set(shown), shown


def test_a_corrupted_result_names_the_file_and_the_command_that_rebuilds_it(clone):
    """A truncated result makes the next rule stop with one line naming the file and the rebuild command, which
    works."""
    target = "results/stiffness/stiffness.nc"
    (clone / target).write_bytes((clone / target).read_bytes()[:2000])
    proc = snakemake(clone, "--cores", "1", "results/reports/stiffness.html", check=False)
    assert proc.returncode != 0
    lines = [line for line in (proc.stdout + proc.stderr).splitlines() if "cannot read" in line]
    assert lines and target in lines[0] and f"snakemake --force {target}" in lines[0], proc.stderr[-3000:]
    assert "HDF5-DIAG" not in proc.stdout + proc.stderr
    snakemake(clone, "--cores", "1", "--force", target)
    snakemake(clone, "--cores", "1", "results/reports/stiffness.html")


def test_every_variable_a_published_file_may_name_is_written(built):
    """Each paper's RESULT_VARIABLES (what the published-file validation lets a measure name) is a variable of one of
    the paper's result files: the validation's list is true."""
    import importlib

    import xarray as xr

    from linkwork.papers import PAPERS

    for paper in PAPERS:
        written = set()
        for path in (built / "results" / paper).glob("*.nc"):
            with xr.open_dataset(path) as ds:
                written |= set(ds.variables)
        declared = importlib.import_module(f"linkwork.papers.{paper}.checks").RESULT_VARIABLES
        assert declared and declared <= written, (paper, sorted(declared - written))


def test_a_truncated_table_stops_the_report_naming_it(clone):
    """A comparison table cut short (head -c: still a valid CSV of fewer rows) stops its report with one line naming the
    file and the command that rebuilds it; nothing is rendered from it."""
    target = "results/stiffness/comparison.csv"
    text = (clone / target).read_bytes()
    (clone / target).write_bytes(text[: len(text) // 2])
    report = clone / "results/reports/stiffness.html"
    before = report.read_bytes()
    proc = snakemake(clone, "--cores", "1", "results/reports/stiffness.html", check=False)
    message = proc.stdout + proc.stderr
    lines = [line for line in message.splitlines() if "does not match its checksum" in line]
    assert proc.returncode != 0 and lines and target in lines[0] and "snakemake --force" in lines[0], message[-3000:]
    assert not report.exists() or report.read_bytes() == before
    assert not list((clone / "results").rglob("*.tmp"))


#: Makes every netCDF write and every report's HTML write of a job fail as on a full disk (a partial file first).
FULL_DISK = """
import errno, pathlib
import xarray

def _netcdf(self, path=None, *args, **kwargs):
    pathlib.Path(path).write_bytes(b"partial")
    raise RuntimeError("NetCDF: HDF error")

_write_text = pathlib.Path.write_text

def _text(self, *args, **kwargs):
    if self.name.endswith(".html.tmp"):
        _write_text(self, "partial")
        raise OSError(errno.ENOSPC, "No space left on device")
    return _write_text(self, *args, **kwargs)

xarray.Dataset.to_netcdf = _netcdf
pathlib.Path.write_text = _text
"""


def test_a_full_disk_stops_a_job_in_one_line_and_leaves_no_temporary(clone, tmp_path):
    hook = tmp_path / "hook"
    hook.mkdir()
    (hook / "sitecustomize.py").write_text(FULL_DISK, encoding="utf-8")
    env = _env(clone)
    env["PYTHONPATH"] = f"{hook}{os.pathsep}{env['PYTHONPATH']}"
    for target, said in (
        ("results/reports/stiffness.html", "(No space left on device)"),
        ("results/stiffness/stiffness.nc", "(NetCDF: HDF error)"),
    ):
        proc = subprocess.run(
            [sys.executable, "-m", "snakemake", "--cores", "1", "--force", target], cwd=clone, env=env,
            capture_output=True, text=True, timeout=900,
        )
        message = proc.stdout + proc.stderr
        lines = [
            line
            for line in message.splitlines()
            if f"cannot write {target}" in line or f"cannot write {clone / target}" in line
        ]
        assert proc.returncode != 0 and lines and said in lines[0] and "free disk space" in lines[0], message[-3000:]
        assert "Traceback" not in message, message[-3000:]
        assert not list((clone / "results").rglob("*.tmp")), list((clone / "results").rglob("*.tmp"))


def test_snakemakes_own_report_holds_the_reports_and_tables_with_captions(built, tmp_path):
    """`snakemake --report` after a reproduction: one self-contained page with the workflow's description, every
    rendered report and every comparison table under their captions (workflow/report/)."""
    page = tmp_path / "report.html"
    snakemake(built, "--report", str(page))
    html = page.read_text(encoding="utf-8")
    assert "linkwork re-derives five published papers" in html and "Published numbers beside ours" in html
    assert html.count("The rendered report") >= 1 and "Every published number of the paper beside ours" in html
    from linkwork.papers import PAPERS

    for name in [*PAPERS, "index", "accuracy", "sweeps"]:
        assert f"{name}.html" in html, name


#: A sixth paper, as a maintainer would add one: its package, its rule file, its report and its published numbers;
#: no shared file is edited.
TOY_PAPER = {
    "lib/linkwork/papers/toy/__init__.py": (
        '''"""Paper ``toy``: a test's."""

TITLE = "Toy 2026: one printed number"
CITATION = "A. Toy, One printed number, a test's journal 1(1), 2026"
ORDER = 6
'''
    ),
    "lib/linkwork/papers/toy/studies.py": (
        '''"""The toy paper's study."""

import xarray as xr


def study(cfg):
    """Rule study: the toy paper's one number."""
    return xr.Dataset({"answer": ((), 42.0, {"units": "1", "long_name": "the answer"})})
'''
    ),
    "lib/linkwork/papers/toy/checks.py": (
        '''"""The toy paper's checks: none (it has no config section)."""

RESULT_VARIABLES = frozenset({"answer"})


def check(section, key="toy"):
    """Nothing to check."""
'''
    ),
    "lib/linkwork/papers/toy/findings.py": (
        '''"""The toy paper's number beside ours."""

from ...pipeline.compare import compare_datasets, counts_dataset, findings_attrs


def compare(cfg, published, result):
    """Rule study: the comparison table and the findings."""
    table = compare_datasets(published, [result])
    findings = counts_dataset(table)
    findings.attrs.update(findings_attrs("Toy 2026", "", ""))
    return table, findings
'''
    ),
    "workflow/rules/toy.smk": (
        """# Paper "toy": one printed number (a test's).


rule toy:
    input:
        code=code("linkwork.papers.toy.studies"),
    output:
        "results/toy/result.nc",
    params:
        study="linkwork.papers.toy.studies:study",
        cfg={},
    script:
        STUDY


rule toy_compare:
    input:
        published="config/published/toy.yaml",
        result="results/toy/result.nc",
        code=code("linkwork.papers.toy.findings"),
    output:
        comparison_table("toy"),
        "results/toy/findings.nc",
    params:
        study="linkwork.papers.toy.findings:compare",
        cfg={},
    script:
        STUDY


REPORT_INPUTS["toy"] = paper_report("toy", result="results/toy/result.nc")
"""
    ),
    "reports/toy.py": (
        """# %% [markdown]
# # The toy paper, reproduced

# %%
from _common import answer, comparison_table, inputs, load

files = inputs()
answer("toy", load(files["findings"]), load(files["comparison"]))
comparison_table(load(files["comparison"]))
"""
    ),
    "lib/linkwork/papers/toy/statements.yaml": (
        """findings:
  - id: holds
    answer: 1
    kind: holds
    text: "It holds up: its one number, {{ ours | num }}, is ours."
    values:
      ours: {row: {id: answer}, column: reproduced}
      verdict: {row: {id: answer}, column: verdict}
    when:
      - {test: "verdict == 'reproduced'", says: "the number reproduced"}
"""
    ),
    "config/published/toy.yaml": (
        """paper: toy
quantities:
  - {id: answer, quantity: the printed number, value: 42.0, unit: "1", where: "p. 1", tolerance: {abs: 0.5},
     measure: {variable: answer, reduce: value}}
"""
    ),
}


def test_a_sixth_paper_joins_the_dag_the_index_and_the_findings_without_a_shared_edit(clone):
    """The toy paper's own files only: a dry run plans its jobs and the reports across papers, and a run puts it in the
    index and the README's findings.  No rule file names a paper in a condition."""
    shared = {p: p.read_bytes() for p in (clone / "workflow").rglob("*") if p.is_file()}
    for rel, text in TOY_PAPER.items():
        (clone / rel).parent.mkdir(parents=True, exist_ok=True)
        (clone / rel).write_text(text, encoding="utf-8")
    assert all(p.read_bytes() == data for p, data in shared.items())  # nothing shared was touched
    planned = job_listing(clone)
    assert {"toy", "toy_compare", "assumptions:toy", "report:toy", "report:index", "readme_findings"} <= {
        j.split("/")[0] for j in planned
    }, sorted(planned)
    snakemake(
        clone, "--cores", "2", "results/reports/index.html", "results/readme_findings.md", "results/reports/toy.html"
    )
    assert "Toy 2026: one printed number" in (clone / "results/readme_findings.md").read_text()
    assert "toy.html" in (clone / "results/reports/index.html").read_text()
    assert "It holds up: its one number, 42, is ours." in (clone / "results/reports/toy.html").read_text()
    assert "It holds up: its one number, 42, is ours." in (clone / "results/readme_findings.md").read_text()
    for rules in (clone / "workflow").rglob("*.smk"):
        assert "paper ==" not in rules.read_text(), rules


def test_real_run_builds_every_output(built):
    for rel in OUTPUTS:
        assert (built / rel).stat().st_size > 0, rel
    for name in REPORTS:
        html = (built / f"results/reports/{name}.html").read_text()
        assert "Traceback" not in html
        assert 'vnd.jupyter.stderr" tabindex' not in html  # no warnings or errors printed
        assert "data:image/png;base64" in html  # figures embedded (the index: its verdict matrix)
    index = (built / "results/reports/index.html").read_text()
    assert all(f"{p}.html" in index for p in ("stiffness", "beatup", "clearance", "heald", "transplanter"))
    # one row per paper (its answer and counts), then the verdict matrix of papers x published numbers per scenario
    assert index.count("Does it hold up?") + index.count("does it hold up?") >= 1
    assert "One line per paper, model variant and named scenario" in index
    for paper in ("beatup", "heald", "transplanter"):  # the best consistent assumption set per scenario is shown
        assert "rows matched at once" in (built / f"results/reports/{paper}.html").read_text(), paper


def test_reports_and_readme_findings_hold_no_code_names_in_prose(built):
    """No rendered report and no README finding shows a snake_case identifier, a config key path or an unrendered
    template in prose (tables marked as config-key listings excepted); every page title names its paper."""
    from prose import leaks, page_title, visible_text

    from linkwork.papers import PAPERS

    problems = {}
    for name in REPORTS:
        page = (built / f"results/reports/{name}.html").read_text()
        found = leaks(visible_text(page))
        title = page_title(page)
        if not title or title.lower() == "notebook":
            found.append(f"page title {title!r}")
        if found:
            problems[name] = found
    findings = (built / "results/readme_findings.md").read_text()
    if leaks(findings):
        problems["README findings"] = leaks(findings)
    assert not problems, problems
    for paper in PAPERS:  # the title names the paper: one of its title's words of five letters or more
        title = page_title((built / f"results/reports/{paper}.html").read_text()).lower()
        words = {w for w in re.findall(r"[a-z]{5,}", PAPERS[paper].lower())}
        assert words & set(re.findall(r"[a-z]{5,}", title)), (paper, title)


#: How many words a paper's answer may take: a reader takes it in at once.
ANSWER_WORDS = 60


def _labels_as_labels(text: str, labels: set[str]) -> list[str]:
    """Model-variant and scenario labels used as labels in ``text``: a phrase of several words anywhere, a one-word
    label in parentheses, after a '·' or beside 'model'/'variant', a one-letter label as a word."""
    found = []
    for label in labels:
        if not label:
            continue
        if " " in label and label.lower() in text.lower():
            found.append(label)
        elif len(label) == 1 and re.search(rf"(?<![\w'’]){re.escape(label)}(?![\w'’])", text):
            found.append(label)
        elif re.search(rf"\({re.escape(label)}\)|· {re.escape(label)}\b|\b{re.escape(label)} (model|variant)\b"
                       rf"|\b(model|variant) {re.escape(label)}\b", text, re.I):
            found.append(label)
    return found


def test_every_answer_is_short_plain_and_every_row_is_the_classifiers_own(built):
    """Each paper's answer, rendered from its generated findings as the README, the index and its report show it: at
    most ANSWER_WORDS words, no verdict-class name, no scenario or variant label used as a label, no code name; and
    every comparison row's class is what the classifier gives from the row alone (no relabelling after it)."""
    import html as html_lib

    import pandas as pd
    import xarray as xr

    from linkwork.papers import PAPERS
    from linkwork.pipeline import statements
    from linkwork.pipeline.compare import VERDICTS, reclassify
    from prose import leaks

    for paper in PAPERS:
        findings = xr.open_dataset(built / f"results/{paper}/findings.nc")
        table = pd.read_csv(built / f"results/{paper}/comparison.csv", keep_default_na=False, na_values=[""])
        rendered = statements.render(paper, findings, table)
        text = " ".join(r.text for r in sorted(rendered, key=lambda r: r.answer or 0) if r.answer is not None)
        assert 0 < len(text.split()) <= ANSWER_WORDS, (paper, len(text.split()), text)
        assert not [v for v in VERDICTS if re.search(rf"\b{re.escape(v)}\b", text, re.I)], (paper, text)
        labels = {str(x) for c in ("model", "scenario") if c in table for x in table[c].dropna().unique()}
        assert not _labels_as_labels(text, labels), (paper, _labels_as_labels(text, labels), text)
        assert not leaks(text), (paper, leaks(text))
        for row in table.to_dict("records"):
            assert reclassify(row) == row["verdict"], (paper, row["id"], row.get("scenario"), row["verdict"])
    readme = (built / "results/readme_findings.md").read_text()
    index = (built / "results/reports/index.html").read_text()
    for paper in PAPERS:  # the same answer in the README block, the index and the report
        findings = xr.open_dataset(built / f"results/{paper}/findings.nc")
        table = pd.read_csv(built / f"results/{paper}/comparison.csv", keep_default_na=False, na_values=[""])
        rendered = statements.render(paper, findings, table)
        assert statements.answer(rendered) in readme, paper
        assert statements.answer_html(rendered) in index, paper
        first = sorted((r for r in rendered if r.answer is not None), key=lambda r: r.answer)[0].text.split(". ")[0]
        page = (built / f"results/reports/{paper}.html").read_text()
        shown = " ".join(html_lib.unescape(re.sub(r"<[^>]+>", " ", page)).split())
        assert first in shown, (paper, first)


def test_pages_a_reader_moves_through(built):
    """Every page: a bar linking the index and every other report, a table of contents of its sections, every
    figure's alt text from its caption (not nbconvert's placeholder), no HTML entity shown as text (escaped twice),
    and the index's verdict picture holds every headline row of every paper's comparison table; the index is light
    without its figures."""
    import html as html_lib

    import pandas as pd

    from linkwork.papers import PAPERS

    for name in REPORTS:
        page = (built / f"results/reports/{name}.html").read_text()
        bar = re.search(r'<nav [^>]*class="site"[^>]*>(.*?)</nav>', page, re.S)
        assert bar, name
        for other in REPORTS:
            assert other == name or f'href="{other}.html"' in bar.group(1), (name, other)
        assert re.search(r'<nav [^>]*class="toc"', page), name
        for img in re.findall(r"<img\b[^>]*>", page):
            alt = re.search(r'alt="([^"]*)"', img)
            assert alt and len(alt.group(1)) > 20 and "No description" not in alt.group(1), (name, img[:80])
        shown = html_lib.unescape(re.sub(r"<[^>]+>", " ", re.sub(r"<(style|script)\b.*?</\1>", " ", page, flags=re.S)))
        assert not re.search(r"&#x?[0-9a-fA-F]+;|&[a-z]+;", shown), (name, re.findall(r".{30}&#?\w+;.{30}", shown)[:3])
    index = (built / "results/reports/index.html").read_text()
    rows = sum(
        int((pd.read_csv(built / f"results/{p}/comparison.csv").role == "headline").sum()) for p in PAPERS
    )
    assert f"{rows} cells: every headline row of the {len(PAPERS)} papers' comparison tables" in index
    assert len(re.sub(r"data:image/[a-z]+;base64,[A-Za-z0-9+/=]+", "", index).encode()) < 100_000


def test_second_run_has_nothing_to_do(built):
    assert planned_jobs(built) == {}


def test_forced_rerun_writes_identical_bytes(clone):
    """A study, a stiff (NDF) multibody scene (settled from two starts, with its check reruns) and every rendered
    report: forced again, the same bytes (the accuracy report too: rendered again from the same timings file)."""
    reports = [f"results/reports/{name}.html" for name in REPORTS]
    targets = ["results/stiffness/stiffness.nc", "results/clearance/slender/lubricated_2.nc", *reports]
    before = {p: hashlib.sha256((clone / p).read_bytes()).hexdigest() for p in targets}
    # the targets alone: not the jobs they depend on, nor the jobs a rewritten scene would otherwise pull in after it
    # (the claims, the input samples continued from it, the compare step)
    proc = snakemake(clone, "--force", "--allowed-rules", "stiffness", "clearance_scene", "report", "--", *targets)
    wrote = [line for line in proc.stdout.splitlines() if ": wrote " in line]
    assert all(any(Path(p).name in line for line in wrote) for p in targets), proc.stdout  # each job ran again
    assert {p: hashlib.sha256((clone / p).read_bytes()).hexdigest() for p in targets} == before


# --- reruns at the granularity of a config key --------------------------------------------------------

SPEC = yaml.safe_load((Path(__file__).resolve().parent / "rerun_spec.yaml").read_text())


def _ranges(pattern: str) -> list[str]:
    """Expand a numeric range ``{a..b}`` or ``{a..b..step}`` (inclusive) in a spec pattern."""
    m = re.search(r"\{(\d+)\.\.(\d+)(?:\.\.(\d+))?\}", pattern)
    if not m:
        return [pattern]
    a, b, step = int(m[1]), int(m[2]), int(m[3] or 1)
    return [q for k in range(a, b + 1, step) for q in _ranges(pattern[: m.start()] + str(k) + pattern[m.end():])]


def expected_jobs(patterns: list[str], all_jobs: list[str]) -> set[str]:
    """The job ids matching the spec's patterns (each must match at least one job; ``{a..b}`` is a numeric
    range), plus 'all'."""
    out = {"all"}
    for pattern in (q for p in patterns for q in _ranges(p)):
        hits = [j for j in all_jobs if fnmatch.fnmatchcase(j, pattern)]
        assert hits, f"spec pattern {pattern!r} matches no job"
        out.update(hits)
    return out


#: libyaml where installed: an edit test reads and writes the whole config once per row.
_LOADER, _DUMPER = getattr(yaml, "CSafeLoader", yaml.SafeLoader), getattr(yaml, "CSafeDumper", yaml.SafeDumper)


def _set_key(path: Path, key: str, value) -> None:
    cfg = yaml.load(path.read_text(), Loader=_LOADER)
    node = cfg
    *parents, last = key.split(".")
    for part in parents:
        node = node[int(part)] if isinstance(node, list) else node[part]
    if isinstance(node, list):
        last = int(last)
    assert last in (range(len(node)) if isinstance(node, list) else node), key
    assert node[last] != value, f"{key} already has the value {value!r}"
    node[last] = value
    path.write_text(yaml.dump(cfg, Dumper=_DUMPER, sort_keys=False))


def test_the_spec_covers_every_paper_the_sweeps_and_the_linkages():
    assert len(SPEC) >= 15
    assert {row["key"].split(".")[0] for row in SPEC} == {
        "stiffness",
        "beatup",
        "heald",
        "transplanter",
        "clearance",
        "sweeps",
        "linkages",
    }


def on_two_clones(built: Path, tmp_path: Path, label: str, items: list, check) -> list[str]:
    """``check(root, dry, item)`` for every item, the items split over two clones of the built copy with a dry-run
    server each (a dry run on each core); the failures it returns (None: none), merged."""
    def run(worker: int, part: list) -> list[str]:
        root = clone_of(built, tmp_path / f"{label}{worker}")
        with DryRuns(root) as dry:
            return [failure for item in part if (failure := check(root, dry, item))]

    with ThreadPoolExecutor(max_workers=2) as pool:
        return [f for part in pool.map(run, range(2), [items[0::2], items[1::2]]) for f in part]


def _mismatch(what: str, planned: set[str], expected: set[str]) -> str | None:
    if planned == expected:
        return None
    return f"{what}: extra {sorted(planned - expected)}, missing {sorted(expected - planned)}"


def test_single_key_edits_rerun_exactly_what_reads_the_key(built, declared, tmp_path):
    """Each row of tests/rerun_spec.yaml: the dry run after the edit schedules exactly the listed jobs."""
    def check(root: Path, dry: DryRuns, row: dict) -> str | None:
        config = root / "config/config.yaml"
        original = config.read_text()
        _set_key(config, row["key"], row["value"])
        try:
            planned = set(job_listing(root, dry=dry))
        finally:
            config.write_text(original)
        return _mismatch(row["key"], planned, expected_jobs(row["jobs"], list(declared)))

    failures = on_two_clones(built, tmp_path, "edits", SPEC, check)
    assert not failures, "\n".join(failures)


def test_every_report_renders_in_headless_chromium(built):
    """Each report loads in a real browser with no console error and every image decodes; screenshots kept in
    results/."""
    from browser import check_pages

    pages = sorted((built / "results/reports").glob("*.html"))
    assert {p.stem for p in pages} == set(REPORTS)
    results = check_pages(pages, PROJECT / "results" / "screenshots")
    for name, r in results.items():
        assert r["loaded"], name
        assert not r["errors"], f"{name}: {r['errors']}"
        assert r["broken_images"] == 0, f"{name}: {r['broken_images']} of {r['images']} images did not decode"
        assert r["images"] >= (0 if name == "index.html" else 1), name


def test_readme_rerun_table_is_the_spec():
    """docs/parameters.md shows the specification, row for row (generated by `python tests/rerun_spec.py`)."""
    from rerun_spec import readme_table

    readme = (PROJECT / "docs" / "parameters.md").read_text()
    assert readme_table(SPEC) in readme


# --- reruns at the granularity of a lib module ------------------------------------------------------

LIB_MODULES = sorted(str(p.relative_to(PROJECT)) for p in (PROJECT / "lib/linkwork").rglob("*.py"))


def _descendants(jobs: dict[str, dict[str, list[str]]], start: set[str]) -> set[str]:
    """``start`` and every job that consumes, directly or not, an output of a job in it."""
    producer = {out: j for j, spec in jobs.items() for out in spec["output"]}
    consumers: dict[str, set[str]] = {}
    for j, spec in jobs.items():
        for inp in spec["input"]:
            if inp in producer:
                consumers.setdefault(producer[inp], set()).add(j)
    out, todo = set(start), list(start)
    while todo:
        for nxt in consumers.get(todo.pop(), ()):
            if nxt not in out:
                out.add(nxt)
                todo.append(nxt)
    return out


def traced_modules(built: Path) -> dict[str, set[str]]:
    """Job outputs (first output) -> lib files the job's processes (and a report's kernel) loaded."""
    records = [json.loads(p.read_text()) for p in (built / "trace").glob("*.json")]
    by_pid = {r["pid"]: r for r in records}
    jobs: dict[str, set[str]] = {}
    for r in records:
        owner = r if r["outputs"] else by_pid.get(r["ppid"])
        if owner is None or not owner["outputs"]:
            continue  # the snakemake process itself, or a helper process of no job
        files = {
            str(Path(f).resolve().relative_to(built.resolve()))
            for f in r["files"]
            if f and Path(f).resolve().is_relative_to(built.resolve())
        }
        jobs.setdefault(owner["outputs"][0], set()).update(files)
    return jobs


def test_every_import_a_job_made_is_a_declared_input(built, declared):
    """The independent route: what each job really loaded at run time is inside its declared code inputs."""
    traced = traced_modules(built)
    by_output = {spec["output"][0]: (j, set(spec["input"])) for j, spec in declared.items() if spec["output"]}
    jobs_with_lib = 0
    for output, files in traced.items():
        job, inputs = by_output[output]
        missing = sorted(f for f in files if f not in inputs)
        assert not missing, f"{job} loaded {missing} without declaring them"
        jobs_with_lib += bool(files)
    assert jobs_with_lib >= len(declared) - 2  # every job but `all` ran Python that loaded linkwork


def test_every_job_computes_with_one_blas_thread(built):
    """Snakemake runs the jobs side by side, one core each: every job's processes (a report's kernel included) compute
    with one OpenBLAS thread in each library loaded (numpy's and scipy's), as the libraries themselves report it
    (the Snakefile's default; without it each library starts one thread per core, on CI's two cores two)."""
    records = [json.loads(p.read_text()) for p in (built / "trace").glob("*.json")]
    by_pid = {r["pid"]: r for r in records}
    in_jobs = [r for r in records if r["outputs"] or by_pid.get(r["ppid"], {}).get("outputs")]
    job_of = lambda r: (r["outputs"] or by_pid[r["ppid"]]["outputs"])[0]  # noqa: E731
    assert len({job_of(r) for r in in_jobs if r["blas_threads"]}) == sum(ALL_JOBS.values()) - 1  # all but `all`
    more = [(job_of(r), r["blas_threads"]) for r in in_jobs if set(r["blas_threads"].values()) - {1}]
    assert not more, more


def test_editing_any_lib_module_reruns_exactly_its_dependants(built, declared, tmp_path):
    """Edit every lib module in turn: the dry run schedules the jobs that declare it and their descendants."""
    def check(root: Path, dry: DryRuns, rel: str) -> str | None:
        path = root / rel
        text, stat = path.read_text(), path.stat()
        path.write_text(text + "\n# edited\n")
        try:
            planned = set(job_listing(root, dry=dry))
        finally:
            path.write_text(text)
            os.utime(path, ns=(stat.st_atime_ns, stat.st_mtime_ns))
        users = {j for j, spec in declared.items() if rel in spec["input"]}
        return _mismatch(rel, planned, _descendants(declared, users) | ({"all"} if users else set()))

    failures = on_two_clones(built, tmp_path, "modules", LIB_MODULES, check)
    assert not failures, "\n".join(failures)
    # the layout's promise, as examples: an engine reaches several papers, a paper reaches only itself
    users = {rel: {j.split(":")[0] for j, spec in declared.items() if rel in spec["input"]} for rel in LIB_MODULES}
    assert {"stiffness", "beatup_sixbar", "transplanter_optim", "clearance_scene"} <= users[
        "lib/linkwork/engines/kinematics.py"
    ]
    assert not {r for r in users["lib/linkwork/engines/kinematics.py"] if r.startswith("heald")}
    heald = [j for j, spec in declared.items() if "lib/linkwork/papers/heald/model.py" in spec["input"]]
    assert heald and all(
        j.startswith("heald_") or ":heald" in j for j in heald
    ), heald  # its rules, sweep and uncertainty


def test_unactivated_environment_runs_the_reports(clone):
    """`.venv/bin/snakemake` without activating the environment: the report rule finds jupytext (one report, removed
    first, rendered again)."""
    report = clone / "results/reports/stiffness.html"
    report.unlink()
    env = dict(os.environ, PATH="/usr/bin:/bin", PYTHONPATH=str(clone / "lib"))
    proc = subprocess.run(
        [str(Path(sys.executable).parent / "snakemake"), "--cores", "1", "results/reports/stiffness.html"],
        cwd=clone,
        env=env,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-3000:]
    assert "data:image/png;base64" in report.read_text()
