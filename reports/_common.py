"""Helpers shared by the report scripts (presentation only: load, format, show; no numerics).

A report is run by workflow/scripts/render_report.py, which passes its inputs by name as absolute
paths in the environment variable LINKWORK_REPORT; the rule file workflow/rules/reports.smk is the one
place that says which files each report reads.  Text that comes from config or results is escaped
before it reaches the HTML.
"""

from __future__ import annotations

import html
import json
import math
import os
import re
from pathlib import Path
from types import SimpleNamespace

import pandas as pd
from IPython.display import HTML, Markdown, display

from linkwork.pipeline.compare import VERDICT_COLOURS  # noqa: F401 (the index's matrix reads it from here)
from linkwork.pipeline.results import load as load_result
from linkwork.pipeline.results import verify

RELATION = {"eq": "±", "ge": "≥", "le": "≤"}


def inputs() -> dict[str, Path | list[Path]]:
    """The report's inputs by name (paths, or lists of paths), as the renderer passed them."""
    given = json.loads(os.environ.get("LINKWORK_REPORT", "{}")).get("inputs", {})
    if not given:
        raise SystemExit("this report is rendered by the pipeline: run `snakemake results/reports/<name>.html`")
    return {k: [Path(p) for p in v] if isinstance(v, list) else Path(v) for k, v in given.items()}


def loaded() -> SimpleNamespace:
    """Every input of the report read by its type (``load``), as attributes named as the rule names them (a list input
    as a list): the one place a report's standard inputs (result, comparison, findings, published, uncertainty, ...) are
    read."""
    return SimpleNamespace(**{k: [load(p) for p in v] if isinstance(v, list) else load(v) for k, v in inputs().items()})


def load(path: Path):
    """Read a report input by its type: netCDF (Dataset), CSV (DataFrame), YAML or JSON (dict)."""
    data = load_result(path)
    if isinstance(data, pd.DataFrame):  # text columns empty in every row read back as float NaN: make them text
        for column in ("model", "scenario", "decided_by", "numerical_source", "input_source", "tolerance_source"):
            if column in data:
                data[column] = data[column].astype(object).where(data[column].notna(), "").astype(str)
    return data


def read_csv(path: Path, **options) -> pd.DataFrame:
    """A CSV result read with pandas' ``options``, after its checksum (a truncated or replaced table is named, not
    read)."""
    verify(path)
    return pd.read_csv(path, **options)


def assumed(files) -> dict[str, dict]:
    """The paper's labelled config entries, whole (value, status, reason, range or choices), by dotted key path: read
    from its assumptions result, the one input that carries the reasons (studies receive values only)."""
    ds = load(files["assumptions"])
    return {str(k): json.loads(str(v)) for k, v in zip(ds.entry.values, ds.entry_json.values, strict=True)}


def esc(value) -> str:
    """Text from config or results, safe to put into Markdown/HTML."""
    return html.escape(str(value), quote=True)


def md(text: str) -> None:
    display(Markdown(text))


def _colour_verdict(value: str) -> str:
    colour = VERDICT_COLOURS.get(value)
    return f"background-color: {colour}" if colour else ""


_TABLES = 0


#: A table longer than this many rows is collapsed (<details>): the page shows its caption, a click opens it.
LONG_TABLE_ROWS = 12


def table(
    df: pd.DataFrame,
    formats: dict[str, str] | None = None,
    caption: str | None = None,
    html_columns: tuple[str, ...] = (),
    collapse: bool | None = None,
) -> None:
    """Show a DataFrame with verdict cells coloured; every cell is escaped except ``html_columns`` (links we build).
    A column with the same text in every row (of more than three) is said once, in a note under the table; a table of
    more than LONG_TABLE_ROWS rows is collapsed unless ``collapse`` says otherwise."""
    global _TABLES
    _TABLES += 1  # a counter, not pandas' random uuid, names the table's CSS ids: a rerun writes the same HTML
    constant = [
        c for c in df.columns
        if len(df) > 3 and c not in html_columns and "verdict" not in str(c) and df[c].astype(str).nunique() == 1
    ]
    note = "; ".join(f"{c}: {df[c].iloc[0]}" for c in constant)
    df = df.drop(columns=constant)
    styler = (
        df.style.set_uuid(f"t{_TABLES}")
        .hide(axis="index")
        .set_properties(**{"text-align": "left", "vertical-align": "top"})
    )
    styler = styler.set_table_styles([{"selector": "th", "props": [("text-align", "left")]}])
    verdict_cols = [c for c in df.columns if "verdict" in str(c)]
    if verdict_cols:
        styler = styler.map(_colour_verdict, subset=verdict_cols)
    plain = [c for c in df.columns if c not in html_columns]
    styler = styler.format(escape="html", subset=plain, na_rep="–")
    if formats:
        styler = styler.format({k: v for k, v in formats.items() if k in df.columns}, na_rep="–", escape="html")
    if caption:
        styler = styler.set_caption(esc(caption))
    page = styler.to_html()
    if note:
        page += f"<p><small>The same in every row: {esc(note)}.</small></p>"
    if collapse if collapse is not None else len(df) > LONG_TABLE_ROWS:
        page = f"<details><summary>{esc(caption or 'Table')} ({len(df)} rows: show)</summary>{page}</details>"
    display(HTML(page))


def provenance(ds, keys=("paper_id", "study", "linkwork_version", "git_commit", "config_sha256")) -> None:
    """The provenance attributes of a result, as a list."""
    md("\n".join(f"* **{k}**: `{esc(ds.attrs[k])}`" for k in keys if k in ds.attrs))


def _num(value: float, digits: int = 5) -> str:
    return "–" if pd.isna(value) else f"{value:.{digits}g}"


def _digits_for(value: float, tolerance: float) -> int:
    """Significant digits that resolve a tenth of ``tolerance`` at the size of ``value`` (at least 4)."""
    if pd.isna(value) or pd.isna(tolerance) or tolerance <= 0 or value == 0:
        return 4
    return max(4, math.ceil(math.log10(abs(value) / (0.1 * tolerance))) + 1)


def _range(low: float, high: float, tolerance: float) -> str:
    """Our range over the assumed inputs, to the digits its tolerance needs; one value where no input moves it."""
    if pd.isna(low):
        return "–"
    digits = _digits_for(max(abs(low), abs(high)), tolerance)
    if low == high:
        return f"{_num(low, digits)} (no assumed input moves it)"
    return f"{_num(low, digits)} … {_num(high, digits)}"


#: Unit suffixes of config keys, dropped when a key is named in prose (the unit is in the table's unit column).
_UNIT_SUFFIXES = ("_kg_m3", "_m_s2", "_m_s", "_Pa_s", "_Pa", "_deg", "_rpm", "_m2", "_m4", "_m", "_kg", "_s")
_GREEK = {"theta": "θ", "eta": "η", "zeta": "ζ", "omega": "ω", "alpha": "α", "beta": "β"}
_NAMES = {"youngs_modulus": "Young's modulus"}


def key_words(text: str) -> str:
    """Config key names in ``text`` ('theta4_deg', 'damping_ratio', 'density_kg_m3') as words for prose: the unit
    suffix dropped, Greek letters spelt as such, underscores as spaces ('θ4', 'damping ratio', 'density'); a symbol
    with a capital subscript ('clearance_E', 'M_P') stays as written."""
    def word(m: re.Match) -> str:
        key = m.group(0)
        for suffix in _UNIT_SUFFIXES:
            if key.endswith(suffix) and len(key) > len(suffix):
                key = key[: -len(suffix)]
                break
        if key != key.lower():  # a symbol with a subscript (clearance_E, M_P): kept as written
            return m.group(0)
        if key in _NAMES:
            return _NAMES[key]
        for name, letter in _GREEK.items():
            key = re.sub(rf"^{name}(?=\d|_|$)", letter, key)
        return key.replace("_", " ")

    return re.sub(r"(?<![\w.])[A-Za-z][A-Za-z0-9]*(?:_[A-Za-z0-9]+)+(?![\w.])", word, text)


def published_cell(value: float, tolerance: float, relation: str, source: str, digits: int = 5) -> str:
    """A published value with its acceptance: '1.2 (± 0.005)', '3 (≥ 2.9)'; a one-sided threshold that is our reading
    of a claim in words (not a printed number) says so: '≤ 0.8 (our reading)'."""
    sign = {"ge": "≥", "le": "≤"}.get(str(relation))
    if sign and str(source).startswith("our reading"):
        return f"{sign} {_num(value, digits)} (our reading)"
    if sign:
        edge = value - tolerance if relation == "ge" else value + tolerance
        return f"{_num(value, digits)} ({sign} {_num(edge, 3)})"
    return f"{_num(value, digits)} (± {_num(tolerance, 2)})"


def comparison_table(rows: pd.DataFrame, caption: str | None = None, scale: float = 1.0, digits: int = 5) -> None:
    """Published numbers beside ours with the verdict's ingredients: tolerance and its source, our numerical
    error bar and its source, the range of our value over the assumed inputs, what decides the verdict.
    ``scale`` multiplies every value (a unit change for display, e.g. 1e3 for m -> mm)."""
    scenarios = list(dict.fromkeys(rows["scenario"])) if "scenario" in rows else [""]
    out = pd.DataFrame(
        {
            **({"scenario": rows.scenario} if len(scenarios) > 1 else {}),
            "quantity": rows.quantity,
            "published": [
                published_cell(p * scale, t * scale, r, s, digits)
                for p, t, r, s in zip(
                    rows.published, rows.tolerance, rows.get("relation", ["eq"] * len(rows)), rows.tolerance_source
                )
            ],
            "tolerance from": rows.tolerance_source,
            "ours": [_num(v * scale, digits) for v in rows.reproduced],
            "numerical error (in the row's unit)": [_num(e * scale, 2) for e in rows.numerical_error],
            "error from": rows.numerical_source,
            # where no range is shown, the input source says why (no assumed input enters, none propagated there, ...)
            "over the assumed inputs": [
                (
                    _range(lo * scale, hi * scale, t * scale)
                    if pd.notna(lo)
                    else (src if isinstance(src, str) and src else "–")
                )
                for lo, hi, t, src in zip(
                    rows.input_low, rows.input_high, rows.tolerance, rows.get("input_source", [""] * len(rows))
                )
            ],
            "decided by": rows.decided_by.fillna("").map(key_words),
            "unit": rows.unit,
            "verdict": rows.verdict,
        }
    )
    table(out, caption=caption)
    verdict_legend(rows.verdict)


def verdict_legend(verdicts) -> None:
    """One line under a verdict table: what each class in it means (the shared definitions)."""
    from linkwork.pipeline.compare import VERDICT_MEANING, VERDICTS

    used = [v for v in VERDICTS if v in set(verdicts)]
    if used:
        md("<small>" + "; ".join(f"*{esc(v)}*: {esc(VERDICT_MEANING[v])}" for v in used) + ".</small>")


def oat_table(
    unc,
    quantities: dict[str, str],
    entries: dict[str, dict],
    model: str = "",
    scale: dict[str, float] | None = None,
    caption: str | None = None,
    scenario: int = 0,
    skip: set[str] | frozenset = frozenset(),
) -> None:
    """Each assumed input moved alone over its range (in one scenario, the first by default): the range it gives
    each listed quantity, and why that range (from ``entries``, the labelled config entries: ``assumed``).  The
    input column lists config keys (marked as such).

    ``quantities``: published id -> column label; ``scale``: id -> display factor; ``skip``: input paths (without
    ``.value``) left out of the table, e.g. those a model does not read."""
    scale = scale or {}
    index = {str(q): i for i, q in enumerate(unc.quantity.values)}
    low = unc.oat_low.values[scenario] if "scenario" in unc.oat_low.dims else unc.oat_low.values
    high = unc.oat_high.values[scenario] if "scenario" in unc.oat_high.dims else unc.oat_high.values
    rows = []
    for k, name in enumerate(unc.input.values):
        if str(name).removesuffix(".value") in skip:
            continue
        entry = entries.get(str(name).removesuffix(".value"), {})
        why = (
            entry.get("range_reason") or entry.get("reason") or str(unc.input_reason.values[k])
        )  # a printed value's rounding: its own text
        row = {
            "input (config key)": str(name).removesuffix(".value"),
            "range": str(unc.input_range.values[k]),
            "why": why,
        }
        for qid, label in quantities.items():
            q = index[f"{model}|{qid}"]
            f = scale.get(qid, 1.0)
            row[label] = f"{_num(low[k, q] * f, 4)} … {_num(high[k, q] * f, 4)}"
        rows.append(row)
    table(
        pd.DataFrame(rows),
        caption=caption
        or f"Each assumed input moved alone over its range, the others at their assumed values ({design_text(unc)}).",
    )


def consistent_sets_table(unc, cmp: pd.DataFrame, reads: dict[str, set[str]] | None = None) -> None:
    """Per named scenario and model variant, the best consistent assumption set: how many of the rows that are not
    robust deviations match at once under one set of assumed inputs, which rows, which no consistent set of that
    size reconciles, and where the set lies (the config keys it moves from their assumed values; with ``reads``,
    model -> the input names it reads, only those)."""
    if "consistent_count" not in unc:
        return
    name = {f"{m}|{i}": q for m, i, q in zip(cmp.model.fillna(""), cmp.id, cmp.quantity, strict=True)}
    keys = [str(q) for q in unc.quantity.values]
    nominal = [float(x) for x in unc.input_nominal.values]
    rows = []
    for n, scen in enumerate(unc.scenario.values):
        for m, model in enumerate(unc.row_model.values):
            of_model = [
                k
                for k, q in enumerate(keys)
                if q.startswith(f"{model}|") and pd.notna(unc.matched_in_best_set.values[n, k])
            ]
            if not of_model:
                continue
            best = [name.get(keys[k], keys[k]) for k in of_model if unc.matched_in_best_set.values[n, k] == 1]
            never = [name.get(keys[k], keys[k]) for k in of_model if unc.in_consistent_set.values[n, k] == 0]
            at = unc.consistent_at.values[n, m]
            names = [str(p).removesuffix(".value").rsplit(".", 1)[-1] for p in unc.input.values]
            moved = [f"{names[j]} = {_num(at[j], 4)}" for j in range(at.size)
                     if pd.notna(at[j]) and not math.isclose(at[j], nominal[j], rel_tol=1e-9, abs_tol=0.0)
                     and (reads is None or names[j] in reads.get(str(model), names))]
            rows.append(
                {
                    **({"scenario": str(scen)} if unc.sizes["scenario"] > 1 else {}),
                    **({"model": str(model)} if str(model) else {}),
                    "rows matched at once": (
                        f"{int(unc.consistent_count.values[n, m])} of {int(unc.consistent_candidates.values[n, m])}"
                    ),
                    "matched together": "; ".join(best) or "none",
                    "not reconciled with them": "; ".join(never) or "none",
                    "the set: config keys moved from their assumed values": (
                        ", ".join(moved) or "none (the assumed values)"
                    ),
                }
            )
    if rows:
        table(
            pd.DataFrame(rows),
            caption=(
                "The best consistent assumption set per scenario: one point of the assumed inputs' box under which most"
                " of the rows that are not robust deviations match at once (found by bounded searches). A row 'depends"
                " on assumptions' only if it matches in such a set; a row that matches only where the others fail is"
                " 'only where other rows fail'."
            ),
        )


def design_text(unc) -> str:
    """The sample design of an uncertainty study in words, from what it holds (counts of each kind of sample)."""
    labels = [str(x) for x in unc.sample.values]
    lhs = sum(" lhs " in f" {x.split(' | ')[-1]} " for x in labels)
    corners = sum(x.split(" | ")[-1].startswith("corner ") for x in labels)
    scen = unc.sizes.get("scenario", 1)
    parts = [
        f"{int(unc.samples)} samples in all" + (f" over {scen} scenarios" if scen > 1 else ""),
        "nominal and one at a time",
    ]
    if corners:
        parts.append(f"{corners} box corners")
    parts.append(f"{lhs} Latin-hypercube points" if lhs else "no Latin hypercube")
    if "low_at" in unc:
        parts.append(
            "then bounded searches of each headline value's extremes (at most"
            f" {int(unc.attrs.get('search_evaluations', 0))} evaluations each)"
        )
    return "; ".join(parts)


def answer(paper: str, findings, comparison) -> None:
    """The paper's answer at the top of its report, then its other findings grouped: what also holds, what also does
    not, what cannot be tested (each statement rendered from the results; a withdrawn one struck through with its
    failed condition)."""
    from linkwork.pipeline import statements

    rendered = statements.render(paper, findings, comparison)
    md(f"**Does the paper hold up?** {statements.answer(rendered)}")
    groups = statements.by_kind([r for r in rendered if r.answer is None])  # the answer's own are said above
    titles = {"holds": "Other findings that hold", "does not hold": "Other findings that do not hold",
              "cannot be tested": "Open: decided by what the paper does not give, or by its model",
              "beyond the paper": "Our findings beyond the paper's claims",
              "the source text": "Notes on the source text"}
    md("\n\n".join(
        f"**{titles[kind]}**\n\n" + "\n".join(f"* {r.markdown()}" for r in groups[kind])
        for kind in statements.KINDS if groups[kind]
    ))
    md('<div class="contents-here"></div>')  # the page's table of contents goes here (render_report)


def answer_html(paper: str, findings, comparison) -> str:
    """The paper's answer as HTML, for a table cell (the index)."""
    from linkwork.pipeline import statements

    return statements.answer_html(statements.render(paper, findings, comparison))


def declutter(fig) -> int:
    """Hide every point label (an axes' annotation) that would overlap a label placed before it, or any other text of
    its axes (title, axis labels, tick labels, legend), at the figure's size; returns how many were hidden (a caption
    says that labels that would overlap are left out)."""
    from matplotlib.transforms import Bbox

    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    hidden = 0
    for ax in fig.axes:
        fixed = [ax.title, ax.xaxis.label, ax.yaxis.label, *ax.get_xticklabels(), *ax.get_yticklabels()]
        if ax.get_legend() is not None:
            fixed.append(ax.get_legend())
        kept = [a.get_window_extent(renderer) for a in fixed if a.get_visible()]
        inside = ax.get_window_extent(renderer)
        for text in ax.texts:
            box = text.get_window_extent(renderer)
            if text.get_clip_on():  # drawn clipped to the axes: only its part inside can clash
                box = Bbox.intersection(box, inside)
                if box is None:
                    continue
            if any(box.overlaps(other) for other in kept):
                text.set_visible(False)
                hidden += 1
            else:
                kept.append(box)
    return hidden


def newmark_convergence(ax, ked) -> None:
    """The Newmark step study of the transplanter's dynamic stress (``ked``: its result): the field and peak errors
    against the reference step, a slope-2 guide, the observed order between neighbouring steps, the pipeline's step."""
    ax.loglog(
        ked.newmark_step, ked.newmark_field_error, "o-",
        label="stress field: max |σ − σ_ref| / peak (bounds the peak's error)",
    )
    ax.loglog(ked.newmark_step, ked.newmark_peak_error, "s--", label="peak stress itself")
    first = float(ked.newmark_field_error[0])
    ax.loglog(ked.newmark_step, first * (ked.newmark_step / float(ked.newmark_step[0])) ** 2, "k:", lw=1,
              label="slope 2")
    ax.axvline(float(ked.newmark_pipeline_step), color="C3", ls=":",
               label=f"pipeline step {float(ked.newmark_pipeline_step):g}°")
    for h, p_ in zip(ked.newmark_pair.values, ked.newmark_order.values):
        ax.annotate(f"order {p_:.2f}", (h, float(ked.newmark_field_error.sel(newmark_step=h))),
                    textcoords="offset points", xytext=(6, -12), fontsize=8)
    ax.set_xlabel("Newmark step (deg of crank angle)")
    ax.set_ylabel("relative error vs the reference step")
    ax.set_title(f"dynamic stress at our optimum (reference {ked.attrs['newmark_reference_step_deg']:g}°)", fontsize=10)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7)


def caption(text: str) -> None:
    """A figure caption (escaped), shown under the figure."""
    md(f"*Figure: {esc(text.strip())}*")  # a space before the closing '*' would leave the emphasis unrendered


def show_log_log(ax, xlabel: str, ylabel: str, text: str) -> None:
    """Label a log-log panel, grid it, show its legend and the figure, then its caption."""
    import matplotlib.pyplot as plt

    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    plt.show()
    caption(text)


def verdict_figure(rows: pd.DataFrame, title: str, note: str = "") -> None:
    """Each published number's acceptance band (grey, |ours - published| <= tolerance) against our nominal value (dot),
    our numerical error bar (black whisker) and our range over the assumed inputs (blue bar, drawn only where the
    assumed inputs move the value), all in units of the tolerance.  Rows with a zero tolerance or no value of ours are
    left out.  ``note`` is added to the caption (e.g. the sense and sign convention the numbers are judged in)."""
    import textwrap

    import matplotlib.pyplot as plt
    import numpy as np
    from matplotlib.ticker import FuncFormatter

    rows = rows[(rows.tolerance > 0) & rows.reproduced.notna()]
    if rows.empty:
        return
    labels = [textwrap.fill(str(q), 48) for q in rows.quantity]
    lines = sum(label.count("\n") + 1 for label in labels)
    fig, ax = plt.subplots(figsize=(10, 0.3 * lines + 0.25 * len(rows) + 1.8), layout="constrained")
    y = np.arange(len(rows))[::-1]
    scale = rows.tolerance.to_numpy()
    nominal = (rows.reproduced.to_numpy() - rows.published.to_numpy()) / scale
    low = (rows.input_low.to_numpy() - rows.published.to_numpy()) / scale
    high = (rows.input_high.to_numpy() - rows.published.to_numpy()) / scale
    error = np.nan_to_num(rows.numerical_error.to_numpy() / scale)
    for yi, rel in zip(y, rows.get("relation", ["eq"] * len(rows))):
        ax.fill_betweenx([yi - 0.35, yi + 0.35], -1, 1e9 if rel == "ge" else 1, color="0.85", lw=0)
    moved = np.isfinite(low) & np.isfinite(high) & (low != high)
    if moved.any():
        ax.hlines(y[moved], low[moved], high[moved], color="C0", lw=5, alpha=0.6, label="ours over the assumed inputs")
    ax.errorbar(
        nominal, y, xerr=error, fmt="o", color="k", ms=5, capsize=3, label="ours at nominal inputs (± numerical error)"
    )
    ax.axvline(0, color="k", lw=0.8)
    span = np.nanmax(np.abs(np.concatenate([nominal, low, high, [1.5]])))
    ax.set_xlim(-1.15 * span, 1.15 * span)
    if span > 50:
        ax.set_xscale("symlog", linthresh=1.0)
        ax.xaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    ax.set_yticks(y, labels, fontsize=8)
    ax.set_ylim(-0.7, len(rows) - 0.3)
    ax.set_xlabel("(our value − published) / tolerance   (grey: within the tolerance)")
    ax.set_title(title)
    ax.grid(alpha=0.3, axis="x")
    fig.legend(fontsize=8, loc="outside lower center", ncol=2)
    plt.show()
    caption(
        f"{title}: for each published number the grey band is the published value ± its tolerance; the dot is ours at"
        " the nominal inputs with its numerical error bar"
        + (
            ", the blue bar our range over the assumed inputs"
            if moved.any()
            else " (no assumed input moves these values)"
        )
        + ", all divided by the tolerance."
        + (f" {note}" if note else "")
    )
