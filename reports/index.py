# ---
# jupyter:
#   jupytext:
#     formats: py:percent
#     text_representation:
#       extension: .py
#       format_name: percent
# ---

# %% [markdown]
# # linkwork: published vs reproduced, paper by paper
#
# Each row counts the published numbers of one paper that our re-derivation
# **matches** (within half a unit of the last printed digit, or the tolerance given in
# `config/published/<paper>.yaml`), that **deviate** beyond that tolerance, or that are
# **not reproducible** from what the paper gives. Where a paper is compared under several
# models or parameter sets (stiffness: the paper's printed model vs the statics-consistent
# one; heald: chain models A and B; clearance: decoded vs slender-rod inertias), the counts
# are for the reference one named in the row, and the others are summarised in the last
# column. Each report explains them.

# %%
import pandas as pd
from _common import load, md, report_context, table

from linkwork.compare import verdict_counts

inputs, params = report_context({})
papers = params.get("papers", ["stiffness", "beatup", "clearance", "transplanter", "heald"])
reference = params.get("reference_forms", {})
titles = {
    "stiffness": "Huang, Wu, Li 2022: equivalent stiffness of a coupled four-bar (energy method)",
    "beatup": "Gao 1983: six-bar beating-up mechanism vs four-bar",
    "clearance": "Li et al.: four-bar with clearance joints and lubrication",
    "transplanter": "Li, Xu 2001: elastodynamic design of a crank-rocker transplanter",
    "heald": "Grigoriev, Kheylo 2021: mechanical chains of a heald motion",
}
rows = []
for paper in papers:
    path = inputs.get(f"comparison_{paper}")
    if path is None or not path.exists():
        rows.append((paper, titles.get(paper, ""), None, None, None, "not yet built", ""))
        continue
    cmp = load(path)  # papers with a single model leave the model column empty ("")
    ref = reference.get(paper, cmp.model.iloc[0] if len(cmp) else "")
    counts = verdict_counts(cmp[cmp.model == ref])
    others = []
    for model, group in cmp.groupby("model"):
        if model != ref:
            c = verdict_counts(group)
            others.append(f"{model}: {c['matches']} matched, {c['deviates']} deviating, {c['not reproducible']} n/r")
    link = f'<a href="{paper}.html">{paper} report</a>' + (f" (reference form: {ref})" if ref else "")
    rows.append((paper, titles.get(paper, ""), counts["matches"], counts["deviates"], counts["not reproducible"], link, "; ".join(others)))
df = pd.DataFrame(rows, columns=["paper", "title", "matched", "deviating", "not reproducible", "report", "other model forms"])
for col in ("matched", "deviating", "not reproducible"):
    df[col] = df[col].map(lambda v: "–" if pd.isna(v) else f"{int(v)}")
table(df)
md(
    f"{sum(r[5] != 'not yet built' for r in rows)} of {len(rows)} papers built. What accuracy costs in time, for every "
    'numerical method of the pipeline: <a href="accuracy.html">accuracy report</a>. Parameter sweeps: '
    '<a href="sweeps.html">sweeps report</a>.'
)
