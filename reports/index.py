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
# One row per paper: its answer, in plain words, with the terms it uses. The picture below shows the verdict on every
# published headline number and claim of every paper, in every model variant and named scenario; each paper's report
# has the evidence, and the verdict classes say what decides them.

# %% [markdown]
# ## Each paper's answer

# %%
import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from _common import VERDICT_COLOURS, answer_html, caption, esc, inputs, load, md, read_csv, table
from matplotlib.patches import Patch

from linkwork.papers import PAPERS, GLOSSARY, LABELS
from linkwork.pipeline.compare import VERDICT_MEANING, VERDICTS, scenario_of

files = inputs()


rows, blocks, keys = [], [], []
for paper, title in PAPERS.items():
    findings = load(files[f"findings_{paper}"])
    comparison = read_csv(files[f"comparison_{paper}"], keep_default_na=False, na_values=[""])
    rows.append(
        {
            "paper": f'<a href="{paper}.html">{esc(title)}</a>',
            "does it hold up?": answer_html(paper, findings, comparison) + (
                "<br><small><em>" + "; ".join(f"{esc(k)}: {esc(v)}" for k, v in GLOSSARY[paper].items())
                + "</em></small>" if GLOSSARY[paper] else ""
            ),
        }
    )
    headline = comparison[comparison.role == "headline"]
    # a paper with one model or one reading leaves that column empty (NaN): keep its rows (groupby drops NaN keys)
    model_of = headline.model.astype(object).where(headline.model.notna(), "").astype(str)
    for (model, scen), part in headline.groupby([model_of, scenario_of(headline)], sort=False):
        blocks.append((paper, model, scen, list(part.verdict)))
    first = headline[(model_of == model_of.iloc[0]) & (scenario_of(headline) == scenario_of(headline).iloc[0])]
    keys += [{"paper": paper, "column": k + 1, "published number or claim": q} for k, q in enumerate(first.quantity)]
table(pd.DataFrame(rows), html_columns=("paper", "does it hold up?"))

# %% [markdown]
# ## Every published number's verdict, in one picture

# %%
width = max(len(v) for *_, v in blocks)
fig, ax = plt.subplots(figsize=(10, 0.32 * len(blocks) + 1.6), layout="constrained")
for y, (_, _, _, verdicts) in enumerate(blocks):
    for x, v in enumerate(verdicts):
        ax.add_patch(plt.Rectangle((x, y), 0.92, 0.86, color=VERDICT_COLOURS[v]))
labels = [" · ".join(p for p in (paper, model, scen) if p) for paper, model, scen, _ in blocks]
ax.set_xlim(0, width)
ax.set_ylim(len(blocks), 0)
ax.set_yticks(np.arange(len(blocks)) + 0.43, labels, fontsize=8)
ax.set_xticks(np.arange(width) + 0.46, [str(k + 1) for k in range(width)], fontsize=8)
ax.set_xlabel("published headline number or claim, in the order of each paper's comparison table")
ax.tick_params(length=0)
for side in ax.spines.values():
    side.set_visible(False)
used = [v for v in VERDICTS if any(v in b[3] for b in blocks)]
fig.legend(
    handles=[Patch(color=VERDICT_COLOURS[v], label=v) for v in used], loc="outside lower center", ncol=4, fontsize=8
)
ax.set_title("Every paper's headline verdicts, per model variant and named scenario")
plt.show()
caption(
    "One line per paper, model variant and named scenario (a discrete modelling choice, judged apart); one cell per "
    "published headline number or claim, coloured by its verdict class. The classes: "
    + "; ".join(f"{v}: {VERDICT_MEANING[v]}" for v in used)
    + ". The model labels: "
    + "; ".join(f"{paper} · {label}: {text}" for paper, labels in LABELS.items() for label, text in labels.items())
    + f". {sum(len(b[3]) for b in blocks)} cells: every headline row of the {len(PAPERS)} papers' comparison tables;"
    " the table below names each column."
)
table(pd.DataFrame(keys), caption="The columns of the picture: each paper's published numbers and claims, in order",
      collapse=True)

# %% [markdown]
# ## The pages across papers

# %%
md(
    'What accuracy costs in time, for every numerical method of the pipeline: <a href="accuracy.html">accuracy'
    ' report</a>. Parameter sweeps: <a href="sweeps.html">sweeps report</a>.'
)
