"""The clearance work-precision study's error in the dry scene (the journal eccentricity over the first impacts,
relative to the clearance): a reference floor below the errors it ranks, convergence with the tolerance, a start moved
by a nanometre read as a small change, and the pipeline's setting of each kind of scene in the accuracy summary."""

import copy
from functools import lru_cache

import numpy as np
import pytest

from conftest import load_yaml
from linkwork.papers.clearance.fourbar import initial_state, integrate
from linkwork.papers.clearance.accuracy import (
    _setting, contact_error, eccentricity, is_dry, setting_label, work_precision,
)
from linkwork.papers.clearance.adapter import parameters, scene_effects
from linkwork.papers.clearance.studies import cycle
from linkwork.pipeline.accuracy import collect, highlights

SECTION = load_yaml("config/config.yaml")["clearance"]
WP = SECTION["work_precision"]
DRY = next(s for s in WP["scenes"] if is_dry(SECTION["scenes"][s]["effects"]))
LUBRICATED = next(s for s in WP["scenes"] if not is_dry(SECTION["scenes"][s]["effects"]))
P = parameters(SECTION, WP["variant"], DRY)
JOINTS, EFFECTS = scene_effects(SECTION, DRY)
T = np.linspace(0.0, WP["cycles"] * cycle(P), int(WP["cycles"] * WP["points_per_cycle"]) + 1)
WINDOW_S = WP["dry_error_window_cycles"] * cycle(P)
REF = WP["reference"][DRY]


@lru_cache(maxsize=None)
def states(method: str, value: float, offset: tuple[float, float] = (0.0, 0.0)) -> np.ndarray:
    """The dry scene's states at the study's samples (the start's coupler moved by ``offset``, m)."""
    y0 = initial_state(P, JOINTS, offset=offset) if any(offset) else None
    return integrate(P, JOINTS, EFFECTS, T, _setting(method, value, WP), y0=y0)[0]


def error(method: str, value: float, offset: tuple[float, float] = (0.0, 0.0)) -> float:
    return contact_error(states(method, value, offset), states(REF["method"], REF["rtol"]), T, WINDOW_S, P, JOINTS)


def test_eccentricity_from_the_states_is_the_engines():
    ys, diags, *_ = integrate(P, JOINTS, EFFECTS, T, _setting("dopri5", 1e-8, WP))
    e = eccentricity(P, JOINTS, ys)
    assert np.allclose(np.linalg.norm(e[:, 0], axis=-1), diags[:, 4], rtol=1e-10, atol=1e-15)
    assert np.linalg.norm(e[0, 0]) < 1e-12  # the journal starts centred
    assert (diags[T <= WINDOW_S, 5] > 0).any()  # and meets its bushing inside the window: the window spans impacts


def test_the_reference_floor_is_far_below_every_error_it_ranks():
    floor = contact_error(
        states(REF["method"], REF["check_rtol"]), states(REF["method"], REF["rtol"]), T, WINDOW_S, P, JOINTS
    )
    errors = {f"{m} {v:g}": error(m, v) for m, values in WP["scenes"][DRY].items() for v in values}
    loosest = max(errors.values())
    assert floor < 1e-3 * loosest, (floor, errors)
    assert floor < 0.1 * min(errors.values()), f"reference pair {floor:.1e}; errors {errors}"


def test_the_error_falls_as_the_tolerance_tightens():
    rtols = sorted(WP["scenes"][DRY]["dopri5"], reverse=True)
    err = {r: error("dopri5", r) for r in rtols}
    assert err[rtols[0]] > 30 * err[rtols[-1]], err
    pairs = [(r, x) for r in rtols for x in rtols if np.isclose(x, r * 1e-2, rtol=1e-9, atol=0.0)]
    assert len(pairs) >= 3
    for (
        r,
        tighter,
    ) in pairs:  # two decades tighter is always more accurate (one decade need not be: 1e-6 and 1e-7 are alike)
        assert err[tighter] < err[r], (r, err)
    slope = np.polyfit(np.log10(rtols), np.log10([err[r] for r in rtols]), 1)[0]
    assert slope > 0.2, (slope, err)
    steps = sorted(WP["scenes"][DRY]["rk4"], reverse=True)
    rk4 = [error("rk4", h) for h in steps]
    assert all(b < a for a, b in zip(rk4, rk4[1:], strict=False)), dict(zip(steps, rk4, strict=True))


@pytest.mark.parametrize("offset", [(1e-9, 0.0), (0.0, 1e-9)], ids=["x", "y"])
def test_a_nanometre_of_the_start_is_a_small_reading(offset):
    """At the reference tolerance, a start moved by 1 nm (2e-5 c) reads far below the errors of the loose settings
    ranked, and 10 nm reads about ten times as much: the window ends before the impacts amplify differences beyond
    linear.  The pipeline's own setting errs by about as much as a start moved by 2 nm (5e-4 c against 2-3e-4 c): it
    is at the floor of what this measure tells apart, and below a fifth of the section tolerance by which the states
    are found (numerical error cannot break an orbit's repetition)."""
    moved = error(REF["method"], REF["rtol"], offset)
    assert moved < 0.01 * error("dopri5", max(WP["scenes"][DRY]["dopri5"])), moved
    ten = error(REF["method"], REF["rtol"], (10 * offset[0], 10 * offset[1]))
    assert 4 < ten / moved < 25, (moved, ten)
    pipeline = SECTION["integrators"]["explicit"]
    assert error(pipeline["method"], pipeline["rtol"]) < 0.2 * SECTION["states"]["section_tolerance"]


def small_config(**integrators):
    cfg = copy.deepcopy(SECTION)
    cfg["work_precision"].update(
        repeats=1, scenes={DRY: {"dopri5": [1e-4, 1e-6, 1e-9]}, LUBRICATED: {"bdf": [1e-4, 1e-6, 1e-9]}}
    )
    for kind, rtol in integrators.items():
        cfg["integrators"][kind] = {**cfg["integrators"][kind], "rtol": rtol, "atol": rtol * 1e-3}
    return cfg


def test_the_study_records_its_measure_and_the_summary_shows_both_pipeline_settings():
    cfg = small_config(explicit=3e-7)  # not in the list: the study adds the pipeline's setting
    ds, timings = work_precision(cfg)
    assert ds.attrs["dry_error_window_cycles"] == WP["dry_error_window_cycles"]
    assert (
        "|e - e of the reference| / c" in ds.error_measure.sel(scene=DRY).item()
        and "RMS" in ds.error_measure.sel(scene=LUBRICATED).item()
    )
    assert float(ds.reference_error.sel(scene=DRY)) == pytest.approx(
        contact_error(
            states(REF["method"], REF["check_rtol"]), states(REF["method"], REF["rtol"]), T, WINDOW_S, P, JOINTS
        ),
        rel=1e-9,
    )
    assert f"{DRY}: {float(ds.reference_error.sel(scene=DRY)):.2e}" in ds.attrs["reference_error"]
    assert float(ds.error.sel(scene=DRY, setting="dopri5 rtol=1e-06")) == pytest.approx(error("dopri5", 1e-6), rel=1e-9)
    assert float(ds.error.sel(scene=LUBRICATED, setting="bdf rtol=1e-06")) == float(
        ds.rms_error.sel(scene=LUBRICATED, setting="bdf rtol=1e-06")
    )
    summary, seconds = collect([ds], [timings])
    shown = highlights(summary, seconds)
    dry_label = setting_label(cfg["integrators"]["explicit"])
    lub_label = setting_label(cfg["integrators"]["stiff"])
    assert dry_label == f"{SECTION['integrators']['explicit']['method']} rtol=3e-07"
    assert shown[f"clearance integrators, {DRY}"]["pipeline_setting"] == f"{dry_label} ({DRY})"
    assert shown[f"clearance integrators, {LUBRICATED}"]["pipeline_setting"] == f"{lub_label} ({LUBRICATED})"
    assert shown[f"clearance integrators, {DRY}"]["pipeline_error"] == pytest.approx(
        float(ds.error.sel(scene=DRY, setting=dry_label))
    )
