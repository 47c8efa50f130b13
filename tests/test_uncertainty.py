"""Input-uncertainty study: the sample design, and the clearance paper's two-stage propagation against
judging the claims directly on rerun scenes."""

import copy

import numpy as np
import pytest

from conftest import load_yaml
from linkwork.pipeline.uncertainty import Input, apply, batches, labelled_inputs, sample_count, samples

SECTION = load_yaml("config/config.yaml")["clearance"]
PUBLISHED = load_yaml("config/published/clearance.yaml")


def test_design_one_at_a_time_then_latin_hypercube_within_the_ranges():
    ins = [Input("a.value", 1.0, 0.5, 2.0, "r"), Input("b.value", 1e-3, 1e-5, 1e-2, "r"), Input("c.value", "x", np.nan, np.nan, "r", ("x", "y", "z"))]
    design = samples(ins, lhs_points=20, seed=3)
    assert len(design) == sample_count(ins, 20) == 1 + 2 + 2 + 2 + 20
    assert design[0].label == "nominal" and design[0].values == {}
    for s in design[1:7]:  # one at a time: exactly the input named in `moved`
        assert list(s.values) == [s.moved]
    lhs = design[7:]
    a = np.array([s.values["a.value"] for s in lhs])
    b = np.array([s.values["b.value"] for s in lhs])
    assert a.min() >= 0.5 and a.max() <= 2.0 and b.min() >= 1e-5 and b.max() <= 1e-2
    # Latin hypercube: each of the 20 equal strata of a holds exactly one point; b is stratified in log
    assert sorted(np.floor((a - 0.5) / 1.5 * 20).astype(int)) == list(range(20))
    assert sorted(np.floor(np.log(b / 1e-5) / np.log(1e3) * 20).astype(int)) == list(range(20))
    assert {s.values["c.value"] for s in lhs} == {"x", "y", "z"}
    assert [s.label for s in samples(ins, 20, 3)] == [s.label for s in design]  # fixed seed: same design


def test_apply_replaces_only_existing_paths_on_a_copy():
    cfg = {"a": {"value": 1.0, "status": "assumed"}}
    moved = apply(cfg, {"a.value": 2.0})
    assert moved["a"]["value"] == 2.0 and cfg["a"]["value"] == 1.0
    with pytest.raises(KeyError):
        apply(cfg, {"a.missing": 2.0})


def test_batches_cover_every_sample_once():
    assert [list(r) for r in batches(7, 3)] == [[0, 1, 2], [3, 4, 5], [6]]


def test_labelled_inputs_are_the_ranged_entries():
    found = [i.path for i in labelled_inputs(SECTION["assumed"], "assumed.")]
    assert found == ["assumed.joint_length_m.value", "assumed.v0_m_s.value", "assumed.v1_m_s.value", "assumed.e0_m.value"]


@pytest.fixture(scope="module")
def small_clearance():
    """One variant, one settling and one recorded cycle, a coarse output grid: cheap scenes, same code paths."""
    cfg = copy.deepcopy(SECTION)
    cfg["variants"] = {"decoded": cfg["variants"]["decoded"]}
    cfg["numerics"].update(settle_cycles=1, record_cycles=1, points_per_cycle=180)
    cfg["statistics"].update(settle_max_cycles=2, record_cycles=4, tight_record_cycles=2, uncertainty_record_cycles=2, batch_cycles=2)
    cfg["uncertainty"].update(lhs_points=0)
    return cfg


def test_a_clearance_batch_moves_only_the_scenes_that_read_its_input():
    from linkwork.papers.clearance.uncertainty import batch_jobs

    found = batch_jobs(SECTION)
    jobs = {(s["label"], j["variant"]): j["scenes"] for j in found for s in j["samples"]}
    assert len(jobs) == 8 * len(SECTION["variants"])  # four inputs at two ends; the nominal sample reruns nothing
    for variant in SECTION["variants"]:
        assert jobs[("assumed.e0_m.value low", variant)] == ["lubricated_1", "lubricated_2", "lubricated_both"]
        # v1 enters every scene that names friction: the dry ones and the lubricated ones (their dry contact)
        friction = [n for n, spec in SECTION["scenes"].items() if "friction" in spec["effects"]]
        assert jobs[("assumed.v1_m_s.value high", variant)] == friction == ["dry_1", "dry_2", "dry_both", "lubricated_1", "lubricated_2", "lubricated_both"]
    # one batch per variant and set of moved scenes: joint length and e0 share the lubricated one, v0 and v1 the one of all six
    assert [(j["variant"], len(j["samples"])) for j in found] == [(v, 4) for v in SECTION["variants"] for _ in range(2)]


def test_a_clearance_sample_takes_its_moved_scenes_from_a_direct_rerun_and_the_others_from_the_nominal_runs(small_clearance):
    """Two routes to a sample's deviations: the batch (narrow config, only the moved scenes) gathered with the
    nominal claims, against each scene rerun directly at the moved value.  A moved scene's mean is the direct
    rerun's mean over the same recorded cycles; a scene the input does not enter keeps the nominal mean; the
    nominal sample reproduces the nominal claims."""
    from linkwork.configformat import pick
    from linkwork.papers.clearance import uncertainty
    from linkwork.papers.clearance.adapter import scene_keys
    from linkwork.papers.clearance.studies import COMPARED, claims, recorded, scene

    cfg = small_clearance
    nominal_runs = [scene(cfg, "decoded", n) for n in ["ideal", *COMPARED]]
    nominal = claims(cfg, nominal_runs, [scene(cfg, "decoded", n, "tight") for n in COMPARED])
    label = "assumed.e0_m.value high"
    job = next(j for j in uncertainty.batch_jobs(cfg) if label in [s["label"] for s in j["samples"]])
    values = next(s["values"] for s in job["samples"] if s["label"] == label)
    keys = sorted({k for s in job["scenes"] for k in scene_keys(cfg, "decoded", s)} - {"statistics.record_cycles"}) + ["statistics.uncertainty_record_cycles"]
    part = uncertainty.batch(pick(cfg, keys), job["samples"], job["variant"])  # the batch's config as the rule passes it
    moved = part.cycle_deviation.sel(sample=label).isel(variant=0)
    lubricated, dry = ["lubricated_1", "lubricated_2", "lubricated_both"], ["dry_1", "dry_2", "dry_both"]
    assert np.isfinite(moved.sel(scene=lubricated)).all()
    assert np.isnan(moved.sel(scene=dry)).all()  # e0 does not enter a dry scene
    gathered = uncertainty.gather(cfg, [part], nominal, PUBLISHED)
    means = gathered.sample_mean_deviation.sel(sample=label, variant="decoded")

    at = apply(cfg, values)
    cycles = cfg["statistics"]["uncertainty_record_cycles"]
    for k, name in enumerate(COMPARED):
        if name in lubricated:  # the direct route: the scene rerun at the moved film cap
            direct = recorded(scene(at, "decoded", name, "pipeline", record=cycles))[..., -cycles:].mean(axis=-1)
            np.testing.assert_allclose(means.isel(scene=k).values, direct, rtol=1e-12)
        else:
            np.testing.assert_array_equal(means.isel(scene=k).values, nominal.mean_deviation.sel(variant="decoded", scene=name).values)
    for claim in nominal.claim.values:
        base = float(gathered.value.sel(sample="nominal", quantity=f"decoded|{claim}"))
        assert base == float(nominal.holds.sel(variant="decoded", claim=claim))


def test_a_transplanter_sample_optimised_from_the_nominal_optimum_reaches_the_cold_start_optimum():
    """The warm start of the transplanter samples (from our nominal optimum, not the initial diameters) is a
    speed-up only: at the range's corner of E and density both starts reach the same diameters."""
    from linkwork.engines.optimize import slsqp
    from linkwork.papers.transplanter.studies import problem

    cfg = load_yaml("config/config.yaml")["transplanter"]
    ftol = cfg["optimization"]["slsqp_ftol"]
    initial = np.array(cfg["initial_diameters_m"], dtype=float)
    nominal, _ = slsqp(problem(cfg), initial, ftol)
    material = f"materials.{cfg['material']['name']}"
    corner = apply(cfg, {f"{material}.youngs_modulus_Pa.value": cfg["materials"][cfg["material"]["name"]]["youngs_modulus_Pa"]["range"][0],
                         f"{material}.density_kg_m3.value": cfg["materials"][cfg["material"]["name"]]["density_kg_m3"]["range"][1]})
    cold, cold_info = slsqp(problem(corner), initial, ftol)
    warm, warm_info = slsqp(problem(corner), nominal, ftol)
    assert cold_info["success"] and warm_info["success"]
    assert np.abs(warm - cold).max() < 1e-9  # m: far below the paper's 0.01 mm digits
    assert not np.allclose(cold, nominal, rtol=0, atol=1e-6)  # the corner does move the optimum
    assert warm_info["evaluations"] < cold_info["evaluations"]
