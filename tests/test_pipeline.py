"""Pipeline plumbing: narrow config values, import closures, config reading, validation memo, sweeps, text."""

import copy
import os
import textwrap
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml

from conftest import PROJECT, load_yaml
from linkwork.configformat import get_path, labelled, pick
from linkwork.pipeline.compare import where_true
from linkwork.pipeline.deps import closure
from linkwork.pipeline.errors import ConfigError
from linkwork.pipeline.sweeps import gather, grid, point_dataset
from linkwork.project.validate import load_yaml as read_config
from linkwork.project.validate import merge_overrides, validate_once


def test_pick_copies_exactly_the_named_paths():
    section = {"a": {"b": 1, "c": [2, 3]}, "d": 4, "e": {"f": {"g": 5}}}
    out = pick(section, ["a.c", "e.f.g"])
    assert out == {"a": {"c": [2, 3]}, "e": {"f": {"g": 5}}}
    out["a"]["c"].append(9)
    assert section["a"]["c"] == [2, 3]  # a deep copy
    with pytest.raises(KeyError, match="a.x"):
        pick(section, ["a.x"])
    assert get_path(section, "e.f") == {"g": 5}
    assert labelled({"value": 2, "status": "assumed", "reason": "r"}) == 2.0


def _package(tmp_path: Path) -> Path:
    """A small package ``linkwork`` with absolute, relative, lazy and 'from package import module' imports."""
    lib = tmp_path / "lib"
    files = {
        "linkwork/__init__.py": "",
        "linkwork/a.py": "from . import b\nfrom .sub import c as cc\n",
        "linkwork/b.py": "import numpy as np\n",
        "linkwork/sub/__init__.py": "",
        "linkwork/sub/c.py": "def f():\n    from ..d import g\n    return g\n",
        "linkwork/d.py": "from linkwork.e import (\n    x,\n    y,\n)\n",
        "linkwork/e.py": '"""Not an import: from the paper we import nothing."""\n',
        "linkwork/unused.py": "",
    }
    for rel, text in files.items():
        (lib / rel).parent.mkdir(parents=True, exist_ok=True)
        (lib / rel).write_text(text)
    (tmp_path / "reports").mkdir()
    (tmp_path / "reports/_helper.py").write_text("import linkwork.b\n")
    (tmp_path / "reports/r.py").write_text("from _helper import x\nimport pandas\n")
    return lib


def test_closure_follows_every_kind_of_import(tmp_path):
    lib = _package(tmp_path)
    names = {str(p.relative_to(tmp_path)) for p in closure("linkwork.a", lib)}
    assert names == {
        f"lib/linkwork/{n}" for n in ("__init__.py", "a.py", "b.py", "sub/__init__.py", "sub/c.py", "d.py", "e.py")
    }
    # an entry given by name brings its parent packages (they run when it is imported)
    assert {str(p.relative_to(tmp_path)) for p in closure("linkwork.sub.c", lib)} >= {
        "lib/linkwork/__init__.py",
        "lib/linkwork/sub/__init__.py",
    }
    report = {str(p.relative_to(tmp_path)) for p in closure(tmp_path / "reports/r.py", lib)}
    assert report == {"reports/r.py", "reports/_helper.py", "lib/linkwork/__init__.py", "lib/linkwork/b.py"}


def test_closure_of_the_real_studies_keeps_papers_apart():
    lib = PROJECT / "lib"
    for paper in ("stiffness", "beatup", "clearance", "transplanter", "heald"):
        files = {str(p.relative_to(lib)) for p in closure(f"linkwork.papers.{paper}.studies", lib)}
        others = {
            f for f in files if f.startswith("linkwork/papers/") and f.count("/") == 3 and f.split("/")[2] != paper
        }
        assert not others, f"{paper} reaches {others}"
    heald = {str(p.relative_to(lib)) for p in closure("linkwork.papers.heald.studies", lib)}
    assert "linkwork/engines/kinematics.py" not in heald and "linkwork/engines/chains.py" in heald


def test_config_reader_names_duplicate_keys_and_syntax_errors(tmp_path):
    path = tmp_path / "c.yaml"
    path.write_text("a:\n  b: 1\n  b: 2\n")
    with pytest.raises(ConfigError, match=r"c.yaml, line 3: config key 'b' is given twice .*first at line 2"):
        read_config(path)
    path.write_text("a: [1, 2\nb: 3\n")
    with pytest.raises(ConfigError, match=r"c.yaml, line \d+, column \d+: not valid YAML"):
        read_config(path)
    path.write_text("a: {b: 1.0e-6, c: 1e-6}\n")
    assert read_config(path) == {"a": {"b": 1e-6, "c": "1e-6"}}  # PyYAML's rule, caught later by the schema


def test_command_line_values_override_the_file_key_by_key():
    config = {"clearance": {"joints": {"friction": 0.3}}, "new": 1}
    merge_overrides(config, {"clearance": {"joints": {"friction": 0.001, "restitution": 0.9}, "ground_m": 0.4}})
    assert config == {"clearance": {"joints": {"friction": 0.3, "restitution": 0.9}, "ground_m": 0.4}, "new": 1}


def test_validation_is_remembered_only_for_the_same_config(tmp_path, config):
    stamp = tmp_path / "stamp"
    lib, schema = PROJECT / "lib", PROJECT / "config/schema.yaml"
    validate_once(config, schema, lib, stamp)
    key = stamp.read_text()
    validate_once(config, schema, lib, stamp)  # remembered
    assert stamp.read_text() == key
    bad = copy.deepcopy(config)
    bad["stiffness"]["linkage"]["crank_m"] = -1.0
    with pytest.raises(ConfigError, match="stiffness.linkage.crank_m"):
        validate_once(bad, schema, lib, stamp)
    assert stamp.read_text() == key  # a failed validation leaves the memo as it was


def test_sweep_grid_and_gather_fill_every_cell_once():
    axes = {"clearance_m": [1e-5, 2e-5], "crank_speed_rad_s": [10.0, 20.0, 30.0]}
    points = grid(axes)
    assert len(points) == 6 and points[1] == {"clearance_m": 1e-5, "crank_speed_rad_s": 20.0}
    outputs = {"y": ("N", "a force")}
    datasets = [point_dataset(p, {"y": p["clearance_m"] * p["crank_speed_rad_s"]}, outputs) for p in points]
    out = gather(axes, datasets)
    assert np.allclose(out.y.values, np.outer(axes["clearance_m"], axes["crank_speed_rad_s"]))
    with pytest.raises(ValueError, match="once each"):
        gather(axes, datasets[:-1] + datasets[:1])


def test_where_true_names_sub_ranges():
    x = np.array([1.0, 2.0, 3.0, 4.0, 5.0])
    assert where_true(x, [True] * 5) == "all of 1–5"
    assert where_true(x, [False] * 5) == "none of 1–5"
    assert where_true(x, [True, True, False, True, False]) == "1–2, 4–4"


def test_every_lib_module_docstring_and_no_paper_imports_another():
    lib = PROJECT / "lib/linkwork"
    for path in lib.rglob("*.py"):
        text = path.read_text()
        assert text.lstrip().startswith('"""'), f"{path} has no module docstring"
        rel = path.relative_to(lib).parts
        if rel[0] == "papers" and len(rel) == 3:
            for other in ("stiffness", "beatup", "clearance", "transplanter", "heald"):
                if other != rel[1]:
                    assert (
                        f"papers.{other}" not in text and f"from ..{other}" not in text
                    ), f"{path} imports paper {other}"
        if rel[0] == "engines":
            assert (
                "papers" not in text.split('"""', 2)[-1] and "pipeline" not in text.split('"""', 2)[-1]
            ), f"engine {path} imports a paper or the pipeline"


def test_results_load_names_the_file_and_the_rebuild_command(tmp_path):
    from linkwork.pipeline.results import UnreadableResult, load, write

    path = tmp_path / "r.nc"
    write(xr.Dataset({"a": ((), 1.0, {"units": "1", "long_name": "a"})}), path)
    assert float(load(path).a) == 1.0
    path.write_bytes(path.read_bytes()[:100])
    with pytest.raises(UnreadableResult, match=rf"cannot read {path}.*snakemake --force {path}"):
        load(path)


def test_units_are_one_home():
    """rpm, gravity and degree conversions are defined once, in linkwork.units."""
    lib = PROJECT / "lib/linkwork"
    for path in lib.rglob("*.py"):
        if path.name == "units.py":
            continue
        text = path.read_text()
        assert "9.80665" not in text, path
        assert "2 * np.pi / 60" not in text and "2.0 * np.pi / 60" not in text, path


def test_scene_keys_follow_the_effects():
    from linkwork.papers.clearance.adapter import parameters, scene_keys

    section = load_yaml("config/config.yaml")["clearance"]
    section["scenes"]["film_only"] = {
        "clearance_joints": [1],
        "effects": ["lubrication", "contact", "gravity"],
        "integrator": "stiff",
    }
    dry = scene_keys(section, "slender", "dry_1")
    lub = scene_keys(section, "slender", "lubricated_1")
    film_only = scene_keys(section, "slender", "film_only")
    ideal = scene_keys(section, "decoded", "ideal")
    assert (
        "joints.friction" in dry
        and "joints.friction" in lub
        and "joints.friction" not in film_only
        and "joints.friction" not in ideal
    )
    assert "assumed.v0_m_s" in lub and "assumed.v0_m_s" not in film_only
    assert "joints.viscosity_Pa_s" in lub and "joints.viscosity_Pa_s" not in dry
    assert not any(k.startswith("integrators") for k in ideal) and "integrators.explicit" in dry
    assert "bodies.crank.inertia_kg_m2" in ideal and "bodies.crank.inertia_kg_m2" not in dry  # slender computes J
    p = parameters(pick(section, dry), "slender", "dry_1")
    assert np.isnan(p.viscosity) and p.friction == section["joints"]["friction"]


def test_no_report_or_script_is_left_over_from_the_flat_layout():
    assert not os.path.exists(PROJECT / "lib/linkwork/from_config.py")
    for path in list((PROJECT / "reports").glob("*.py")) + list((PROJECT / "workflow/scripts").glob("*.py")):
        text = path.read_text()
        assert "report_context" not in text and "linkwork.config " not in text, path


@pytest.mark.parametrize(
    "name", ["stiffness", "beatup", "heald", "transplanter", "clearance", "accuracy", "sweeps", "index"]
)
def test_reports_only_load_and_format(name):
    """A report imports presentation helpers only, never a numerical lib module, and holds no reductions of results."""
    text = (PROJECT / "reports" / f"{name}.py").read_text()
    imports = [line for line in text.splitlines() if line.startswith(("import ", "from "))]
    allowed = (
        "import json",
        "import textwrap",
        "import matplotlib.pyplot as plt",
        "from matplotlib.patches import",
        "import numpy as np",
        "import pandas as pd",
        "from _common import",
        "from linkwork.papers import PAPERS",
        f"from linkwork.papers.{name} import CITATION",
        # presentation constants: the verdict classes' names and meanings, the clearance paper's words for its code
        # names
        "from linkwork.pipeline.compare import VERDICT",
        "from linkwork.papers.clearance.words import",
        "from linkwork.units import",
    )  # unit conversions at the report's boundary
    assert all(line.startswith(allowed) for line in imports), imports
    for reduction in (".max()", ".min()", ".mean()", "np.mean(", "np.median(", "np.abs(", "np.interp(", "np.polyfit("):
        assert reduction not in text, f"reports/{name}.py computes {reduction}"
    textwrap.dedent(text)  # (readable as a script)


@pytest.mark.parametrize(
    "name", ["stiffness", "beatup", "heald", "transplanter", "clearance", "accuracy", "sweeps", "index"]
)
def test_only_the_declared_reports_show_wall_times(name):
    """Wall times reach a report only through a timings side file: a report outside MEASURED_REPORTS neither
    names one in its rule inputs nor reads one, so it renders to the same bytes on every rerun."""
    from linkwork.pipeline.fingerprint import MEASURED_REPORTS

    script = (PROJECT / "reports" / f"{name}.py").read_text()
    rules = "\n".join(p.read_text() for p in sorted((PROJECT / "workflow" / "rules").glob("*.smk")))
    entry = f'REPORT_INPUTS["{name}"] = '  # each report's inputs are registered once (a paper's by its own rule file)
    assert rules.count(entry) == 1, name
    block = rules[rules.index(entry):].split("\n\n", 1)[0]  # the registration up to the next blank line
    reads = "timings" in script or "time_s" in script or "timings" in block
    assert reads == (
        name in MEASURED_REPORTS
    ), f"reports/{name}.py: reads wall times {reads}, declared {name in MEASURED_REPORTS}"


def test_fingerprints_split_measured_reports_from_results(tmp_path):
    """A changed netCDF file is a difference that must not happen; a changed measured report is allowed; a file
    present in one run only is named."""
    from linkwork.pipeline.fingerprint import compare, fingerprints

    (tmp_path / "results/reports").mkdir(parents=True)
    (tmp_path / "results/a").mkdir()
    for rel, text in {
        "results/a/x.nc": "1",
        "results/reports/accuracy.html": "t=1",
        "results/reports/beatup.html": "b",
    }.items():
        (tmp_path / rel).write_text(text)
    first = fingerprints(tmp_path)
    assert sorted(first) == ["results/a/x.nc", "results/reports/accuracy.html", "results/reports/beatup.html"]
    (tmp_path / "results/reports/accuracy.html").write_text("t=2")
    assert compare(first, fingerprints(tmp_path)) == {
        "identical": ["results/a/x.nc", "results/reports/beatup.html"],
        "measured": ["results/reports/accuracy.html"],
        "differing": [],
        "missing": [],
    }
    (tmp_path / "results/reports/beatup.html").write_text("c")
    (tmp_path / "results/a/x.nc").unlink()
    split = compare(first, fingerprints(tmp_path))
    assert split["differing"] == ["results/reports/beatup.html"] and split["missing"] == ["results/a/x.nc"]


def test_readme_measured_figures_are_rendered_from_the_benchmark_files():
    """The measured figures (docs/measured.md) are exactly what benchmarks/readme.py renders from benchmarks/measured/
    (so none is typed by hand), and every benchmark script has its file there."""
    import importlib.util

    spec = importlib.util.spec_from_file_location("bench_readme", PROJECT / "benchmarks" / "readme.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    block = module.render()
    assert (
        block in (PROJECT / "docs" / "measured.md").read_text()
    ), "run `python benchmarks/readme.py` after a benchmark"
    for name in module.SECTIONS:
        assert (PROJECT / "benchmarks" / "measured" / f"{name}.json").exists(), name


def test_readme_findings_carry_the_fingerprint_of_these_sources():
    """The README's findings were written by `make readme` from a run of exactly this checkout's sources (code,
    config, published numbers, pins): any change of them since fails here until `make readme` runs again."""
    from linkwork.project.readme import sources_fingerprint, stamped_fingerprint

    stamped = stamped_fingerprint((PROJECT / "README.md").read_text(encoding="utf-8"))
    assert stamped is not None, "the README's findings carry no sources stamp: run `make readme`"
    assert stamped == sources_fingerprint(PROJECT), (
        "the sources changed since the README's findings were computed: run `make readme` (a full run)"
    )


def test_the_sources_fingerprint_moves_with_code_config_and_pins_and_not_with_tests_or_docs(tmp_path):
    """Each kind of source edited in a small tree moves the fingerprint; tests, docs, results and the README do
    not."""
    from linkwork.project.readme import sources_fingerprint

    files = {
        "Snakefile": "x", "constraints.txt": "numpy==2.0", "pyproject.toml": "[p]", "config/config.yaml": "a: 1",
        "config/published/p.yaml": "b: 2", "lib/linkwork/m.py": "c = 3", "lib/linkwork/sub/n.py": "d = 4",
        "workflow/rules/r.smk": "rule r:", "workflow/scripts/s.py": "e = 5",
        "tests/test_t.py": "f = 6", "docs/d.md": "g", "results/r.nc": "h", "README.md": "i",
    }
    for rel, text in files.items():
        (tmp_path / rel).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / rel).write_text(text)
    base = sources_fingerprint(tmp_path)
    for rel in files:
        original = (tmp_path / rel).read_text()
        (tmp_path / rel).write_text(original + " ")
        moved = sources_fingerprint(tmp_path) != base
        (tmp_path / rel).write_text(original)
        assert moved == (rel.split("/")[0] not in ("tests", "docs", "results", "README.md")), rel
    (tmp_path / "lib/linkwork/m.py").rename(tmp_path / "lib/linkwork/m2.py")  # a renamed module moves it too
    assert sources_fingerprint(tmp_path) != base


def test_the_readme_check_names_a_changed_number_and_a_changed_word():
    from linkwork.project.readme import END, START, differences, stamp

    fresh = f"{START}\n\nK max 3.4600e+06 N/m, verdict differs\n\n{END}"
    readme = f"intro\n{START}\n{stamp('0' * 64)}\n\nK max 3.4601e+06 N/m, verdict differs\n\n{END}\nend"
    assert differences(readme, fresh) == []  # within 1e-3, the stamp ignored
    changed = differences(readme.replace("3.4601e+06", "3.5e+06"), fresh)
    assert changed == ["README 3.5e+06 against this run's 3.4600e+06"]
    assert differences(readme.replace("differs", "reproduced"), fresh) == ["the findings differ in words"]


def _workflow_rules() -> tuple[set[str], set[str]]:
    """(every rule of the workflow, the rules declared local), read from the rule files."""
    import re

    text = "\n".join(p.read_text() for p in sorted((PROJECT / "workflow" / "rules").glob("*.smk")))
    rules = set(re.findall(r"^rule (\w+):", text, flags=re.M))
    block = re.search(r"^localrules:\n((?:    .*\n?)+)", text, flags=re.M)
    local = {name.strip() for name in block.group(1).replace("\n", " ").split(",") if name.strip()} if block else set()
    return rules | {"all"}, local


def test_slurm_profile_requests_cover_the_measured_jobs():
    """Every rule that is submitted (not local) has a memory, run-time and core request in profiles/slurm, and
    the requests leave room over the measured peak memory (1.5x) and longest wall time (5x) of its jobs in a
    full run (benchmarks/measured/job_resources.json); the local rules exist and each measured one is short."""
    import json

    profile = yaml.safe_load((PROJECT / "profiles" / "slurm" / "config.yaml").read_text())
    measured = json.loads((PROJECT / "benchmarks" / "measured" / "job_resources.json").read_text())["rules"]
    rules, local = _workflow_rules()
    assert local <= rules, local - rules
    requests = profile["set-resources"]
    assert set(requests) == rules - local, (set(requests) ^ (rules - local))
    for rule, req in requests.items():
        assert {"mem_mb", "runtime", "cpus_per_task"} <= set(req), rule
        if rule in measured:
            assert req["mem_mb"] >= 1.5 * measured[rule]["max_rss_mb"], rule
            assert req["runtime"] * 60 >= 5 * measured[rule]["max_wall_s"], rule
    for rule in local & set(measured):
        assert (
            measured[rule]["max_wall_s"] < 5.0
        ), f"{rule} runs on the submitting host but took {measured[rule]['max_wall_s']:.1f} s"
    assert not set(
        profile.get("default-resources", [])
    ), "site settings (partition, account) belong to a profile of the user's"


def test_slurm_profile_sets_no_site():
    """The shipped profile names no partition, account or cluster: the cluster's defaults apply."""
    text = (PROJECT / "profiles" / "slurm" / "config.yaml").read_text()
    for key in ("slurm_partition", "slurm_account", "clusters", "slurm_cluster"):
        assert all(key not in line.split("#")[0] for line in text.splitlines()), key


@pytest.mark.parametrize("outside", [False, True])
def test_the_figure_check_stops_a_render_that_draws_outside_the_canvas(tmp_path, outside):
    """render_report draws each figure once at its own size; with LINKWORK_CHECK_FIGURES=1 a figure whose text
    lies beyond its canvas (here a label at x = 1.6 of the axes) fails the render, naming the figure."""
    import subprocess
    import sys

    x = 1.6 if outside else 0.5
    notebook = tmp_path / "tiny.py"
    notebook.write_text(textwrap.dedent(f"""\
        # %%
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(3, 2), layout="constrained")
        ax.set_title("probe")
        ax.text({x}, 0.5, "a label", transform=ax.transAxes)
        plt.show()
        """))
    env = {**os.environ, "LINKWORK_CHECK_FIGURES": "1"}
    proc = subprocess.run(
        [
            sys.executable, str(PROJECT / "workflow/scripts/render_report.py"), str(notebook),
            str(tmp_path / "tiny.html"),
        ],
        env=env,
        capture_output=True,
        text=True,
        timeout=300,
    )
    if outside:
        assert proc.returncode != 0 and "figure 'probe' draws over" in proc.stderr, proc.stderr[-2000:]
        assert not (tmp_path / "tiny.html").exists()
    else:
        assert proc.returncode == 0, proc.stderr[-2000:]
        assert (
            "data:image/png;base64" in (tmp_path / "tiny.html").read_text()
            or "image/png" in (tmp_path / "tiny.html").read_text()
        )


def labelled_section() -> dict:
    """A config section with a labelled range and a labelled choice (a fresh copy per call)."""
    return {
        "fe": {
            "damping_ratio": {"value": 0.02, "status": "assumed", "reason": "r", "range": [0.01, 0.05],
                              "range_reason": "rr"},
            "steps": 3,
        },
        "gravity": {"value": 0.0, "status": "assumed", "reason": "g", "choices": [0.0, 9.8],
                    "choice_labels": ["off", "on"]},
    }


def test_values_only_strips_labels_but_keeps_what_a_rule_names():
    """A study receives values: a labelled entry keeps its value (and only the label fields a rule names)."""
    from linkwork.configformat import labelled_entries, values_only

    section = labelled_section()
    out = values_only(section)
    assert out == {"fe": {"damping_ratio": {"value": 0.02}, "steps": 3}, "gravity": {"value": 0.0}}
    assert values_only(section, keep=["fe.damping_ratio.range"])["fe"]["damping_ratio"] == {
        "value": 0.02,
        "range": [0.01, 0.05],
    }
    assert section["fe"]["damping_ratio"]["reason"] == "r"  # a copy: the config is untouched
    assert list(labelled_entries(section)) == ["fe.damping_ratio", "gravity"]
    assert labelled_entries(section)["gravity"]["choice_labels"] == ["off", "on"]


def test_a_rules_params_change_with_a_reason_only_where_the_rule_names_it():
    """narrow: a rule's params are values; a reason edit leaves them equal, a range edit changes them only where the
    rule names the range or takes the design fields (the uncertainty design); the choices travel with the design."""
    import copy

    from linkwork.configformat import DESIGN_FIELDS, narrow

    section = labelled_section()
    edited = copy.deepcopy(section)
    edited["fe"]["damping_ratio"]["reason"] = "another reason"
    edited["gravity"]["reason"] = "another reason"
    ranged = copy.deepcopy(section)
    ranged["fe"]["damping_ratio"]["range"] = [0.01, 0.06]
    for paths in (["fe", "gravity"], ["fe.damping_ratio", "fe.damping_ratio.range"]):
        for fields in ((), DESIGN_FIELDS):
            assert narrow(edited, paths, fields) == narrow(section, paths, fields)  # a reason reaches no study
    assert narrow(ranged, ["fe", "gravity"]) == narrow(section, ["fe", "gravity"])
    assert narrow(ranged, ["fe.damping_ratio", "fe.damping_ratio.range"]) != narrow(
        section, ["fe.damping_ratio", "fe.damping_ratio.range"]
    )
    design = narrow(section, ["fe", "gravity"], DESIGN_FIELDS)
    assert design["gravity"] == {"value": 0.0, "choices": [0.0, 9.8], "choice_labels": ["off", "on"]}
    assert design["fe"]["damping_ratio"] == {"value": 0.02, "range": [0.01, 0.05]}


def test_assumptions_hold_every_labelled_entry_whole():
    from linkwork.pipeline.assumptions import assumptions

    section = {
        "a": {"value": 1.0, "status": "sourced", "reason": "printed"},
        "b": {"c": {"value": 0.02, "status": "assumed", "reason": "r", "range": [0.01, 0.05], "range_reason": "rr"}},
        "g": {
            "value": 0.0,
            "status": "assumed",
            "reason": "g",
            "choices": [0.0, 9.8],
            "choice_labels": ["gravity off", "gravity on"],
        },
        "n": 3,
    }
    ds = assumptions(section)
    assert list(ds.entry.values) == ["a", "b.c", "g"]
    assert list(ds.range.values) == ["", "0.01–0.05", "gravity off / gravity on"]
    assert list(ds.reason.values) == ["printed", "r", "g"] and ds.range_reason.values[1] == "rr"


def test_papers_are_found_by_their_packages_and_a_module_reading_them_depends_on_each(tmp_path):
    """A package with TITLE, CITATION and ORDER in its __init__ is a paper, in ORDER; a paper's own modules do not
    import its siblings, and a module that reads PAPERS has every paper's __init__ in its import closure."""
    import subprocess
    import sys

    from linkwork.papers import CITATIONS, PAPERS

    assert list(PAPERS) == ["stiffness", "beatup", "clearance", "transplanter", "heald"] and set(CITATIONS) == set(
        PAPERS
    )
    probe = (
        "import sys, linkwork.papers.stiffness.studies; print(sorted(m for m in sys.modules if m.count('.') == 2 and"
        " m.startswith('linkwork.papers.')))"
    )
    out = subprocess.run(
        [sys.executable, "-c", probe], env={**os.environ, "PYTHONPATH": str(PROJECT / "lib")}, capture_output=True,
        text=True, check=True,
    )
    assert out.stdout.strip() == "['linkwork.papers.stiffness']"
    lib = PROJECT / "lib"
    readme = {str(p.relative_to(lib)) for p in closure("linkwork.project.readme", lib)}
    assert {f"linkwork/papers/{p}/__init__.py" for p in PAPERS} <= readme


def test_daemon_timers_let_a_process_end_before_its_pending_timers_fire():
    """The Snakefile's daemon_timers: a process with an hour-long timer pending (as the scheduler's re-evaluation under
    the default profile's job-rate limit) ends at once; without it, the same process waits for the timer (checked with
    a short one, so that the test shows the wait it prevents)."""
    import subprocess
    import sys
    import time

    def run(patch: bool, delay: float) -> float:
        code = (
            "import threading\n"
            + ("from linkwork.pipeline.scheduler import daemon_timers\ndaemon_timers()\n" if patch else "")
            + f"threading.Timer({delay}, print).start()\n"
        )
        t0 = time.perf_counter()
        subprocess.run([sys.executable, "-c", code], check=True, timeout=60)
        return time.perf_counter() - t0

    assert run(True, 3600.0) < 30.0
    assert run(False, 3.0) >= 3.0
