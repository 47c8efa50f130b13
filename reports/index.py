# ---
# jupyter:
#   jupytext:
#     formats: py:percent
#     text_representation:
#       extension: .py
#       format_name: percent
# ---

# %% [markdown]
# # linkwork: does each paper hold up?
#
# For every paper: the one-sentence answer its findings compute, then its published headline numbers and claims
# counted by verdict class **on the physically defensible model** (stiffness: internal forces from statics; clearance:
# slender-rod inertias; heald: the physical linkage), with the paper's own model counted separately. Table cells
# (Table 3 angles, Table 1 cells) are trivial checks and are counted apart. The classes:
#
# * **matches**: our value, with its numerical error bar and over the whole range of the assumed inputs, lies within the
#   published value's tolerance;
# * **deviates**: it lies outside, whatever the assumed inputs;
# * **undetermined (numerics)**: our own numerical error bar straddles the tolerance;
# * **depends on assumptions**: the verdict changes within the plausible ranges of the assumed inputs (the report names
#   the input that decides);
# * **not reproducible**: the paper lacks what reproducing the number needs.

# %%
import pandas as pd
from _common import esc, inputs, load, md, table

from linkwork.papers import PAPERS

files = inputs()
CLASSES = ["matches", "deviates", "undetermined (numerics)", "depends on assumptions", "not reproducible"]


def counts(findings, model: str, role: str) -> str:
    c = findings.verdict_count.sel(count_model=model, role=role)
    parts = [f"{int(c.sel(verdict=v))} {v}" for v in CLASSES if int(c.sel(verdict=v))]
    return ", ".join(parts) if parts else "none"


rows = []
for paper, title in PAPERS.items():
    findings = load(files[f"findings_{paper}"])
    models = [str(m) for m in findings.count_model.values]
    defensible = findings.attrs["defensible_model"] or models[0]
    own = findings.attrs["paper_model"]
    rows.append({
        "paper": f'<a href="{paper}.html">{paper}</a>',
        "title": esc(title),
        "does it hold up?": esc(findings.attrs["answer"]),
        "headline, defensible model": (f"{esc(defensible)}: " if defensible else "") + counts(findings, defensible, "headline"),
        "headline, the paper's own model": f"{esc(own)}: {counts(findings, own, 'headline')}" if own and own != defensible else "(the same model)",
        "table cells (trivial checks)": counts(findings, defensible, "table cell"),
    })
table(pd.DataFrame(rows), html_columns=("paper", "title", "does it hold up?", "headline, defensible model", "headline, the paper's own model", "table cells (trivial checks)"))
md(
    'What accuracy costs in time, for every numerical method of the pipeline: <a href="accuracy.html">accuracy report</a>. '
    'Parameter sweeps: <a href="sweeps.html">sweeps report</a>.'
)
