"""Reproduced numbers against config/published/stiffness.yaml, within its tolerances.

The findings of the report are asserted here, so a change that breaks them fails:
the paper's own model (Tables 1-2 as printed) reproduces every Table 3 angle and
all headline numbers but the upper end of the K_c range; the statics-consistent
model deviates; eq. (14) taken literally misses the K_c numbers.
"""

import numpy as np
import pytest

from linkwork.papers.stiffness.studies import stiffness as build_dataset
from linkwork.pipeline.compare import compare, verdict_counts


@pytest.fixture(scope="module")
def stiffness_ds():
    from conftest import load_yaml

    return build_dataset(load_yaml("config/config.yaml")["stiffness"])


def _table(stiffness_published, stiffness_ds, form):
    return compare(stiffness_published, stiffness_ds.sel(form=form), form).set_index("id")


def test_every_table3_angle_within_rounding(stiffness_published, stiffness_ds):
    t = _table(stiffness_published, stiffness_ds, "tables")
    cells = t[t.index.str.startswith("table3")]
    assert len(cells) == 72
    assert (cells.verdict == "reproduced").all(), cells[cells.verdict != "reproduced"]


def test_papers_own_model_reproduces_the_headline_numbers(stiffness_published, stiffness_ds):
    t = _table(stiffness_published, stiffness_ds, "tables")
    for qid in ("K_h_max", "K_h_argmax", "K_h_min", "K_h_argmin", "K_h_mean", "K_c_min", "K_c_mean"):
        assert t.loc[qid, "verdict"] == "reproduced", t.loc[qid]
    # documented deviation: printed 3.89e4, the model gives 3.897e4 (0.19 %), beyond rounding
    assert t.loc["K_c_max", "verdict"] == "differs"
    assert 0.001 < t.loc["K_c_max", "relative_deviation"] < 0.003


def test_statics_consistent_model_does_not_reproduce_the_paper(stiffness_published, stiffness_ds):
    t = _table(stiffness_published, stiffness_ds, "equilibrium")
    headline = t[~t.index.str.startswith("table3") & ~t.index.str.endswith("_not_constant")]
    assert verdict_counts(headline)["differs"] == len(headline) == 8
    assert t.loc["K_h_argmax", "reproduced"] == 240.0 and t.loc["K_h_argmin", "reproduced"] == 70.0


def test_the_conclusion_holds_in_every_form(stiffness_published, stiffness_ds):
    """Both stiffnesses vary by far more than 20 % over a turn, whichever internal forces are used."""
    for form in ("equilibrium", "tables", "printed"):
        t = _table(stiffness_published, stiffness_ds, form)
        assert (t.loc[["K_h_not_constant", "K_c_not_constant"], "verdict"] == "reproduced").all()
        assert (t.loc[["K_h_not_constant", "K_c_not_constant"], "reproduced"] > 1.5).all()


def test_literal_eq14_misses_the_rotational_stiffness(stiffness_published, stiffness_ds):
    t = _table(stiffness_published, stiffness_ds, "printed")
    for qid in ("K_c_min", "K_c_max", "K_c_mean"):
        assert t.loc[qid, "verdict"] == "differs"
        assert -0.13 < t.loc[qid, "relative_deviation"] < -0.10
    assert t.loc["K_h_max", "verdict"] == "reproduced"  # eq. (8) is right


def test_implied_modulus_scales_with_the_ratio():
    """E_implied = E x published / reproduced: a model that gives half the published value implies twice E."""
    import pandas as pd

    from linkwork.papers.stiffness.findings import implied_modulus

    table = pd.DataFrame({"model": ["tables", "tables"], "id": ["K_h_max", "K_c_min"], "unit": ["N/m", "N m/rad"],
                          "published": [2.0, 3.0], "reproduced": [1.0, 3.0]})
    implied = implied_modulus(table, 2.1e8, ["tables"])
    assert np.allclose(implied.sel(implied_form="tables").values, [4.2e8, 2.1e8])
