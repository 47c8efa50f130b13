"""Shared fixtures: the project's config, schema and published numbers."""

import copy
from functools import lru_cache
from pathlib import Path

import pytest
import yaml

PROJECT = Path(__file__).resolve().parent.parent


@lru_cache(maxsize=None)
def _parsed(rel: str):
    with open(PROJECT / rel) as fh:
        return yaml.load(fh, Loader=getattr(yaml, "CSafeLoader", yaml.SafeLoader))


def load_yaml(rel: str):
    """A project file's YAML, parsed once per test process (libyaml where installed, as lib reads config), a fresh copy
    for every caller: a test may change what it is given."""
    return copy.deepcopy(_parsed(rel))


@pytest.fixture()
def config():
    return load_yaml("config/config.yaml")


@pytest.fixture()
def schema():
    return load_yaml("config/schema.yaml")


@pytest.fixture(scope="session")
def stiffness_published():
    return load_yaml("config/published/stiffness.yaml")


#: The session's ``validation_memo`` (for helpers that take no fixture).
_SESSION: dict = {}


@pytest.fixture(scope="session", autouse=True)
def validation_memo(tmp_path_factory):
    """Where validate_config's physical checks remember a pass, as the Snakefile's validation does: a check runs again
    only on a section or code it has not passed (the heald check follows its linkage through the turn, about a second
    per run).  A bad section is never remembered: its check raises every time."""
    from linkwork.project.validate import Memo

    _SESSION["memo"] = Memo(tmp_path_factory.mktemp("validated"), PROJECT / "lib")
    return _SESSION["memo"]


def expect_config_error(config, schema, *fragments):
    """validate_config must fail with a message containing every fragment."""
    from linkwork.pipeline.errors import ConfigError
    from linkwork.project.validate import validate_config

    with pytest.raises(ConfigError) as info:
        validate_config(config, schema, _SESSION.get("memo"))
    for fragment in fragments:
        assert fragment in str(info.value), str(info.value)


def assert_rhs_solves_the_numpy_equations(
    linkage,
    gravity: bool,
    times,
    position_noise: float,
    rate_noise: float,
    seed: int,
    states: int = 10,
    driver_row: int | None = None,
) -> None:
    """At perturbed states of a linkage (random times in ``times``): the compiled right-hand side's accelerations
    satisfy M q'' = g - Phi_q^T lam and Phi_q q'' = gamma - 2 a Phi' - b^2 Phi, with Phi, Phi_q, gamma and g (gravity,
    springs) written independently in numpy (``engines.multibody.assembly``); with ``driver_row``, the driver's power is
    -lam[driver_row] times the driven body's rate."""
    import numpy as np

    from linkwork.engines.multibody import assembly
    from linkwork.engines.multibody.model import compile_scene, pack

    module = compile_scene(linkage, gravity)
    params, _ = pack(linkage)
    rng = np.random.default_rng(seed)
    y0 = assembly.start_state(linkage)
    nq = linkage.n_coordinates
    mass = assembly.mass_vector(linkage)
    driven = 3 * linkage.body_index(linkage.driver.body) + 2
    for _ in range(states):
        y = y0 + np.r_[rng.normal(0, position_noise, nq), rng.normal(0, rate_noise, nq), 0.0]
        t = rng.uniform(*times)
        out = module.rhs(t, y, params, np.zeros(1), np.zeros(4, dtype=np.int64), np.zeros(module.N_DIAG))
        q, qd, qdd = y[None, :nq], y[None, nq : 2 * nq], out[nq : 2 * nq]
        phi, jac, nu = assembly.constraints(linkage, q, np.array([t]))
        gamma = assembly.gamma_of(linkage, q, qd, np.array([t]))[0]
        rate = jac[0] @ qd[0] - nu[0]
        b = linkage.baumgarte
        assert np.allclose(
            jac[0] @ qdd, gamma - 2 * b * rate - b * b * phi[0], rtol=1e-8, atol=1e-8 * np.abs(gamma).max()
        )
        g = assembly.applied_forces(linkage, q, gravity, qd)[0][0]
        lam = np.linalg.lstsq(jac[0].T, g - mass * qdd, rcond=None)[0]
        assert np.allclose(jac[0].T @ lam, g - mass * qdd, atol=1e-8 * max(np.abs(mass * qdd).max(), np.abs(g).max()))
        if driver_row is not None:
            assert out[2 * nq] == pytest.approx(-lam[driver_row] * qd[0, driven], rel=1e-8)


# One line per hard case, printed at the end of every test run: what was pushed, which invariant held.
HARD_CASES = {
    "test_change_point_linkage_passes_its_singular_position": (
        "four-bar with s + l = p + q through its collinear position",
        "loop closure <= 1e-12, rates flagged NaN only there",
    ),
    "test_crank_at_toggle_positions": (
        "crank exactly at the crank-coupler toggles",
        "rocker rate 0 to 1e-12, rocker angle extreme",
    ),
    "test_lengths_at_the_edge_of_assembly": (
        "triple rocker exactly at its limit angle, then 1e-6 rad beyond",
        "exact closure at the limit, clear error beyond",
    ),
    "test_exactly_at_a_resonance": (
        "chain solved exactly at an undamped velocity resonance",
        "flagged singular, no exception; finite with damping",
    ),
    "test_zero_clearance_recovers_the_ideal_joint": (
        "Vulfson clearance 1e-15 m; a 1e10 N/m pin",
        "ideal joint recovered; rigid limit by w^2 m / k",
    ),
    "test_vulfson_limits_without_division_errors": (
        "|R| = 0 and clearance = 0 in Vulfson's k_tau",
        "no division error (errors raised on any float fault)",
    ),
    "test_low_frequency_limit": (
        "chain at w = 1e-6 rad/s; w = 0 refused",
        "static warp load through levers and joints, to 1e-6",
    ),
    "test_clearance_1_micron_and_1_mm": (
        "radial clearance 1 um and 1 mm",
        "constraint drift < 1e-6 m, penetration bounded",
    ),
    "test_crank_speed_times_ten": ("crank speed x10 (6000 rev/min)", "finite response, constraint drift < 1e-6 m"),
    "test_restitution_one_does_not_create_energy": (
        "restitution 1.0, no friction",
        "energy minus driver work does not grow",
    ),
    "test_restitution_0_3_dissipates": ("restitution 0.3", "energy minus driver work falls"),
    "test_lubrication_driven_to_eps_one": (
        "oil too thin to hold the journal (eps -> 1 and beyond)",
        "film force finite and bounded, contact takes over",
    ),
    "test_friction_at_zero_slip": ("tangential slip exactly 0, friction 0.3", "no NaN, drift < 1e-6 m"),
    "test_journal_starting_in_contact": (
        "journal of joint 1 starting pressed into its bushing",
        "finite response, drift < 1e-6 m",
    ),
    "test_every_diameter_at_the_minimum": (
        "every transplanter diameter at 4 mm",
        "finite KED response, over-stress reported",
    ),
    "test_crank_speed_near_the_first_natural_frequency": (
        "crank speed at the first natural frequency",
        "dynamic response below the 1/(2 zeta) amplification, warning set",
    ),
    "test_optimiser_from_an_infeasible_start_ends_feasible": (
        "SUMT started at 3 mm diameters (infeasible)",
        "optimum satisfies every constraint",
    ),
}


def pytest_terminal_summary(terminalreporter):
    lines = []
    for report in terminalreporter.stats.get("passed", []) + terminalreporter.stats.get("failed", []):
        if report.when != "call" or "hard" not in report.keywords:
            continue
        name = report.nodeid.split("::")[-1].split("[")[0]
        pushed, held = HARD_CASES.get(name, ("(undescribed)", "(undescribed)"))
        status = "held" if report.passed else "FAILED"
        lines.append(f"hard: {report.nodeid.split('::')[-1]}: pushed {pushed}; {status}: {held}")
    if lines:
        terminalreporter.write_sep("-", f"hard cases ({len(lines)})")
        for line in lines:
            terminalreporter.write_line(line)


def pytest_collection_modifyitems(items):
    """The workflow files (test_workflow*.py) first, the order kept otherwise: under `make test` (two workers, one
    file each, in collection order: --no-loadscope-reorder) the Snakemake build, the longest file, starts at once
    instead of last."""
    items.sort(key=lambda item: not item.path.name.startswith("test_workflow"))


def render_stiffness_page(tmp_path, cfg, check_figures: bool = True):
    """The stiffness report rendered by render_report from results computed here with ``cfg`` (its config section):
    (the page's HTML, the comparison table, the findings Dataset)."""
    import os
    import subprocess
    import sys

    from linkwork.papers.stiffness.findings import compare
    from linkwork.papers.stiffness.studies import stiffness
    from linkwork.pipeline import results

    ds = stiffness(cfg)
    ds.attrs.update(results.provenance("stiffness", cfg, study="linkwork.papers.stiffness.studies:stiffness"))
    table, fnd = compare(cfg, load_yaml("config/published/stiffness.yaml"), ds)
    results.write(ds, tmp_path / "stiffness.nc")
    results.write(fnd, tmp_path / "findings.nc")
    table.to_csv(tmp_path / "comparison.csv", index=False)
    inputs = {
        "result": tmp_path / "stiffness.nc",
        "findings": tmp_path / "findings.nc",
        "comparison": tmp_path / "comparison.csv",
        "published": Path("config/published/stiffness.yaml").resolve(),
    }
    out = tmp_path / "stiffness.html"
    args = [a for k, v in inputs.items() for a in ("--input", f"{k}={v}")]
    env = {**os.environ, **({"LINKWORK_CHECK_FIGURES": "1"} if check_figures else {})}
    proc = subprocess.run(
        [sys.executable, "workflow/scripts/render_report.py", "reports/stiffness.py", str(out), *args],
        env=env, capture_output=True, text=True, timeout=600,
    )
    assert proc.returncode == 0, proc.stderr[-3000:]
    return out.read_text(), table, fnd

