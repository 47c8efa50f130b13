# ---
# jupyter:
#   jupytext:
#     formats: py:percent
#     text_representation:
#       extension: .py
#       format_name: percent
# ---

# %% [markdown]
# # What accuracy costs in time: every numerical method of the pipeline
#
# Each panel is a work-precision plot: error against the method's reference versus wall time, with every point
# labelled by its setting and the pipeline's setting marked by a star. Times are measured inside the studies (median of
# several repeats after a warm-up) and kept in `results/accuracy/timings.json`, not in the netCDF, so that reruns
# stay byte-identical. Errors are relative. An exact method is plotted at 1e-16. The clearance integrators have a
# panel per kind of scene, because the pipeline has a setting for each and each is measured in its own way: in the
# dry scene the journal eccentricity over the first impacts relative to the clearance, in the lubricated one the
# claims' RMS measure (the clearance report, section 5, says why).

# %%
import textwrap

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from _common import caption, declutter, inputs, load, md, newmark_convergence, show_log_log, table

from linkwork.papers.clearance.words import in_words

files = inputs()
ds = load(files["result"])
timing = load(files["timings"])
times = timing["seconds"]
df = pd.DataFrame(
    {
        "method": ds.method.values,
        "setting": ds.setting.values,
        "error": ds.error.values,
        "pipeline": ds.pipeline.values.astype(bool),
    }
)
df["time_s"] = [times[f"{m}/{s}"] for m, s in zip(df.method, df.setting)]
df["setting"] = df.setting.map(in_words)  # the clearance scenes by name, not by code
df["method"] = df.method.map(in_words)
methods = list(dict.fromkeys(df.method))

# %%
n_rows = -(-len(methods) // 3)  # one panel per method, three to a row
fig, axes = plt.subplots(n_rows, 3, figsize=(16, 4.5 * n_rows), constrained_layout=True, squeeze=False)
for ax, method in zip(axes.flat, methods):
    sub = df[df.method == method]
    family = sub.setting.map(
        lambda x: (
            "mode superposition"
            if x.endswith("modes")
            else (
                "uniform grid"
                if x.endswith("points")
                else x.split()[0] + (" " + x[x.rfind("(") :] if x.endswith(")") else "")
            )
        )
    )
    for fam in dict.fromkeys(family):
        part = sub[family == fam]
        ax.loglog(part.time_s, part.error, "o-", ms=4, label=fam)
    ax.figure.canvas.draw()  # the limits are set: each label leans away from the panel's nearer edges
    for _, r in sub.iterrows():
        fx, fy = ax.transAxes.inverted().transform(ax.transData.transform((r.time_s, r.error)))
        ax.annotate(  # clipped to the panel as a last resort: a label never runs over another panel's text
            r.setting.replace("central differences ", "").rsplit(" (", 1)[0], (r.time_s, r.error), fontsize=7,
            alpha=0.85, xytext=(-3 if fx > 0.55 else 3, -3 if fy > 0.8 else 3), textcoords="offset points",
            ha="right" if fx > 0.55 else "left", va="top" if fy > 0.8 else "bottom", clip_on=True,
        )
    pipe = sub[sub.pipeline]
    ax.plot(pipe.time_s, pipe.error, "k*", ms=15, label="pipeline setting")
    ax.set_title(textwrap.fill(method, 38), fontsize=9)
    ax.set_xlabel("wall time (s)")
    ax.set_ylabel("relative error")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7)
for ax in axes.flat[len(methods):]:
    ax.axis("off")
left_out = declutter(fig)
plt.show()
caption(
    "Error against each method's reference versus wall time (log-log), one panel per numerical method; points are"
    " labelled by their setting"
    + (f" ({left_out} labels that would overlap another are left out; the tables below list every setting)"
       if left_out else "")
    + ", the star is the pipeline's setting. Exact methods are entered at 1e-16."
)

# %% [markdown]
# ## The FE mesh: why the peak stress converges at order 1
#
# The transplanter's peak stress is the largest of h|v''| + |u'| over the frame (the paper's eq. (8) divided by E).
# Its error against the finest mesh falls slowly with the elements' size, at about first order for the quintic element
# and not much faster for the cubic one (the table), far below what their bending interpolation gives. The first-order
# term is the axial strain: the paper's element interpolates the axial displacement linearly, so u' is constant over an
# element, its mean; where the bending peak sits (at a member's end) the inertia loads make the true axial strain vary
# along the member, and the element's mean misses it by O(h). On a cantilever with a known solution (a test of the
# suite, on the same elements) the curvature at the clamp converges at order 2 (cubic) or is exact (quintic), the
# element's axial strain at order 1, and so does their sum. We keep the paper's element and its stress recovery; the
# term is the mesh's share of the error bar.

# %%
fe = df[df.method == in_words("FE mesh and modes")]
fe_rows = []
for kind in ("frame6", "quintic8"):
    part = fe[fe.setting.str.startswith(kind)]
    levels = [int(x.rsplit("x", 1)[1]) for x in part.setting]
    err = part.error.to_numpy()
    orders = np.log2(err[:-1] / err[1:]) / np.log2(np.array(levels[1:]) / np.array(levels[:-1]))
    fe_rows.append(
        {
            "element": {"frame6": "cubic (frame6)", "quintic8": "quintic (the paper's, quintic8)"}[kind],
            "errors at x1, x2, x4, x8 (vs x16)": ", ".join(f"{e:.2g}" for e in err),
            "observed orders between neighbours": ", ".join(f"{o:.2f}" for o in orders),
        }
    )
table(
    pd.DataFrame(fe_rows),
    caption=(
        "The FE mesh study's peak-stress errors against the quintic mesh with 16 times the elements, and the orders"
        " they show. At order 1 the reference itself carries about the x8 mesh's error, so the finer points understate"
        " theirs by up to that much"
    ),
)

# %% [markdown]
# ## Newmark's time step (the transplanter's dynamic stress)
#
# The transplanter's dynamic solution integrates the finite-element model in time with Newmark's average-acceleration
# rule, a second-order method. Its step study is the transplanter paper's own (error against a reference step, not
# against wall time), shown here beside the other methods.

# %%
if "newmark" in files:
    ked = load(files["newmark"])
    fig, ax = plt.subplots(figsize=(7, 4.5), constrained_layout=True)
    newmark_convergence(ax, ked)
    plt.show()
    caption(
        "Relative error of the transplanter's dynamic stress at our optimum against the Newmark step (degrees of"
        f" crank angle), measured against a reference step of {ked.attrs['newmark_reference_step_deg']:g}°: the"
        " largest error over the stress field (which bounds the peak's) and the peak's own, a slope-2 guide, the"
        " observed order between neighbouring steps and the pipeline's step."
    )
    md(
        f"Observed orders {', '.join(f'{v:.2f}' for v in ked.newmark_order.values)} against the rule's 2. At the"
        f" pipeline's step of {float(ked.newmark_pipeline_step):g}° the error bound is"
        f" {float(ked.newmark_pipeline_error):.1e} of the peak stress."
    )

# %% [markdown]
# ## What a user gains or loses by moving each setting
#
# For each method: the pipeline's setting, its error and time, and the most accurate other setting that was tried,
# with its time as a multiple of the pipeline's.

# %%
rows = [
    (
        in_words(m), in_words(h["pipeline_setting"]), h["pipeline_error"], h["pipeline_s"],
        in_words(h["best_other_setting"]), h["best_other_error"], h["best_other_time_ratio"],
    )
    for m, h in timing["highlights"].items()
]
table(
    pd.DataFrame(
        rows,
        columns=[
            "method", "pipeline setting", "its error", "its time (s)", "most accurate other setting", "its error ",
            "its time / pipeline's",
        ],
    ),
    {"its error": "{:.1e}", "its error ": "{:.1e}", "its time (s)": "{:.2e}", "its time / pipeline's": "{:.1f}"},
)
md(
    "Reading the table: where the most accurate other setting is both less accurate and slower, the pipeline's choice"
    " dominates (analytic derivatives, the closed-form strain energy, K⁻¹F instead of mode superposition). Where it is"
    " more accurate, its time ratio is the price of that accuracy. Errors are relative to each method's own reference"
    " (a finer setting or an exact route); exact methods are entered at 1e-16."
)

# %%
table(
    df.sort_values(["method", "time_s"]).rename(columns={"time_s": "wall time (s)"}),
    {"error": "{:.1e}", "wall time (s)": "{:.2e}"},
)

# %% [markdown]
# ## Integrators side by side: linkwork, scipy and Exudyn on one clearance scene
#
# One dry clearance scene, the same horizon, the same tight reference and the same error measure (the claims' RMS
# deviation from the ideal curve) for linkwork's compiled Dormand–Prince, scipy's integrators stepped around the same
# compiled right-hand side, and Exudyn (its own model: exact constraints instead of Baumgarte's, so a pointwise
# measure would compare the models). In a dry scene that measure also reads the impacts' sensitivity to the start
# state (the clearance report, section 5, gives its size), so only differences above it rank the methods. It runs with
# `make crosscheck`. The question it answers: is the hand-written compiled integrator worth keeping, or would scipy's
# do? The rule, set beforehand: if a scipy integrator needs at most twice linkwork's time at equal error (the median
# over linkwork's error levels), use it.

# %%
if "crosscheck_wp" in files:
    import numpy as np

    xw = load(files["crosscheck_wp"])
    fig, ax = plt.subplots(figsize=(9, 5.5), constrained_layout=True)
    methods = list(dict.fromkeys(str(s).split()[0] for s in xw.setting.values))
    for m in methods:
        sel = [i for i, s in enumerate(xw.setting.values) if str(s).split()[0] == m]
        e, t = xw.error.values[sel], xw.time_s.values[sel]
        ok = np.isfinite(e) & np.isfinite(t)
        origin = "linkwork, compiled" if m in ("dopri5", "rk4") else "scipy on the compiled right-hand side"
        ax.loglog(t[ok], np.maximum(e[ok], 1e-16), "o-", label=f"{m} ({origin})")
    ax.loglog(xw.exudyn_time_s.values, xw.exudyn_error.values, "s--", label="Exudyn (Newmark, fixed step)")
    show_log_log(
        ax,
        "wall time (s)",
        "relative error of the RMS deviation from ideal",
        f"Work-precision on {in_words(xw.attrs['scene'])} ({xw.attrs['variant']}) against {xw.attrs['reference']}:"
        " error of the claims' measure versus wall time; tolerances from loose (left) to tight (right) for the"
        " adaptive integrators, steps for Exudyn.",
    )
    r = xw.time_ratio_at_equal_error
    rows = [
        (str(m), *(f"{v:.1f}" if np.isfinite(v) else "not reached" for v in r.sel(compared_method=m).values))
        for m in r.compared_method.values
    ]
    table(pd.DataFrame(rows, columns=["method", *[f"at the error of {s}" for s in r.dopri5_setting.values]]), {})
    md(
        "*Table: at the error linkwork's compiled Dormand–Prince reaches with each of its settings, the least wall time"
        " any setting of the method needs to be at least as accurate, as a multiple of linkwork's least time (the"
        " work-precision fronts; the error of single settings does not fall monotonically with the tolerance in a scene"
        " with impacts).*"
    )
    medians = ", ".join(f"{m}: {v:.1f}×" for m, v in zip(xw.compared_method.values, xw.median_time_ratio.values))
    md(
        f"**Decision: {xw.attrs['decision']}** (median over linkwork's error levels; {medians}). scipy steps from"
        " Python, so every step pays the interpreter around the compiled right-hand side; Exudyn's clearance joint is"
        " its own compiled contact."
    )
else:
    md("This render ran without the cross-check: run `make crosscheck` to add the side-by-side study.")
