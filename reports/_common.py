"""Helpers shared by the report scripts (presentation only: load, format, show; no numerics).

A report is run by workflow/scripts/render_report.py, which passes its inputs by name as absolute
paths in the environment variable LINKWORK_REPORT; the rule file workflow/rules/reports.smk is the one
place that says which files each report reads.  Text that comes from config or results is escaped
before it reaches the HTML.
"""

from __future__ import annotations

import html
import json
import os
from pathlib import Path

import pandas as pd
from IPython.display import HTML, Markdown, display

from linkwork.pipeline.results import load as load_result

VERDICT_COLOURS = {"matches": "#d9f2d9", "deviates": "#f9d6d5", "not reproducible": "#eeeeee"}


def inputs() -> dict[str, Path | list[Path]]:
    """The report's inputs by name (paths, or lists of paths), as the renderer passed them."""
    given = json.loads(os.environ.get("LINKWORK_REPORT", "{}")).get("inputs", {})
    if not given:
        raise SystemExit("this report is rendered by the pipeline: run `snakemake results/reports/<name>.html`")
    return {k: [Path(p) for p in v] if isinstance(v, list) else Path(v) for k, v in given.items()}


def load(path: Path):
    """Read a report input by its type: netCDF (Dataset), CSV (DataFrame), YAML or JSON (dict)."""
    data = load_result(path)
    if isinstance(data, pd.DataFrame) and "model" in data:
        data["model"] = data["model"].fillna("").astype(str)
    return data


def esc(value) -> str:
    """Text from config or results, safe to put into Markdown/HTML."""
    return html.escape(str(value), quote=True)


def md(text: str) -> None:
    display(Markdown(text))


def _colour_verdict(value: str) -> str:
    colour = VERDICT_COLOURS.get(value)
    return f"background-color: {colour}" if colour else ""


def table(df: pd.DataFrame, formats: dict[str, str] | None = None, caption: str | None = None, html_columns: tuple[str, ...] = ()) -> None:
    """Show a DataFrame with verdict cells coloured; every cell is escaped except ``html_columns`` (links we build)."""
    styler = df.style.hide(axis="index")
    verdict_cols = [c for c in df.columns if "verdict" in str(c)]
    if verdict_cols:
        styler = styler.map(_colour_verdict, subset=verdict_cols)
    plain = [c for c in df.columns if c not in html_columns]
    styler = styler.format(escape="html", subset=plain, na_rep="–")
    if formats:
        styler = styler.format({k: v for k, v in formats.items() if k in df.columns}, na_rep="–", escape="html")
    if caption:
        styler = styler.set_caption(esc(caption))
    display(HTML(styler.to_html()))


def provenance(ds, keys=("paper_id", "study", "linkwork_version", "git_commit", "config_sha256")) -> None:
    """The provenance attributes of a result, as a list."""
    md("\n".join(f"* **{k}**: `{esc(ds.attrs[k])}`" for k in keys if k in ds.attrs))
