"""Comparison table: measures, tolerances, verdicts."""

import math

import numpy as np
import xarray as xr

from linkwork.pipeline.compare import (
    acceptance, classify, compare, decided_by, evaluate_measure, expand_tables, tolerance_of, verdict_counts,
)

DS = xr.Dataset(
    {"k": ("angle", np.array([1.0, 3.0, 2.0])), "b": ("angle", np.array([10.0, 20.0, 30.0]))},
    coords={"angle": [0.0, 10.0, 20.0]},
)


def test_measures():
    m = lambda reduce, **kw: evaluate_measure(
        DS, {"variable": "k", "reduce": reduce, "dim": "angle", **kw}
    )  # noqa: E731
    assert m("max") == 3.0 and m("min") == 1.0 and m("mean") == 2.0 and m("range") == 2.0 and m("max_over_min") == 3.0
    assert m("argmax") == 10.0 and m("argmin") == 0.0
    assert m("at", at={"angle": 20.0}) == 2.0
    assert m("max", scale=2.0) == 6.0
    assert math.isnan(evaluate_measure(DS, {"variable": "missing", "reduce": "max"}))
    assert math.isnan(m("at", at={"angle": 15.0}))


def test_verdict_classes():
    nan = math.nan
    # published 1.0 +- 0.005; nominal, numerical error, range over the assumed inputs
    assert classify(1.0, 0.005, "eq", 1.005, 0.0, nan, nan) == "reproduced"
    assert classify(1.0, 0.005, "eq", 1.0051, 0.0, nan, nan) == "differs"
    assert classify(1.0, 0.005, "eq", nan, 0.0, nan, nan) == "not printed"
    # the causes the values cannot show: an undefined value of a model without the quantity; the paper's model deciding
    assert classify(1.0, 0.005, "eq", nan, 0.0, nan, nan, absent="model") == "no counterpart in this model"
    assert classify(1.0, 0.005, "eq", 1.0, 0.0, nan, nan, model_decides=True) == "decided by the paper's model"
    assert (
        classify(1.0, 0.005, "eq", 1.004, 0.002, 1.004, 1.004) == "undetermined by our numerics"
    )  # the error bar straddles
    # the inputs' range straddles
    assert classify(1.0, 0.005, "eq", 1.004, 0.0, 0.99, 1.02) == "decided by an unprinted input"
    assert (
        classify(1.0, 0.005, "eq", 1.010, 0.0, 1.002, 1.02) == "decided by an unprinted input"
    )  # deviates nominally, not robustly
    assert classify(1.0, 0.005, "eq", 1.010, 0.001, 1.008, 1.02) == "differs"
    assert classify(1.0, 0.005, "eq", 1.000, 0.001, 0.998, 1.003) == "reproduced"
    assert classify(3.0, 0.0, "ge", 2.9, 0.01, 2.5, 3.5) == "decided by an unprinted input"
    assert classify(3.0, 0.0, "ge", 3.2, 0.01, 3.1, 30.0) == "reproduced"
    assert acceptance(3.0, 0.0, "ge")[1] == math.inf


def test_the_deciding_input_is_the_one_that_crosses():
    region = acceptance(1.0, 0.005, "eq")
    oat = {"a.value": (1.009, 1.011), "b.value": (0.999, 1.010), "c.value": (1.008, 1.030)}
    assert decided_by(region, 1.010, 0.0, oat) == "b"
    assert (
        decided_by(region, 1.010, 0.0, {"a.value": (1.009, 1.011), "c.value": (1.008, 1.030)})
        == "jointly (largest alone: c)"
    )


def test_tolerances():
    assert tolerance_of({"value": -200.0, "tolerance": {"rel": 0.01}}) == 2.0
    assert tolerance_of({"value": 5.0, "tolerance": {"abs": 0.5}}) == 0.5


def test_tables_expand_cell_by_cell_and_compare():
    published = {
        "quantities": [
            {"id": "kmax", "quantity": "k max", "value": 3.0, "unit": "1", "where": "text", "tolerance": {"abs": 0.0},
             "measure": {"variable": "k", "reduce": "max", "dim": "angle"}},
            {"id": "gone", "quantity": "absent", "value": 1.0, "unit": "1", "where": "text", "tolerance": {"abs": 1.0},
             "measure": {"variable": "zzz", "reduce": "max"}},
        ],
        "tables": [
            {"id": "t", "where": "Table 9", "key": "a", "coordinate": "angle", "unit": "deg", "tolerance": {"abs": 0.5},
             "column_names": ["b"], "columns": {"b": "b"}, "rows": [[0, 10.2], [10, 21.0]]}
        ],
    }
    assert [e["id"] for e in expand_tables(published)] == ["t.b@0", "t.b@10"]
    table = compare(published, DS, model="m").set_index("id")
    assert table.loc["kmax", "verdict"] == "reproduced"
    assert table.loc["gone", "verdict"] == "not printed"
    assert table.loc["t.b@0", "verdict"] == "reproduced"
    assert table.loc["t.b@10", "verdict"] == "differs"
    assert np.isclose(table.loc["t.b@10", "deviation"], -1.0)
    counts = verdict_counts(table.reset_index())
    assert counts == {v: {"reproduced": 2, "differs": 1, "not printed": 1}.get(v, 0) for v in counts}
    assert (table.role == ["headline", "headline", "table cell", "table cell"]).all()


def test_prose_check_finds_code_names_key_paths_and_templates_but_not_marked_config_tables():
    """The checker the report test uses: it must see each kind of leak, and spare tables marked as config-key
    listings."""
    from prose import leaks, visible_text

    page = (
        "<p>The verdict turns on compared_solution and fe.damping_ratio; 31.4 {float(ds.x.sel(model='A')):.1f}"
        " rad/s.</p><table><thead><tr><th>input (config"
        " key)</th></tr></thead><tbody><tr><td>gravity_m_s2</td></tr></tbody></table>"
        "<table><thead><tr><th>scene</th></tr></thead><tbody><tr><td>dry_both</td></tr></tbody></table>"
        "<pre>theta4_deg</pre><p>See"
        " results/reports/index.html, e.g. the K_h curve, config_sha256.</p>"
    )
    found = leaks(visible_text(page))
    assert "compared_solution" in found and "fe.damping_ratio" in found and "dry_both" in found
    assert any("float(" in f for f in found)
    assert "gravity_m_s2" not in found and "theta4_deg" not in found and "config_sha256" not in found
    assert not any(f.startswith("K_h") or f in ("e.g", "index.html") for f in found)
    assert leaks("Plain words, θ4 = 2.5°, Δ_E and the K_c maximum.") == []


def test_config_key_names_become_words_in_the_reports_tables():
    """The comparison tables' 'decided by' column names config keys in words (unit suffix dropped, Greek letters
    spelt, underscores as spaces); symbols with a capital subscript stay as written; the prose check then passes."""
    import sys
    from pathlib import Path

    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "reports"))
    from _common import key_words
    from prose import leaks

    assert key_words("jointly (largest alone: theta4_deg)") == "jointly (largest alone: θ4)"
    assert key_words("youngs_modulus_Pa, density_kg_m3") == "Young's modulus, density"
    assert key_words("damping_ratio") == "damping ratio"
    assert key_words("clearance_E, M_P, k_O") == "clearance_E, M_P, k_O"
    assert leaks(key_words("decided by theta7_deg, l4_m and damping_ratio")) == []


def test_nominal_rows_and_the_verdicts_other_scenarios_change():
    """The first scenario is the nominal one; the rows of the others whose verdict differs from it are the changes;
    a scenario column that is empty in every row (read back from CSV as NaN) is one scenario."""
    import pandas as pd

    from linkwork.pipeline.compare import nominal_rows, scenario_changes

    table = pd.DataFrame({"model": ["A"] * 4, "id": ["x", "y"] * 2, "scenario": ["on", "on", "off", "off"],
                          "verdict": ["reproduced", "differs", "reproduced", "reproduced"]})
    assert list(nominal_rows(table).scenario) == ["on", "on"]
    changed = scenario_changes(table)
    assert list(changed.id) == ["y"] and list(changed.scenario) == ["off"]
    empty = table.assign(scenario=float("nan")).iloc[:2]
    assert len(nominal_rows(empty)) == 2 and scenario_changes(empty).empty


def test_each_scenario_can_carry_its_own_numerical_error_bar():
    """``errors`` per scenario index: the second scenario's row is judged with its own error bar (here 0: decided,
    so 'differs' where the first scenario's bar of 1 leaves it undetermined) and its source is not marked as
    borrowed; a plain (value, source) pair keeps the old behaviour (the first scenario's, marked)."""
    import numpy as np
    import xarray as xr

    from linkwork.pipeline.compare import compare

    published = {
        "quantities": [
            {
                "id": "c",
                "quantity": "a claim",
                "value": 1,
                "relation": "ge",
                "unit": "1",
                "where": "Sec. 1",
                "tolerance": {"abs": 0.0},
                "measure": {"variable": "holds", "reduce": "at", "at": {"claim": "c"}},
            }
        ]
    }
    ds = xr.Dataset({"holds": (("claim",), np.array([0.0]))}, coords={"claim": ["c"]})
    study = xr.Dataset(
        {
            "nominal": (("scenario", "quantity"), np.array([[0.0], [0.0]])),
            "low": (("scenario", "quantity"), np.array([[0.0], [np.nan]])),
            "high": (("scenario", "quantity"), np.array([[0.0], [np.nan]])),
            "oat_low": (("scenario", "input", "quantity"), np.zeros((2, 1, 1))),
            "oat_high": (("scenario", "input", "quantity"), np.zeros((2, 1, 1))),
            "samples": ((), 3),
        },
        coords={"scenario": ["start a", "start b"], "quantity": ["|c"], "input": ["x"]},
    )
    own = compare(published, ds, errors={"c": {0: (1.0, "bar"), 1: (0.0, "bar")}}, uncertainty=study)
    assert own.verdict.tolist() == ["undetermined by our numerics", "differs"] and own.numerical_source.tolist() == [
        "bar",
        "bar",
    ]
    borrowed = compare(published, ds, errors={"c": (1.0, "bar")}, uncertainty=study)
    assert borrowed.verdict.tolist() == ["undetermined by our numerics", "undetermined by our numerics"]
    assert borrowed.numerical_source.tolist() == ["bar", "bar (the first scenario's)"]


def test_the_verdict_classes_are_listed_once():
    """Every per-class table (meaning, colour) has exactly the classes of VERDICTS: the list lives in one place."""
    from linkwork.pipeline.compare import VERDICT_COLOURS, VERDICT_MEANING, VERDICTS

    assert list(VERDICT_MEANING) == list(VERDICTS) and list(VERDICT_COLOURS) == list(VERDICTS)
