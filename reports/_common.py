"""Helpers shared by the report scripts (presentation only, no numerics).

A report is run by workflow/scripts/render_report.py, which passes its inputs
as absolute paths in the environment variable LINKWORK_REPORT.  Run by hand
(for example with jupytext in a notebook) the report falls back to the
default paths below, relative to the project folder.
"""

from __future__ import annotations

import json
import os
from pathlib import Path

import pandas as pd
from IPython.display import HTML, Markdown, display

PROJECT = Path(__file__).resolve().parent.parent
VERDICT_COLOURS = {"matches": "#d9f2d9", "deviates": "#f9d6d5", "not reproducible": "#eeeeee"}


def report_context(defaults: dict[str, str]) -> tuple[dict[str, Path], dict]:
    """(inputs, params) given by the renderer, else the defaults (project-relative paths)."""
    given = json.loads(os.environ.get("LINKWORK_REPORT", "{}"))
    inputs = {k: Path(v) for k, v in given.get("inputs", {}).items()}
    for key, rel in defaults.items():
        inputs.setdefault(key, PROJECT / rel)
    return inputs, given.get("params", {})


def load(path: Path):
    """Read a report input by its type: netCDF (loaded Dataset), CSV (DataFrame), YAML or JSON (dict)."""
    path = Path(path)
    if path.suffix == ".nc":
        import xarray as xr

        with xr.open_dataset(path) as ds:
            return ds.load()
    if path.suffix == ".csv":
        return pd.read_csv(path, dtype={"model": "string"}, keep_default_na=True).assign(model=lambda d: d["model"].fillna(""))
    if path.suffix in (".yaml", ".yml"):
        import yaml

        return yaml.safe_load(path.read_text())
    if path.suffix == ".json":
        return json.loads(path.read_text())
    raise ValueError(f"no reader for {path}")


def md(text: str) -> None:
    display(Markdown(text))


def _colour_verdict(value: str) -> str:
    colour = VERDICT_COLOURS.get(value)
    return f"background-color: {colour}" if colour else ""


def table(df: pd.DataFrame, formats: dict[str, str] | None = None, caption: str | None = None) -> None:
    """Show a DataFrame with verdict cells coloured."""
    styler = df.style.hide(axis="index")
    verdict_cols = [c for c in df.columns if "verdict" in str(c)]
    if verdict_cols:
        styler = styler.map(_colour_verdict, subset=verdict_cols)
    if formats:
        styler = styler.format({k: v for k, v in formats.items() if k in df.columns}, na_rep="–")
    if caption:
        styler = styler.set_caption(caption)
    display(HTML(styler.to_html()))
