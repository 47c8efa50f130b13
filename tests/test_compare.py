"""Comparison table: measures, tolerances, verdicts."""

import math

import numpy as np
import xarray as xr

from linkwork.pipeline.compare import compare, evaluate_measure, expand_tables, tolerance_of, verdict, verdict_counts

DS = xr.Dataset(
    {"k": ("angle", np.array([1.0, 3.0, 2.0])), "b": ("angle", np.array([10.0, 20.0, 30.0]))},
    coords={"angle": [0.0, 10.0, 20.0]},
)


def test_measures():
    m = lambda reduce, **kw: evaluate_measure(DS, {"variable": "k", "reduce": reduce, "dim": "angle", **kw})  # noqa: E731
    assert m("max") == 3.0 and m("min") == 1.0 and m("mean") == 2.0 and m("range") == 2.0
    assert m("argmax") == 10.0 and m("argmin") == 0.0
    assert m("at", at={"angle": 20.0}) == 2.0
    assert m("max", scale=2.0) == 6.0
    assert math.isnan(evaluate_measure(DS, {"variable": "missing", "reduce": "max"}))
    assert math.isnan(m("at", at={"angle": 15.0}))


def test_verdicts_and_tolerances():
    assert verdict(1.0, 1.005, 0.005) == "matches"
    assert verdict(1.0, 1.0051, 0.005) == "deviates"
    assert verdict(1.0, math.nan, 0.005) == "not reproducible"
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
    assert table.loc["kmax", "verdict"] == "matches"
    assert table.loc["gone", "verdict"] == "not reproducible"
    assert table.loc["t.b@0", "verdict"] == "matches"
    assert table.loc["t.b@10", "verdict"] == "deviates"
    assert np.isclose(table.loc["t.b@10", "deviation"], -1.0)
    assert verdict_counts(table.reset_index()) == {"matches": 2, "deviates": 1, "not reproducible": 1}
