"""Input-uncertainty study: the sample design, and the clearance paper's two-stage propagation against
judging the claims directly on rerun scenes."""

import copy
import itertools

import numpy as np
import pytest
import xarray as xr

from conftest import load_yaml
from linkwork.pipeline.compare import classify, compare
from linkwork.pipeline.uncertainty import Input, apply, batches, labelled_inputs, sample_count, samples, scenarios

SECTION = load_yaml("config/config.yaml")["clearance"]
PUBLISHED = load_yaml("config/published/clearance.yaml")


def test_design_choices_are_scenarios_never_sampled_values():
    ins = [Input("a.value", 1.0, 0.5, 2.0, "r"), Input("b.value", 1e-3, 1e-5, 1e-2, "r"),
           Input("c.value", "y", np.nan, np.nan, "r", ("x", "y", "z"), labels=("c is x", "c is y", "c is z"))]
    design = samples(ins, lhs_points=20, seed=3, corner_limit=4)
    per_scenario = 1 + 2 + 2 + 4 + 20  # nominal, one at a time, the 4 corners, the Latin hypercube
    assert len(design) == sample_count(ins, 20, corner_limit=4) == 3 * per_scenario
    assert [s.label for s in scenarios(ins)] == ["c is y", "c is x", "c is z"]  # the nominal choice first
    assert design[0].label == "nominal" and design[0].values == {"c.value": "y"}
    for k, scen in enumerate(("y", "x", "z")):
        block = design[k * per_scenario:(k + 1) * per_scenario]
        assert {s.values["c.value"] for s in block} == {scen}  # a choice is never moved within a scenario
        assert all(s.moved != "c.value" for s in block)
        for s in block[1:5]:  # one at a time: exactly the input named in `moved` besides the scenario's choice
            assert set(s.values) == {s.moved, "c.value"}
        corners = block[5:9]
        assert sorted((s.values["a.value"], s.values["b.value"]) for s in corners) == sorted(
            itertools.product((0.5, 2.0), (1e-5, 1e-2))
        )
        lhs = block[9:]
        a = np.array([s.values["a.value"] for s in lhs])
        b = np.array([s.values["b.value"] for s in lhs])
        # Latin hypercube: each of the 20 equal strata of a holds exactly one point; b is stratified in log
        assert sorted(np.floor((a - 0.5) / 1.5 * 20).astype(int)) == list(range(20))
        assert np.allclose(sorted(np.log(b / 1e-5) / np.log(1e3) * 20 // 1), range(20))
    assert [s.label for s in samples(ins, 20, 3, 4)] == [s.label for s in design]  # fixed seed: same design
    assert len(samples(ins, 0, 3, corner_limit=3)) == 3 * 5  # more corners than the limit: none


def _toy_study(
    fun, names, ranges, published, lhs_points=8, corner_limit=0, evaluations=200, choices=None, workers=1,
    flat_rtol=1e-9,
):
    """A toy paper: inputs ``names`` in ``ranges`` (config section {name: labelled entry}), its results the
    variables of ``fun(**inputs)``; the study's samples, summary and bounded searches as a paper's gather runs them."""
    import xarray as xr

    from linkwork.pipeline.search import searcher
    from linkwork.pipeline.uncertainty import batch_dataset, gathered

    cfg = {
        n: {"value": float(np.mean(r)), "status": "assumed", "reason": "toy", "range": list(r)}
        for n, r in zip(names, ranges)
    }
    if choices:
        cfg["mode"] = {"value": choices[0], "status": "assumed", "reason": "toy", "choices": list(choices)}
    cfg["uncertainty"] = {
        "lhs_points": lhs_points,
        "batch_size": 1000,
        "seed": 1,
        "search": {"corner_limit": corner_limit, "evaluations": evaluations, "xtol": 1e-4, "flat_rtol": flat_rtol},
    }
    ins = list(labelled_inputs({k: v for k, v in cfg.items() if k != "uncertainty"}))

    def results(c):
        args = {n: float(c[n]["value"]) for n in names}
        if choices:
            args["mode"] = c["mode"]["value"]
        return [xr.Dataset({k: ((), float(v)) for k, v in fun(**args).items()})]

    batch = batch_dataset(cfg, ins, samples(ins, lhs_points, 1, corner_limit), published, results)
    return gathered(ins, [batch], "toy", searcher(cfg, published, ins, results), workers)


def _entry(name, value, tol, relation="eq"):
    return {
        "id": name,
        "quantity": name,
        "value": value,
        "unit": "1",
        "where": "text",
        "tolerance": {"abs": tol},
        "relation": relation,
        "measure": {"variable": name, "reduce": "value"},
    }


def test_the_interval_finds_a_corner_that_the_samples_miss():
    """A lowest resonance sqrt(k / m) of a chain: its minimum over the box sits at the soft, heavy corner
    (closed form), which one-at-a-time samples and a small Latin hypercube do not reach."""
    ranges = [(5e3, 5e4), (5.0, 12.0), (2e7, 2e8), (1.5, 2.5)]
    fun = lambda k, m, kn, eta: {"w": float(np.sqrt(1 / (1 / k + 1 / kn) / (m * eta**2)))}  # noqa: E731
    ds = _toy_study(fun, ["k", "m", "kn", "eta"], ranges, {"quantities": [_entry("w", 40.0, 4.0)]}, lhs_points=6)
    exact_low = fun(5e3, 12.0, 2e7, 2.5)["w"]
    exact_high = fun(5e4, 5.0, 2e8, 1.5)["w"]
    samples_low = float(ds.value.sel(quantity="|w").min())
    assert samples_low > 1.2 * exact_low  # the samples alone miss the corner ...
    assert float(ds.low.sel(quantity="|w").squeeze()) == pytest.approx(exact_low, rel=1e-6)  # ... the search finds it
    assert float(ds.high.sel(quantity="|w").squeeze()) == pytest.approx(exact_high, rel=1e-6)
    assert ds.low_at.sel(quantity="|w").values.ravel() == pytest.approx([5e3, 12.0, 2e7, 2.5], rel=1e-6)


def test_the_interval_finds_an_interior_saddle_corner_by_search():
    """f = 4 (a - 1/2)(b - 1/2): every one-at-a-time sample gives 0, the maximum 1 sits at two corners and the
    minimum -1 at the other two; no monotone corner exists, the bounded search from the samples finds them."""
    fun = lambda a, b: {"f": 4 * (a - 0.5) * (b - 0.5)}  # noqa: E731
    ds = _toy_study(fun, ["a", "b"], [(0.0, 1.0), (0.0, 1.0)], {"quantities": [_entry("f", 0.0, 0.1)]}, lhs_points=4)
    assert float(ds.high.sel(quantity="|f").squeeze()) == pytest.approx(1.0, abs=1e-6)
    assert float(ds.low.sel(quantity="|f").squeeze()) == pytest.approx(-1.0, abs=1e-6)


def test_consistent_set_reconciles_the_rows_that_can_match_together():
    """Three rows over inputs a, b in [0, 1]: r1 matches where a < 0.3, r2 where a < 0.5 and b < 0.3, r3 where
    a > 0.7.  The best consistent set matches r1 and r2 at once; r3 matches alone, only where r1 and r2 fail."""
    fun = lambda a, b: {"r1": a, "r2": max(a - 0.2, b), "r3": a}  # noqa: E731
    published = {"quantities": [_entry("r1", 0.0, 0.3), _entry("r2", 0.0, 0.3), _entry("r3", 1.0, 0.3)]}
    ds = _toy_study(fun, ["a", "b"], [(0.0, 1.0), (0.0, 1.0)], published)
    assert int(ds.consistent_count.values.ravel()[0]) == 2
    flags = {q: float(ds.in_consistent_set.sel(quantity=f"|{q}").values.ravel()[0]) for q in ("r1", "r2", "r3")}
    assert flags == {"r1": 1.0, "r2": 1.0, "r3": 0.0}
    best = dict(zip(ds.input.values, ds.consistent_at.values.reshape(-1)))
    assert best["a.value"] < 0.3 and best["b.value"] < 0.3
    from linkwork.pipeline.compare import compare

    table = compare(published, xr.Dataset({"r1": 0.5, "r2": 0.5, "r3": 0.5}), uncertainty=ds).set_index("id")
    assert table.loc["r1", "verdict"] == table.loc["r2", "verdict"] == "decided by an unprinted input"
    assert table.loc["r3", "verdict"] == "only where other rows fail"


def test_a_scenario_gets_its_own_block_of_rows():
    """A choice is a scenario: the comparison judges each scenario on its own nominal point and box."""
    fun = lambda a, mode: {"y": a + (10.0 if mode == "shifted" else 0.0)}  # noqa: E731
    published = {"quantities": [_entry("y", 0.5, 1.0)]}
    ds = _toy_study(fun, ["a"], [(0.0, 1.0)], published, choices=("plain", "shifted"))
    assert list(ds.scenario.values) == ["plain", "shifted"]
    table = compare(published, xr.Dataset({"y": 0.5}), uncertainty=ds)
    assert list(table.scenario) == ["plain", "shifted"]
    assert list(table.verdict) == ["reproduced", "differs"]
    assert table.reproduced.iloc[1] == pytest.approx(10.5)


def test_printed_rounding_is_its_own_class():
    """A value inside its tolerance at the printed inputs that only a rounding input moves out: 'matches as
    printed', not 'decided by an unprinted input'."""
    ins = [Input("p.value", 1.0, 0.995, 1.005, "printed to 0.01", kind="rounding")]
    published = {"quantities": [_entry("y", 1.0, 0.003)]}
    from linkwork.pipeline.uncertainty import evaluated_dataset, summary

    chosen = samples(ins, 0, 1)
    ds = summary([evaluated_dataset([{("", "y"): s.values.get("p.value", 1.0)} for s in chosen], ins, chosen)], ins)
    table = compare(published, xr.Dataset({"y": 1.0}), uncertainty=ds)
    assert table.verdict.iloc[0] == "reproduced at the printed digits"
    assert classify(1.0, 0.003, "eq", 1.004, 0.0, 0.995, 1.005, rounding_only=True) == "differs at the printed digits"


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
    assert found == [
        "assumed.joint_length_m.value", "assumed.v0_m_s.value", "assumed.v1_m_s.value",
        "assumed.impact_velocity_floor_m_s.value", "assumed.e0_m.value",
    ]


@pytest.fixture(scope="module")
def small_clearance():
    """One variant, two starts, short records and checks, a coarse output grid: cheap scenes, same code paths."""
    cfg = copy.deepcopy(SECTION)
    cfg["variants"] = {"decoded": cfg["variants"]["decoded"]}
    cfg["numerics"].update(record_cycles=1, points_per_cycle=360)
    cfg["states"].update(max_cycles=12, check_cycles=2, min_cycles=10)
    cfg["uncertainty"].update(lhs_points=0)
    return cfg


def test_a_clearance_batch_moves_only_the_scenes_that_read_its_input():
    from linkwork.papers.clearance.uncertainty import batch_jobs

    found = batch_jobs(SECTION)
    jobs = {(s["label"], j["variant"]): j["scenes"] for j in found for s in j["samples"]}
    # five inputs at two ends, one batch per input (both ends share its process); nominal points rerun nothing
    assert len(jobs) == 2 * len(found) == 10 * len(SECTION["variants"])
    assert all(len({s["label"].rsplit(" ", 1)[0] for s in j["samples"]}) == 1 for j in found)
    for variant in SECTION["variants"]:
        assert jobs[("assumed.e0_m.value low", variant)] == ["lubricated_1", "lubricated_2", "lubricated_both"]
        # v1 and the impact-velocity floor enter every scene with contact: the dry ones and the lubricated ones (their
        # dry contact)
        friction = [n for n, spec in SECTION["scenes"].items() if "friction" in spec["effects"]]
        assert (
            jobs[("assumed.v1_m_s.value high", variant)]
            == friction
            == ["dry_1", "dry_2", "dry_both", "lubricated_1", "lubricated_2", "lubricated_both"]
        )
        assert jobs[("assumed.impact_velocity_floor_m_s.value low", variant)] == friction
    assert not any("off-centre" in label for label, _ in jobs)  # the other start is a scenario at the nominal inputs


def test_a_clearance_sample_is_judged_on_its_own_state_and_the_other_start_is_a_scenario(small_clearance):
    """Two routes to a sample: the batch (narrow config, only the moved scenes, continued from the nominal state)
    gathered with the nominal claims, against the scene rerun directly at the moved value from the same state.  A moved
    scene's measure is the direct rerun's; a scene the input does not enter keeps the nominal measure; the nominal
    sample reproduces the nominal claims where its margins decide them (else it enters no range: NaN); the second
    start's scenario takes the nominal runs' second start."""
    from linkwork.configformat import pick
    from linkwork.papers.clearance import uncertainty
    from linkwork.papers.clearance.adapter import scene_keys
    from linkwork.papers.clearance.studies import COMPARED, claims, scene

    cfg = small_clearance
    nominal_runs = {n: scene(cfg, "decoded", n) for n in ["ideal", *COMPARED]}
    nominal = claims(cfg, list(nominal_runs.values()))
    label = "assumed.e0_m.value high"
    job = next(j for j in uncertainty.batch_jobs(cfg) if label in [s["label"] for s in j["samples"]])
    keys = sorted(
        {k for s in job["scenes"] for k in scene_keys(cfg, "decoded", s) if not k.startswith("check_integrators.")}
    )
    part = uncertainty.batch(
        pick(cfg, keys), job["samples"], job["variant"], nominal=[nominal_runs[s] for s in job["scenes"]]
    )
    moved = part.judged.sel(sample=label, statistic="judged_mean").isel(variant=0)
    lubricated, dry = ["lubricated_1", "lubricated_2", "lubricated_both"], ["dry_1", "dry_2", "dry_both"]
    assert np.isfinite(moved.sel(scene=lubricated)).all()
    assert np.isnan(moved.sel(scene=dry)).all()  # e0 does not enter a dry scene
    gathered = uncertainty.gather(cfg, [part], nominal, PUBLISHED)
    means = gathered.sample_mean_deviation.sel(sample=label, variant="decoded")
    at = apply(cfg, next(s for s in job["samples"] if s["label"] == label)["values"])
    for k, name in enumerate(COMPARED):
        if name in lubricated:  # the direct route: the scene rerun at the moved film cap, from the nominal state
            direct = scene(
                at, "decoded", name, first_start_only=True, check=False,
                memory=nominal_runs[name].window_memory.values[0],
            )
            np.testing.assert_allclose(means.isel(scene=k).values, direct.judged_mean.values[0], rtol=1e-12)
        else:
            np.testing.assert_array_equal(
                means.isel(scene=k).values,
                nominal.mean_deviation.sel(variant="decoded", scene=name).isel(start=0).values,
            )
    for claim in nominal.claim.values:
        value = float(gathered.value.sel(sample="nominal", quantity=f"decoded|{claim}"))
        if int(nominal.outcome_by_start.sel(variant="decoded", claim=claim).isel(start=0)) >= 0:
            assert value == float(nominal.holds.sel(variant="decoded", claim=claim))
        else:  # the nominal sample, undetermined within its margins, enters no range (as every sample)
            assert np.isnan(value)
        other = f"start {nominal.start.values[1]} | nominal"
        assert float(gathered.value.sel(sample=other, quantity=f"decoded|{claim}")) == float(
            nominal.holds_by_start.sel(variant="decoded", claim=claim).isel(start=1)
        )
    assert list(gathered.scenario.values) == [f"start {s}" for s in nominal.start.values]


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
    corner = apply(
        cfg,
        {
            f"{material}.youngs_modulus_Pa.value": cfg["materials"][cfg["material"]["name"]]["youngs_modulus_Pa"][
                "range"
            ][0],
            f"{material}.density_kg_m3.value": cfg["materials"][cfg["material"]["name"]]["density_kg_m3"]["range"][1],
        },
    )
    cold, cold_info = slsqp(problem(corner), initial, ftol)
    warm, warm_info = slsqp(problem(corner), nominal, ftol)
    assert cold_info["success"] and warm_info["success"]
    assert np.abs(warm - cold).max() < 1e-9  # m: far below the paper's 0.01 mm digits
    assert not np.allclose(cold, nominal, rtol=0, atol=1e-6)  # the corner does move the optimum
    assert warm_info["evaluations"] < cold_info["evaluations"]


def test_a_vertex_ends_the_search_only_where_no_input_moved_inwards_improves_it():
    """First-order optimality at a vertex of the box, one probe per input: a value increasing in both inputs has
    its maximum at (1, 1) (the search stops there after two probes); a value peaking inside the box near that
    vertex is not stopped there, and the search then finds the interior maximum."""
    from linkwork.pipeline.search import Evaluator, extreme, vertex_is_local_extreme

    rising = lambda u: float(u[0] + 2 * u[1])  # noqa: E731
    assert vertex_is_local_extreme(lambda u: -rising(u), np.array([1.0, 1.0]), 0.01)
    assert not vertex_is_local_extreme(lambda u: -rising(u), np.array([1.0, 0.0]), 0.01)  # b moved inwards raises it
    assert not vertex_is_local_extreme(lambda u: -rising(u), np.array([0.5, 1.0]), 0.01)  # not a vertex
    peak = lambda u: np.array([-(u[0] - 0.9) ** 2 - (u[1] - 0.8) ** 2])  # noqa: E731
    calls = []
    ev = Evaluator(lambda u: calls.append(1) or peak(u), 2)
    value, at = extreme(ev, 0, 1.0, [np.array([1.0, 1.0])], 200, 1e-6)
    assert value == pytest.approx(0.0, abs=1e-8) and at == pytest.approx([0.9, 0.8], abs=1e-3)
    ev = Evaluator(lambda u: np.array([rising(u)]), 2)
    value, at = extreme(ev, 0, 1.0, [np.array([1.0, 1.0])], 200, 1e-6)
    assert value == 3.0 and list(at) == [1.0, 1.0] and ev.evaluations == 3  # the vertex and one probe per input


def test_scenarios_searched_side_by_side_give_the_same_study():
    """Two worker processes search the scenarios of a study with a choice: the same Dataset as one process."""
    fun = lambda a, b, mode: {"f": (a - 0.3) ** 2 + b * (2.0 if mode == "y" else 1.0)}  # noqa: E731
    args = (fun, ["a", "b"], [(0.0, 1.0), (0.0, 1.0)], {"quantities": [_entry("f", 0.5, 0.05)]})
    one = _toy_study(*args, lhs_points=4, choices=("x", "y", "z"), workers=1)
    two = _toy_study(*args, lhs_points=4, choices=("x", "y", "z"), workers=2)
    assert one.sizes["scenario"] == 3
    assert one.identical(two)
    assert float(one.low.sel(quantity="|f").isel(scenario=0)) == pytest.approx(
        0.0, abs=1e-6
    )  # a = 0.3, b = 0: an interior minimum


def test_a_value_flat_over_the_box_is_not_searched():
    """A ratio in which the inputs cancel moves only by rounding: its interval stays the samples' range and no
    evaluation is spent on it (the search of a value that does move still runs)."""
    flat = lambda a, b: {"r": (a / b) * (b / a) * (a + 1.0) / (1.0 + a), "g": a + b}  # noqa: E731
    args = (flat, ["a", "b"], [(1.0, 3.0), (0.1, 0.7)], {"quantities": [_entry("r", 1.0, 0.1), _entry("g", 2.0, 0.1)]})
    searched = _toy_study(*args, lhs_points=4, flat_rtol=0.0)
    skipped = _toy_study(*args, lhs_points=4, flat_rtol=1e-9)
    assert float(skipped.low.sel(quantity="|r").squeeze()) == float(skipped.value.sel(quantity="|r").min())
    assert int(skipped.evaluations.squeeze()) < int(searched.evaluations.squeeze())
    assert float(skipped.high.sel(quantity="|g").squeeze()) == pytest.approx(3.7)
