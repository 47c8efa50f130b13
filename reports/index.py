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
from _common import inputs, load, md, table

from linkwork.papers import PAPERS

files = inputs()
rows = []
for paper, title in PAPERS.items():
    findings = load(files[f"findings_{paper}"])
    counts = findings.verdict_count
    models = [str(m) for m in counts.count_model.values]
    ref = findings.attrs["reference_model"]
    c = counts.sel(count_model=ref)
    others = "; ".join(
        f"{m}: {int(counts.sel(count_model=m, verdict='matches'))} matched, {int(counts.sel(count_model=m, verdict='deviates'))} deviating, "
        f"{int(counts.sel(count_model=m, verdict='not reproducible'))} n/r" for m in models if m != ref
    )
    link = f'<a href="{paper}.html">{paper} report</a>' + (f" (reference: {ref})" if ref else "")
    rows.append((paper, title, int(c.sel(verdict="matches")), int(c.sel(verdict="deviates")), int(c.sel(verdict="not reproducible")), link, others))
df = pd.DataFrame(rows, columns=["paper", "title", "matched", "deviating", "not reproducible", "report", "other model forms"])
table(df, html_columns=("report",))
md(
    'What accuracy costs in time, for every numerical method of the pipeline: <a href="accuracy.html">accuracy report</a>. '
    'Parameter sweeps: <a href="sweeps.html">sweeps report</a>.'
)
