"""Findings as the unit of prose (linkwork.pipeline.statements): templates, conditions, withdrawal, and the rendered
stiffness page with a statement withdrawn by a parameter change.  The answers over every paper's generated results,
and every row's class against the classifier, are checked on the workflow's build (tests/test_workflow.py)."""

from __future__ import annotations

import re

import numpy as np
import pandas as pd
import pytest
import xarray as xr
from conftest import load_yaml, render_stiffness_page

from linkwork.pipeline import statements
from linkwork.pipeline.compare import VERDICTS, classify, reclassify


def _write(tmp_path, text: str):
    path = tmp_path / "statements.yaml"
    path.write_text(text, encoding="utf-8")
    return path


FINDINGS = xr.Dataset(
    {"ratio": ("variant", [2.5, 0.5]), "modulus": ((), 2.1e8)},
    coords={"variant": ["a", "b"]},
    attrs={"sense": "up"},
)
TABLE = pd.DataFrame({"model": ["a", ""], "id": ["x", "y"], "reproduced": [1.25, 3.0], "verdict": ["differs", "x"]})


def test_a_statement_reads_its_values_and_renders_when_its_conditions_hold(tmp_path):
    path = _write(tmp_path, """findings:
  - id: one
    answer: 1
    text: "The ratio is {{ r | num(2) }}, the modulus {{ e | num }} MPa, ours {{ x | num }} ({{ v }}, {{ s }})."
    values:
      r: {variable: ratio, sel: {variant: a}}
      e: {variable: modulus, scale: 1.0e-6}
      x: {row: {model: a, id: x}, column: reproduced}
      v: {row: {model: a, id: x}, column: verdict}
      s: {attr: sense}
    when:
      - {test: "r > 2 and v == 'differs'", says: "a ratio above 2"}
""")
    [r] = statements.render("any", FINDINGS, TABLE, path)
    assert r.holds and r.text == "The ratio is 2.5, the modulus 210 MPa, ours 1.25 (differs, up)."
    assert statements.answer([r]) == r.text


def test_a_failed_condition_withdraws_the_statement_visibly_with_the_values_it_read(tmp_path):
    path = _write(tmp_path, """findings:
  - id: one
    answer: 1
    text: "The ratio is {{ r | num(2) }}."
    values: {r: {variable: ratio, sel: {variant: b}}}
    when:
      - {test: "r > 2", says: "a ratio above 2"}
""")
    [r] = statements.render("any", FINDINGS, TABLE, path)
    assert not r.holds and r.failed == "it needs a ratio above 2 (r > 2), and the results give r = 0.5"
    assert r.markdown() == (  # escaped for the page: '>' shows as itself
        "~~The ratio is 0.5.~~ *(withdrawn: it needs a ratio above 2 (r &gt; 2), and the results give r = 0.5)*"
    )
    assert r.html().startswith("<del>The ratio is 0.5.</del> <em>(withdrawn:")


def test_a_missing_value_and_an_ambiguous_row_are_named_and_templates_run_sandboxed(tmp_path):
    path = _write(tmp_path, """findings:
  - id: one
    text: "{{ r }}"
    values: {r: {variable: nothing_here}}
""")
    with pytest.raises(statements.StatementError, match="finding one: value r"):
        statements.render("any", FINDINGS, TABLE, path)
    path = _write(tmp_path, """findings:
  - id: two
    text: "{{ r }}"
    values: {r: {row: {}, column: reproduced}}
""")
    with pytest.raises(statements.StatementError, match="matches 2 rows, not one"):
        statements.render("any", FINDINGS, TABLE, path)
    from jinja2.exceptions import SecurityError

    path = _write(tmp_path, """findings:
  - id: three
    text: "{{ s.__class__.__mro__ }}"
    values: {s: {attr: sense}}
""")
    with pytest.raises(SecurityError):
        statements.render("any", FINDINGS, TABLE, path)


def test_numbers_in_prose():
    assert statements.num(0.0012345) == "0.00123" and statements.num(-19.66) == "−19.7"
    assert statements.num(2.1e8) == "2.1 × 10⁸" and statements.num(1000.0) == "1000"
    assert statements.num(1925.683) == "1930" and statements.num(9.04e-6, 2) == "9 × 10⁻⁶"
    assert statements.num(0.99999) == "1" and statements.num(999.96) == "1000" and statements.num(2.5, 2) == "2.5"
    assert statements.pct(-0.196555, 3) == "−19.7 %" and statements.num(float("nan")) == "–"


def test_every_class_names_its_cause_and_the_classifier_is_reproducible_from_a_row():
    from linkwork.pipeline.compare import CAUSE, VERDICT_COLOURS, VERDICT_MEANING

    assert set(CAUSE) == set(VERDICT_MEANING) == set(VERDICT_COLOURS) == set(VERDICTS)
    assert set(CAUSE.values()) == {
        "the paper's numbers", "an input the paper does not print", "the paper's model", "our model", "our numerics",
    }
    row = {"published": 1.0, "tolerance": 0.005, "relation": "eq", "reproduced": 1.0, "numerical_error": 0.0,
           "input_low": np.nan, "input_high": np.nan, "in_consistent_set": np.nan, "told": ""}
    assert reclassify(row) == classify(1.0, 0.005, "eq", 1.0, 0.0, np.nan, np.nan) == "reproduced"
    assert reclassify({**row, "told": "model decides"}) == "decided by the paper's model"
    assert reclassify({**row, "reproduced": np.nan, "told": "absent from the model"}) == "no counterpart in this model"
    assert reclassify({**row, "reproduced": np.nan}) == "not printed"


def test_a_parameter_change_that_falsifies_a_finding_shows_it_withdrawn_on_the_page(tmp_path):
    """With every member's modulus set to steel's, the statement that the printed modulus is far below steel's is
    false: the rendered stiffness page shows it struck through, with the condition that failed and the value read."""
    cfg = load_yaml("config/config.yaml")["stiffness"]
    steel = float(cfg["steel_youngs_modulus_Pa"]["value"])
    cfg["members"] = {k: {**v, "youngs_modulus_Pa": steel} for k, v in cfg["members"].items()}
    import html

    page, _, _ = render_stiffness_page(tmp_path, cfg)
    text = re.sub(r"\s+", " ", html.unescape(re.sub(r"<[^>]+>", " ", page[page.index("<body"):])))
    assert "<del>It used 210000 MPa: steel links would be 1 times stiffer." in page
    assert "withdrawn: it needs a printed modulus at least 100 times below steel's (steel >= 100), and the results" \
           " give steel = 1" in text
    answer_start = text.index("Does the paper hold up?")
    assert text.index("withdrawn:", answer_start) < text.index("Other findings that hold", answer_start)
