"""Findings as the unit of prose: each paper's statements, declared as text with placeholders, the result values they
read and the conditions under which they are true, rendered from the results.

A paper declares its findings in ``lib/linkwork/papers/<paper>/statements.yaml``::

    findings:
      - id: magnitudes                 # unique within the paper
        answer: 1                      # rank in the paper's answer (absent: the report's list only)
        kind: does not hold            # holds | does not hold | cannot be tested (the report's list groups by it)
        text: >-
          The printed modulus ({{ E_MPa | num }} MPa) is {{ (210e3 / E_MPa) | num(2) }} times below steel's.
        values:                        # name -> where the number is read
          E_MPa: {variable: youngs_modulus, scale: 1.0e-6}                 # findings.nc, optional sel: {dim: label}
          dev: {row: {model: equilibrium, id: K_h_max}, column: relative_deviation}   # comparison.csv
        when:                          # every condition must hold for the sentence to be true
          - {test: "E_MPa < 1000", says: "the printed modulus is far below steel's"}

The text is a Jinja2 template (a sandboxed environment: no attribute access to Python internals, no imports), and each
``test`` a Jinja2 expression over the same values.  A statement whose condition fails at the results is rendered
visibly withdrawn, struck through, with the condition that failed and the values it read: a parameter change never
leaves a sentence silently true.  No number enters the prose except through ``values``.
"""

from __future__ import annotations

import html
import math
import re
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
import xarray as xr
import yaml
from jinja2 import StrictUndefined
from jinja2.sandbox import SandboxedEnvironment

#: How the report groups statements: what holds, what does not, what cannot be tested, what we found beyond the paper's
#: claims, and notes on the source text.
KINDS = ("holds", "does not hold", "cannot be tested", "beyond the paper", "the source text")
PAPERS_DIR = Path(__file__).resolve().parent.parent / "papers"


def statements_path(paper: str) -> Path:
    """The statements file of one paper."""
    return PAPERS_DIR / paper / "statements.yaml"


SUPERSCRIPT = str.maketrans("-0123456789", "⁻⁰¹²³⁴⁵⁶⁷⁸⁹")


def num(value: float, digits: int = 3) -> str:
    """A number for prose: ``digits`` significant digits (trailing zeros dropped), a power of ten outside 1e-3 to 1e6,
    a real minus sign ('−19.7', '1930', '9 × 10⁻⁶')."""
    value = float(value)
    if not math.isfinite(value):
        return "–"
    if value == 0:
        return "0"
    exponent = math.floor(math.log10(abs(float(f"{value:.{digits}g}"))))
    if -3 <= exponent < 6:
        decimals = max(digits - 1 - exponent, 0)
        text = f"{round(value, digits - 1 - exponent):.{decimals}f}"
        text = text.rstrip("0").rstrip(".") if "." in text else text
    else:
        mantissa = f"{value / 10 ** exponent:.{digits}g}"
        text = f"{mantissa} × 10{str(exponent).translate(SUPERSCRIPT)}"
    return text.replace("-", "−")


def pct(value: float, digits: int = 2) -> str:
    """A fraction as a percentage for prose ('0.197' -> '19.7 %')."""
    return f"{num(100 * float(value), digits)} %"


def _environment() -> SandboxedEnvironment:
    env = SandboxedEnvironment(undefined=StrictUndefined, autoescape=False, keep_trailing_newline=False)
    env.filters.update(num=num, pct=pct, abs=abs)
    env.globals.update(min=min, max=max, abs=abs, round=round, zip=zip)
    return env


ENV = _environment()


@dataclass(frozen=True)
class Rendered:
    """One statement rendered at the results: its text, whether every condition held, and the first that failed."""

    id: str
    kind: str
    answer: int | None
    text: str
    holds: bool
    failed: str = ""

    def markdown(self) -> str:
        """The statement as Markdown (HTML-escaped): its text, or its text struck through with the failed condition."""
        text = html.escape(self.text, quote=False)
        if self.holds:
            return text
        return f"~~{text}~~ *(withdrawn: {html.escape(self.failed, quote=False)})*"

    def html(self) -> str:
        """The statement as HTML: its text, or its text struck through with the failed condition."""
        text = html.escape(self.text, quote=False)
        if self.holds:
            return text
        return f"<del>{text}</del> <em>(withdrawn: {html.escape(self.failed, quote=False)})</em>"


class StatementError(ValueError):
    """A statements file names a value the results do not hold, or a template that does not render."""


def load(paper: str, path: Path | None = None) -> list[dict[str, Any]]:
    """The declared findings of one paper (the file's ``findings`` list)."""
    path = path or statements_path(paper)
    with open(path, encoding="utf-8") as f:
        data = yaml.safe_load(f)
    findings = data["findings"]
    ids = [f["id"] for f in findings]
    if len(set(ids)) != len(ids):
        raise StatementError(f"{path}: duplicate finding ids")
    for f in findings:
        if f.get("kind", "holds") not in KINDS:
            raise StatementError(f"{path}: finding {f['id']}: kind must be one of {KINDS}, got {f.get('kind')!r}")
    return findings


def read_value(spec: Mapping[str, Any], findings: xr.Dataset, table: pd.DataFrame) -> Any:
    """One value a statement reads: a findings variable (optionally selected and scaled), a comparison-table cell,
    or a findings attribute (``attr``)."""
    if "attr" in spec:
        return findings.attrs[spec["attr"]]
    if "row" in spec:
        rows = table
        for key, want in spec["row"].items():
            column = rows[key].astype(object).where(rows[key].notna(), "").astype(str)
            rows = rows[column == str(want)]
        if len(rows) != 1:
            raise StatementError(f"comparison row {dict(spec['row'])} matches {len(rows)} rows, not one")
        value = rows.iloc[0][spec["column"]]
        return float(value) * float(spec.get("scale", 1.0)) if spec["column"] not in ("verdict", "decided_by") \
            else str(value)
    da = findings[spec["variable"]]
    if "sel" in spec:
        da = da.sel(spec["sel"])
    if "reduce" in spec:
        da = getattr(da, spec["reduce"])()
    values = np.asarray(da.values)
    if values.dtype.kind in "OUS":
        return str(values.ravel()[0]) if values.size == 1 else [str(v) for v in values.ravel()]
    scaled = values.astype(float) * float(spec.get("scale", 1.0))
    return float(scaled.ravel()[0]) if scaled.size == 1 else scaled.ravel().tolist()


def values_of(finding: Mapping[str, Any], findings: xr.Dataset, table: pd.DataFrame) -> dict[str, Any]:
    """Every value one statement reads, by name."""
    out = {}
    for name, spec in (finding.get("values") or {}).items():
        try:
            out[name] = read_value(spec, findings, table)
        except (KeyError, StatementError) as exc:
            raise StatementError(f"finding {finding['id']}: value {name}: {exc}") from None
    return out


def _shown(values: Mapping[str, Any], test: str) -> str:
    """The values a failed condition read, for the withdrawal note ('E_MPa = 210')."""
    named = [n for n in values if re.search(rf"\b{re.escape(n)}\b", test)]
    return ", ".join(f"{n} = {num(values[n]) if isinstance(values[n], float) else values[n]}" for n in named)


def render_one(finding: Mapping[str, Any], findings: xr.Dataset, table: pd.DataFrame) -> Rendered:
    """One statement at the results: its conditions checked, its text rendered."""
    values = values_of(finding, findings, table)
    failed = ""
    for cond in finding.get("when") or []:
        if not bool(ENV.compile_expression(cond["test"])(**values)):
            failed = f"it needs {cond['says']} ({cond['test']}), and the results give {_shown(values, cond['test'])}"
            break
    text = " ".join(ENV.from_string(finding["text"]).render(**values).split())
    return Rendered(finding["id"], finding.get("kind", "holds"), finding.get("answer"), text, not failed, failed)


def render(paper: str, findings: xr.Dataset, table: pd.DataFrame, path: Path | None = None) -> list[Rendered]:
    """Every declared statement of a paper, rendered at its results, in declaration order."""
    return [render_one(f, findings, table) for f in load(paper, path)]


def answer(rendered: list[Rendered]) -> str:
    """The paper's answer: its answer statements in rank order, withdrawn ones shown as such (Markdown)."""
    ranked = sorted((r for r in rendered if r.answer is not None), key=lambda r: r.answer)
    return " ".join(r.markdown() for r in ranked)


def answer_html(rendered: list[Rendered]) -> str:
    """The paper's answer as HTML (for table cells)."""
    ranked = sorted((r for r in rendered if r.answer is not None), key=lambda r: r.answer)
    return " ".join(r.html() for r in ranked)


def plain_answer(rendered: list[Rendered]) -> str:
    """The answer's words without markup (for counting words and for plain-text places)."""
    ranked = sorted((r for r in rendered if r.answer is not None), key=lambda r: r.answer)
    return " ".join(r.text if r.holds else f"{r.text} (withdrawn: {r.failed})" for r in ranked)


def by_kind(rendered: list[Rendered]) -> dict[str, list[Rendered]]:
    """The statements grouped as the report lists them: what holds, what does not, what cannot be tested."""
    return {k: [r for r in rendered if r.kind == k] for k in KINDS}
