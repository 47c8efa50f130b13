# ---
# jupyter:
#   jupytext:
#     formats: py:percent
#     text_representation:
#       extension: .py
#       format_name: percent
# ---

# %% [markdown]
# # Beat-up paper (Gao, GN721 six-link beating-up mechanism against the 1511M four-link): reproduction report

# %%
import json

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from _common import (
    answer, assumed, caption, consistent_sets_table, design_text, esc, inputs, key_words, loaded, md, provenance,
    show_log_log, table, verdict_figure, verdict_legend,
)

from linkwork.papers.beatup import CITATION

files, got = inputs(), loaded()
ds, win, acc, cmp, fnd, unc, published, sley = (
    got.result, got.window, got.accuracy, got.comparison, got.findings, got.uncertainty, got.published, got.sley_pin,
)
cfg = json.loads(ds.attrs["config_json"])
win_cfg = json.loads(win.attrs["config_json"])
pub = {q["id"]: q for q in published["quantities"]}
t1 = cmp[cmp["id"].str.startswith("table1")]
head = cmp[~cmp["id"].str.startswith("table1")]
head = head.assign(
    quantity=head.quantity.str.replace("theta1", "θ1"),
    numerical_source=head.numerical_source.str.replace("theta6", "θ6"),
)
f = lambda name: float(ds[name])  # noqa: E731
count = dict(zip(fnd.cell_class_name.values, fnd.class_count.values.astype(int)))
evidence = fnd[
    [
        "column", "theta1", "printed", "ours", "deviation", "deviation_in_tolerances", "tolerance", "numerical_error",
        "nominal_model", "offset_model", "printed_column_fd", "our_coarse_fd", "cell_class",
    ]
].to_dataframe()
evidence = evidence.rename(columns={"cell_class": "class"})
table1_spec = next(t for t in published["tables"] if t["id"] == "table1")
printed = {
    table1_spec["columns"][n]["variable"]: np.array(table1_spec["rows"], dtype=float)[:, j + 1]
    for j, n in enumerate(table1_spec["column_names"])
}
SYMBOL = {"l4": "l4", "l7": "l7", "theta4": "θ4", "theta7": "θ7"}
cases = list(fnd.fit_case.values)
fit_mean6 = dict(zip(cases, fnd.fit_theta6_mean_offset.values))
fit_same = dict(zip(cases, fnd.fit_theta6_same_sign.values.astype(int)))
fit_match = dict(zip(cases, fnd.fit_angles_within_printing.values.astype(int)))
offset_par = fnd.attrs["offset_parameter"]
offset_case = f"joint fit, {offset_par} without bounds"
refit_class = "matches the refit with the offset parameter unbounded"
refit_moves = {
    SYMBOL[n]: (
        float(fnd.fit_shift.sel(fit_case="joint fit within rounding", fit_parameter=n)),
        float(fnd.fit_shift.sel(fit_case=offset_case, fit_parameter=n)),
    )
    for n in fnd.fit_parameter.values
    if n != offset_par
}
refit_text = ", ".join(
    f"{k} from {a:+.2f} to {b:+.2f}" for k, (a, b) in refit_moves.items() if f"{a:+.2f}" != f"{b:+.2f}"
)
chosen = fnd.attrs["crank_sense"]
senses = [str(s) for s in fnd.crank_sense.values]
other_sense = next(s for s in senses if s != chosen)
sense_label = dict(zip(senses, fnd.crank_sense_label.values))
sense = sense_label[chosen]
SIGN = {
    "decreasing": -1,
    "increasing": 1,
}  # sign of the crank's rate of turn in each sense (θ1 decreasing or increasing)
sense_value = fnd.sense_value.to_pandas()
sense_verdict = fnd.sense_verdict.to_pandas()
our_reading = head[head.tolerance_source.str.startswith("our reading")]

answer("beatup", fnd, cmp)

# %%
front = f("front_dead_centre")
# the sley's extreme angles are its angles at the dead centres (selected on the fine grid, not reduced)
theta6_front = float(ds.theta6_fine.sel(crank_angle_fine=float(ds.front_dead_centre), method="nearest"))
theta6_back = float(ds.theta6_fine.sel(crank_angle_fine=float(ds.back_dead_centre), method="nearest"))
fig, axes = plt.subplots(2, 1, figsize=(9, 7), sharex=True, constrained_layout=True)
style = {chosen: ("C0", "-"), other_sense: ("C1", "--")}
for s in senses:
    colour, line = style[s]
    phi = np.mod(SIGN[s] * (ds.crank_angle_fine.values - front), 360.0)
    order = np.argsort(phi)
    axes[0].plot(phi[order], ds.theta6_fine.values[order], color=colour, ls=line, label=sense_label[s])
    axes[1].plot(phi[order], SIGN[s] * ds.theta6_rate_fine.values[order], color=colour, ls=line, label=sense_label[s])
    back = float(ds.span_front_to_back_by_sense.sel(crank_sense=s))
    axes[0].plot(back, theta6_back, "v", color=colour, ms=8)
    axes[0].annotate(
        f"back dead centre {back:.2f}°", (back, theta6_back), textcoords="offset points",
        xytext=(-8 if s == chosen else 8, -14), ha="right" if s == chosen else "left", fontsize=8, color=colour,
    )
    for q in ("rate_peak_1", "rate_peak_2"):
        x = sense_value.loc[q, s]
        y = SIGN[s] * float(
            ds.theta6_rate_fine.sel(crank_angle_fine=np.mod(front + SIGN[s] * x, 360.0), method="nearest")
        )
        axes[1].plot(x, y, "o", color=colour, ms=6)
        axes[1].annotate(
            f"{x:.1f}°", (x, y), textcoords="offset points", xytext=(6 if s == chosen else -6, -10 if y < 0 else 4),
            ha="left" if s == chosen else "right", fontsize=8, color=colour,
        )
p_phi = np.mod(SIGN[chosen] * (ds.crank_angle.values - front), 360.0)
axes[0].plot(p_phi, printed["theta6"], "kx", ms=5, label=f"Table 1 as printed ({sense_label[chosen]})")
axes[0].axvline(0, color="k", lw=1)
axes[0].text(3, 0.5 * (theta6_back + theta6_front), f"front dead centre at φ = 0 (θ1 = {front:.2f}°)", fontsize=8)
axes[0].axvline(
    pub["span_front_to_back"]["value"], color="C3", ls=":", lw=1.5,
    label=f"printed back dead centre, {pub['span_front_to_back']['value']:g}° after the front",
)
for q in ("rate_peak_1", "rate_peak_2"):
    v, tol = pub[q]["value"], pub[q]["tolerance"]["abs"]
    axes[1].axvspan(
        v - tol,
        v + tol,
        color="C3",
        alpha=0.12,
        label=(
            f"printed peaks 'near' {pub['rate_peak_1']['value']:g}° and {pub['rate_peak_2']['value']:g}° (± {tol:g}°,"
            " our reading)"
            if q == "rate_peak_1"
            else None
        ),
    )
    axes[1].axvline(v, color="C3", ls=":", lw=1)
axes[1].axhline(0, color="k", lw=0.6)
axes[0].set_ylabel("sley-sword angle θ6 (deg)")
axes[0].set_ylim(min(theta6_back, theta6_front) - 1.2, max(theta6_back, theta6_front) + 0.6)
axes[1].set_ylabel("sley rate dθ6/dφ (rad per rad of crank)")
axes[1].set_xlabel("crank angle φ turned since the front dead centre (deg)")
axes[1].set_xticks(range(0, 361, 30))
for ax in axes:
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="upper center" if ax is axes[0] else "upper left")
plt.show()
caption(
    "The sley over one crank turn from the front dead centre, for the crank turning each way (solid:"
    f" {sense_label[chosen]}, the sense of the verdicts; dashed: {sense_label[other_sense]}). Top: sley-sword angle θ6"
    " in degrees; triangles: the back dead centre in each sense; red dotted: the printed"
    f" {pub['span_front_to_back']['value']:g}°; crosses: Table 1's printed θ6. Bottom: the sley's rate per unit crank"
    " angle (rad/rad; negative: towards the back); dots: its two peaks in each sense; red bands: the printed peaks"
    f" 'near' {pub['rate_peak_1']['value']:g}° and {pub['rate_peak_2']['value']:g}° within our ±"
    f" {pub['rate_peak_1']['tolerance']['abs']:g}° reading. Both the back dead centre and the velocity peaks fall on"
    " the printed positions in one sense only."
)

# %%
md(f"**Paper.** {esc(CITATION)}")

# %% [markdown]
# **What the paper does.** The sley of the GN721 flexible-rapier loom is driven by a crank-rocker ABCD in series with a
# double rocker CDEF. The paper solves both loops with complex vectors (tangent half-angle closed forms, eqs. 5 and 11),
# tabulates the rocker angle θ3 and the sley-sword angle θ6 with their derivatives (Table 1), and compares the weft
# window with that of the 1511M four-bar at equal reed stroke.
#
# **What we do.** We solve the six-bar as a chain of dyads with the project's shared kinematics solver (vector loop
# closure with explicit branches and analytic rates). We check it against the paper's own closed forms and against
# finite differences. We fit the printed parameters once to Table 1's angles within their rounding and judge every cell
# against that one model; for every cell that does not match we give the evidence of why. The paper does not say which
# way the crank turns, so the sense is a named scenario: we compute every sense-dependent claim in both senses. For the
# weft-window comparison the paper gives neither the 1511M dimensions nor S_w, so we show how the windows depend on
# them.

# %% [markdown]
# ## Summary

# %%
peak_tol = pub["rate_peak_1"]["tolerance"]["abs"]
md(f"""
* **Crank sense, a named scenario.** The verdicts are taken for the {esc(sense)}. The evidence for that sense, apart
  from the printed
  {pub['span_front_to_back']['value']:g}° it makes hold ({sense_value.loc['span_front_to_back', chosen]:.2f}° against
  {sense_value.loc['span_front_to_back', other_sense]:.2f}° the other way), is the velocity peaks:
  {sense_value.loc['rate_peak_1', chosen]:.1f}° and
  {sense_value.loc['rate_peak_2', chosen]:.1f}° after the front dead centre in this sense,
  {sense_value.loc['rate_peak_1', other_sense]:.1f}° and
  {sense_value.loc['rate_peak_2', other_sense]:.1f}° in the other, against the printed "near
  {pub['rate_peak_1']['value']:g}° and
  {pub['rate_peak_2']['value']:g}°" (within ± {peak_tol:g}°, our reading, both peaks hold in
  {'this sense only' if fnd.attrs['sense_picked_by_peaks'] == chosen else esc(fnd.attrs['sense_picked_by_peaks'])}).
  Section 3 sets every sense-dependent claim in both senses.
* **Table 1** is set against *one* model: l4, l7, θ4 and θ7 fitted jointly by least squares to the table's 48 printed
angles (θ3 and
  θ6), each held within the rounding interval of its printed digits. {int(fnd.table1_matches)} of
  {int(fnd.table1_total)} printed
  cells match it. {count['printed cell inconsistent']} printed derivatives are contradicted by the paper's own
  neighbouring cells,
  {count['inconclusive']} are inconclusive and {count['marginal']} marginal; {count[refit_class]} cells of θ6's columns
  match a refit in which
  {SYMBOL[offset_par]}, the parameter that removes the offset below, is unbounded (the others re-adjusting within
  rounding), {count['matches only the printed parameters']} match only the printed parameters, and
  {count['beyond the fitted model']} angles
  match no model (section 2).
* **The θ6 offset.** The printed θ6 lies above the model with the printed parameters in {fit_same['printed parameters']}
of 24 rows, by
  {fit_mean6['printed parameters']:.4f}° on average. The fit within rounding leaves
  {fit_mean6['joint fit within rounding']:.4f}°
  ({int(fnd.fit_at_bound)} parameters end on a rounding bound). Moving {SYMBOL[offset_par]} alone by
  {float(fnd.offset_change):+.4f}
  {fnd.offset_change.attrs['units']}, {float(fnd.offset_shift):+.1f} rounding half-widths, outside its rounding,
  removes it; we fitted only four parameters, and another (l5 or l6, for instance) may remove it within its rounding,
  so the offset's cause is open.
* **Headline numbers:** front dead centre {f('front_dead_centre'):.4f}° (printed
{pub['front_dead_centre']['value']:g}°), total swing
  {f('swing'):.4f}° (printed {pub['swing']['value']:g}°); neither depends on the sense. A note, not a verdict: at the
  parameter set fitted to Table 1 (section 2) {'; '.join(
      f"{esc(pub[q]['quantity'].split(' (')[0])} is {v:.4f}° ({'within' if w else 'outside'}"
      f" ± {pub[q]['tolerance']['abs']:g}° of {pub[q]['value']:g}°)"
      for q, v, w in zip(fnd.fitted_note_id.values, fnd.fitted_note_value.values,
                         fnd.fitted_note_within.values))} (section 3).
* **Tolerances that are our reading, not the paper's:**
{'; '.join(esc(q) + ' (' + esc(t) + ')' for q, t in zip(our_reading.quantity, our_reading.tolerance_source))};
  and the band of {float(fnd.fourbar_window_band):g}° around the printed four-bar window (section 5). Each is
  marked *our reading* in
  the "tolerance from" column of the tables.
* **Equations:** (4), (7) and (13) do not follow from (3) and (10). The corrected forms are given in section 4, and
Table 1
  follows them (the printed (7) and (13) would change θ3'' by up to
  {f('theta3_accel_eqs_printed_max_difference'):.3f} and θ6'' by up to
  {f('theta6_accel_eqs_printed_max_difference'):.3f}).
* **The comparative claim is untested.** The paper's conclusion that the six-bar leaves
{pub['window_difference']['value']:g}° more crank angle
  for weft insertion than the 1511M four-bar ({pub['window_sixbar']['value']:g}° against
  {pub['window_fourbar']['value']:g}°) cannot be
  reproduced: the paper gives neither S_w (the reed distance from its front position that lets the shuttle pass) nor
  the 1511M
  dimensions. Section 5 shows which S_w and four-bar arm-to-crank ratios would make the published numbers true; that is
  a constraint, not a verdict.
""")

# %% [markdown]
# ## 1. Parameters

# %%
sb = cfg["sixbar"]
par = pd.DataFrame(
    [(f"l{i}", sb[f"l{i}_m"] * 1e3, "mm") for i in range(1, 8)]
    + [
        ("θ4", sb["theta4_deg"], "deg"), ("θ7", sb["theta7_deg"], "deg"),
        ("branch of dyad B-C-D", sb["branch_rocker"], "θ3 = 42.45° at θ1 = 0"),
        ("branch of dyad C-E-F", sb["branch_sley"], "θ6 = 65.44° at θ1 = 0"),
    ],
    columns=["parameter", "value", "note"],
)
par["value"] = par["value"].map(lambda v: f"{v:g}")
table(par)
md(
    "Derivatives are per unit crank angle, θ' in rad/rad and θ'' in rad/rad². This is the only reading under which"
    " Table 1 reproduces. Its headers say θ1' and θ1'', but θ1'' = 0 for a uniformly turning crank, so θ1'² must be"
    " meant."
)

# %% [markdown]
# ## 2. Table 1 against one joint fit of the printed parameters
#
# l4, l7, θ4 and θ7 are printed with two decimals (mm, deg); the other lengths are whole millimetres, taken as exact
# design values.
# The rounding of those four numbers is *one* fixed error for the whole table, so we fit them once, by least squares
# (SciPy's trust-region least squares), to Table 1's 48 printed angles (24 θ3 and 24 θ6), each held within the rounding
# interval of its
# printed digits (half a unit of the last printed digit). Every one of the 144 cells is then judged against that one
# model.
#
# **Rule.** A cell *matches the fitted model* if |printed − fitted| ≤ half a unit of the cell's printed last digit + our
# numerical
# error of the fitted model. That error is the change of the cell when the fit is repeated at a tighter tolerance, plus
# the
# chain solver's (numbers below). The 48 angles are what the fit sees; the 96 derivative cells are an independent check
# of it.
# A cell that does not match is classed by why:
#
# * **printed cell inconsistent**: the printed derivative disagrees with ours, whereas the paper's own *neighbouring*
# cells agree
#   with ours. The central difference, at the 15° step, of the printed column the derivative comes from (θ for θ', θ'
# for θ'') agrees
#   with the same difference of the fitted model within the rounding of the printed column, while the printed cell is
# off by more
#   than that;
# * **inconclusive**: a neighbour used in that check is itself one of the wrong cells;
# * **marginal**: beyond the printed digit, but smaller than what the 15° check can resolve;
# * **matches the refit with the offset parameter unbounded**: the joint fit is repeated with the parameter that removes
# the θ6
#   offset (below) freed of its rounding bound, the others still held within theirs; a cell of a column that parameter
# moves matches
#   that refit. The class is given only to such columns: θ7 and l7 move θ6 alone, so a θ3 cell the refit happens to
# match (through the
#   other parameters' re-adjustment) is not credited to the offset;
# * **matches only the printed parameters**: an angle the joint fit gave up for others, within the digit of the printed
# parameters' model;
# * **beyond the fitted model**: an angle that matches none of these.

# %%
fit_cfg = json.loads(fnd.attrs["config_json"])["table1_fit"]
md(
    f"The fit runs at tolerance {fit_cfg['tolerance']:.0e} (the function, step and gradient tolerances of the least"
    f" squares) and is repeated at {fit_cfg['check_tolerance']:.0e}; our numerical error of the fitted model is at most"
    f" {float(fnd.fit_numerical_error_max):.1e} (in each column's unit), far below the printed digits, so the printing"
    " rounding decides every cell."
)
par_fit = pd.DataFrame({
    "parameter": [SYMBOL[n] for n in fnd.fit_parameter.values],
    "printed": fnd.fit_printed_value.values,
    "rounding half-width": fnd.fit_half_width.values,
    "fitted within rounding": fnd.fit_value.values,
    "unit": fnd.fit_parameter_unit.values,
    "change (half-widths)": fnd.fit_shift.sel(fit_case="joint fit within rounding").values,
})
table(
    par_fit,
    {
        "printed": "{:.4f}",
        "rounding half-width": "{:.3f}",
        "fitted within rounding": "{:.5f}",
        "change (half-widths)": "{:+.3f}",
    },
    caption=(
        "The joint fit within rounding: the model every Table 1 cell is judged against (a change of ±1 half-width is"
        " the rounding bound)"
    ),
)
shifts = fnd.fit_shift.to_pandas().rename(columns=SYMBOL)
fits = pd.concat([shifts, pd.DataFrame({
    "mean printed θ3 − model (deg)": fnd.fit_theta3_mean_offset.values,
    "mean printed θ6 − model (deg)": fnd.fit_theta6_mean_offset.values,
    "rms over 48 angles (deg)": fnd.fit_rms.values,
    "angles within the printed digit (of 48)": fnd.fit_angles_within_printing.values.astype(int),
    "θ6 rows with the majority sign (of 24)": fnd.fit_theta6_same_sign.values.astype(int),
}, index=shifts.index)], axis=1).reset_index().rename(columns={"fit_case": "model"})
fits["model"] = [m.replace("theta", "θ") for m in fits["model"]]
table(
    fits,
    {
        **{SYMBOL[n]: "{:+.2f}" for n in fnd.fit_parameter.values},
        "mean printed θ3 − model (deg)": "{:+.4f}",
        "mean printed θ6 − model (deg)": "{:+.4f}",
        "rms over 48 angles (deg)": "{:.4f}",
    },
    caption=(
        "What explains the θ6 offset: each fit's parameter changes in rounding half-widths (– : held at the printed"
        " value; beyond ±1: outside rounding) and what it leaves of the offset"
    ),
)
md(
    "**The θ6 offset.** With the printed parameters, the printed θ6 lies above ours in"
    f" {fit_same['printed parameters']} of 24 rows, by {fit_mean6['printed parameters']:.4f}° on average, more than"
    " half the printed digit. The joint fit within rounding reduces it to"
    f" {fit_mean6['joint fit within rounding']:.4f}° with {int(fnd.fit_at_bound)} parameters on a rounding bound:"
    " rounding alone does not explain it. θ3 depends only on l4 and θ4 (the frame AD); l7 and θ7 (where pivot D lies"
    f" seen from the rocking shaft F) move θ6 alone. Moving {SYMBOL[offset_par]} alone by"
    f" {float(fnd.offset_change):+.4f} {fnd.offset_change.attrs['units']} ({float(fnd.offset_shift):+.1f} rounding"
    f" half-widths, outside rounding) leaves {fit_mean6[offset_par + ' alone, without bounds']:+.4f}°; l7 alone does it"
    f" too, but needs {float(fnd.fit_shift.sel(fit_case='l7 alone, without bounds', fit_parameter='l7')):+.1f}"
    " half-widths. l4 and θ4 alone cannot: they move θ3 as well, which the table pins. Without bounds, the four"
    f" parameters together trade l7 against θ7 (the Jacobian's condition number is {float(fnd.fit_condition):.0f}), so"
    " that fit's large changes mean little beyond its smaller rms. Pivot D a little away from where the printed l7 and"
    " θ7 put it would explain the offset; we fitted only these four parameters, and others (l5, for one) may explain it"
    " within their rounding, so the cause stays open."
)

# %%
labels = {
    "theta3": "θ3 (deg)",
    "theta3_rate": "θ3'",
    "theta3_accel": "θ3''",
    "theta6": "θ6 (deg)",
    "theta6_rate": "θ6'",
    "theta6_accel": "θ6''",
}
theta1_tab = fnd.theta1.values[fnd.column.values == "theta6"]
dev_cols = {
    "printed parameters": "nominal_model",
    "joint fit within rounding": "ours",
    f"refit, {offset_par} unbounded (the others within rounding)": "offset_model",
}
fig, ax = plt.subplots(figsize=(9, 4), constrained_layout=True)
th6 = evidence[evidence.column == "theta6"]
for (label, col), marker in zip(dev_cols.items(), ("o", "s", "^")):
    ax.plot(
        th6.theta1, th6.printed - th6[col], marker + "-", ms=4, lw=1,
        label=label.replace(offset_par, SYMBOL[offset_par]),
    )
tol6 = float(th6.tolerance.iloc[0])
ax.axhspan(-tol6, tol6, color="0.85", label="± half the printed digit")
ax.axhline(0, color="k", lw=0.8)
ax.set_xlabel("crank angle θ1 (deg), as tabulated in Table 1")
ax.set_ylabel("printed θ6 − model (deg)")
ax.set_xticks(range(0, 361, 30))
ax.grid(alpha=0.3)
ax.legend(fontsize=8)
plt.show()
caption(
    "Printed θ6 minus the model at Table 1's crank angles, for the printed parameters, the joint fit within rounding,"
    f" and the refit with {SYMBOL[offset_par]} freed of its bound (the other three still within rounding); grey: within"
    " half a unit of the printed digit. Positions do not depend on the crank's sense."
)

# %% [markdown]
# ### The cells that do not match the fitted model, and why
#
# All 144 cells are in the appendix.

# %%
ev = evidence.copy()
ev["quantity"] = ev["column"].map(labels)
order_q = list(labels.values())
bad = ev[ev["class"] != "matches the fitted model"].copy()
why = {
    "printed cell inconsistent": "the paper's neighbouring cells agree with ours",
    "inconclusive": "a neighbour in the check is itself off",
    "marginal": "below what the 15° check resolves",
    refit_class: (
        f"matches the refit with {SYMBOL[offset_par]} unbounded (which also moves, in half-widths, {refit_text})"
    ),
    "matches only the printed parameters": "the joint fit trades it for other angles",
    "beyond the fitted model": "matches no model here",
}
bad["why"] = bad["class"].map(why)
bad = bad.sort_values(
    ["class", "quantity", "theta1"], key=lambda c: c.map(order_q.index) if c.name == "quantity" else c
)
table(
    bad[
        [
            "theta1", "quantity", "printed", "ours", "deviation", "deviation_in_tolerances", "tolerance",
            "nominal_model", "offset_model", "printed_column_fd", "our_coarse_fd", "class", "why",
        ]
    ].rename(
        columns={
            "theta1": "θ1 (deg)",
            "ours": "fitted model",
            "deviation": "printed − fitted",
            "tolerance": "half a printed digit",
            "deviation_in_tolerances": "printed − fitted, in tolerances",
            "nominal_model": "printed parameters",
            "offset_model": f"refit, {SYMBOL[offset_par]} unbounded",
            "printed_column_fd": "15° difference of printed column",
            "our_coarse_fd": "same, of the fit",
        }
    ),
    {
        "printed": "{:.4f}",
        "fitted model": "{:.5f}",
        "printed − fitted": "{:+.5f}",
        "printed − fitted, in tolerances": "{:+.3f}",
        "half a printed digit": "{:.0e}",
        "printed parameters": "{:.5f}",
        f"refit, {SYMBOL[offset_par]} unbounded": "{:.5f}",
        "15° difference of printed column": "{:.4f}",
        "same, of the fit": "{:.4f}",
        "θ1 (deg)": "{:.0f}",
    },
    caption=(
        'Table 1 cells that do not match the fitted model, grouped by why. "In tolerances": printed − fitted divided by'
        " (half the printed digit + our numerical error); beyond ±1 the cell does not match, and a value just beyond 1"
        " is a borderline cell. The last two number columns are filled for derivatives checked against the paper's"
        " neighbouring cells"
    ),
)
worst = evidence[evidence["class"] == "printed cell inconsistent"].sort_values(
    "deviation_in_tolerances", key=lambda c: -c.abs()
)
lines = [
    f"* {labels[r.column]} at θ1 = {r.theta1:.0f}°: printed {r.printed:.4f}, ours {r.ours:.4f}; the 15° difference of"
    f" the printed source column gives {r.printed_column_fd:.4f} beside ours {r.our_coarse_fd:.4f}"
    for r in worst.head(3).itertuples()
]
md("The largest printed-cell errors, each contradicted by the paper's own neighbouring cells:\n\n" + "\n".join(lines))

# %% [markdown]
# ## 3. Headline numbers, and the crank sense
#
# The paper does not say which way the crank turns. The sense is therefore a named scenario (a choice in the
# configuration,
# with both alternatives listed): the verdicts below are taken in the sense of the scenario, and the table after them
# sets every
# sense-dependent claim in both senses. A tolerance whose source starts with *our reading* is ours, not the paper's.

# %%


def decimals(tolerance: float) -> int:
    """Decimal places of a tolerance as printed (0.005 -> 3, 10 -> 0): the digits a value is shown to beside it."""
    text = f"{tolerance:g}"
    return len(text.split(".")[1]) if "." in text else 0


head_table = pd.DataFrame(
    {
        "quantity": head.quantity,
        "published": [f"{p:g} (± {t:g})" for p, t in zip(head.published, head.tolerance)],
        "tolerance from": head.tolerance_source,
        "ours": [f"{v:.{decimals(t) + 1}f}" if pd.notna(v) else "–" for v, t in zip(head.reproduced, head.tolerance)],
        "numerical error": [f"{e:.1e}" if pd.notna(e) else "–" for e in head.numerical_error],
        "error from": head.numerical_source.fillna(""),
        "over the rounding of the printed parameters": [
            "–" if pd.isna(lo) else f"{lo:.{decimals(t) + 1}f} … {hi:.{decimals(t) + 1}f}"
            for lo, hi, t in zip(head.input_low, head.input_high, head.tolerance)
        ],
        "decided by": head.decided_by.fillna("").map(key_words),
        "unit": head.unit,
        "verdict": head.verdict,
    }
)
table(
    head_table,
    caption=(
        f"Headline numbers, each judged for the {sense}. Values are shown to one digit beyond the tolerance; the range"
        " is ours over the rounding of the printed l4, l7, θ4, θ7 (half a unit of their last digit)"
    ),
)
verdict_legend(head.verdict)
fitted_notes = pd.DataFrame(
    {
        "id": fnd.fitted_note_id.values,
        "at the joint fit of Table 1": fnd.fitted_note_value.values,
        "within the tolerance there": np.where(fnd.fitted_note_within.values == 1, "yes", "no"),
    }
)
fitted_notes = fitted_notes.merge(head[["id", "quantity", "published", "tolerance", "reproduced", "verdict"]], on="id")
table(
    fitted_notes[
        [
            "quantity", "published", "tolerance", "reproduced", "verdict", "at the joint fit of Table 1",
            "within the tolerance there",
        ]
    ].rename(columns={"reproduced": "ours (printed parameters)", "verdict": "verdict (printed parameters)"}),
    {
        "published": "{:g}",
        "tolerance": "± {:g}",
        "ours (printed parameters)": "{:.4f}",
        "at the joint fit of Table 1": "{:.4f}",
    },
    caption=(
        "Notes, not verdicts: the dead-centre numbers at the parameter set fitted to Table 1 (section 2) beside their"
        " verdicts at the printed parameters (deg)"
    ),
)
md(
    "The verdicts are taken at the printed parameters, the numbers the paper states; the fit of section 2 is our"
    " reading of what Table 1 was computed with, so what it gives is a note. The fitted parameters lie within their"
    f" rounding intervals ({int(fnd.fit_at_bound)} of them on a bound), so the fitted set is one of the parameter sets"
    " the range column above spans."
)
both = pd.DataFrame(
    {
        "quantity": [pub[q]["quantity"] for q in sense_value.index],
        "published": [f"{pub[q]['value']:g} (± {t:g})" for q, t in zip(sense_value.index, fnd.sense_tolerance.values)],
    }
)
for s in senses:
    both[f"ours, {sense_label[s]}"] = [f"{v:.2f}" for v in sense_value[s]]
    both[f"verdict, {sense_label[s]}"] = sense_verdict[s].values
table(
    both,
    caption=(
        "Every sense-dependent claim in both crank senses, at the printed parameters (deg; our numerical error as in"
        " the table above). The velocity peaks are the evidence for the sense that does not rest on the printed"
        " front-to-back angle itself"
    ),
)
peaks_pick = fnd.attrs["sense_picked_by_peaks"]
span_sense = chosen if sense_verdict.loc["span_front_to_back", chosen] == "reproduced" else other_sense
md(
    f"**Which sense.** The printed {pub['span_front_to_back']['value']:g}° from front to back dead centre holds for the"
    f" {esc(sense_label[span_sense])}"
    " only, but choosing the sense to make it hold proves nothing about it. The velocity peaks are independent"
    f" evidence: the sley's fastest run towards the back comes {sense_value.loc['rate_peak_1', chosen]:.1f}° after the"
    f" front dead centre and its fastest run forward {sense_value.loc['rate_peak_2', chosen]:.1f}° after it for the"
    f" {esc(sense)}, and {sense_value.loc['rate_peak_1', other_sense]:.1f}° and"
    f" {sense_value.loc['rate_peak_2', other_sense]:.1f}° for the {esc(sense_label[other_sense])}. The paper reads them"
    f" off its Fig. 3 as \"near {pub['rate_peak_1']['value']:g}° and {pub['rate_peak_2']['value']:g}°\"; "
    + (
        f"both hold in one sense only, the {esc(sense_label[peaks_pick])}, which is the sense of the verdicts. "
        if peaks_pick in senses
        else f"they hold in {'both senses' if peaks_pick == 'both' else 'neither sense'}, so they do not decide it. "
    )
    + "The two senses are mirror images about the front dead centre (a crank angle φ in one is 360° − φ in the other),"
    f" so the other sense's peaks are 360° minus this sense's: {360 - sense_value.loc['rate_peak_2', chosen]:.1f}°"
    f" and {360 - sense_value.loc['rate_peak_1', chosen]:.1f}°. The acceleration claim, the front dead centre and the"
    " swing do not depend on the sense."
)
verdict_figure(
    head,
    "Beat-up: published headline numbers against ours",
    note=(
        f"Every sense-dependent number (front to back span, velocity and acceleration peaks) is judged for the {sense}"
        " (the scenario); front dead centre and swing do not depend on the sense."
    ),
)
oat_ids = {
    "front_dead_centre": "front dead centre (deg)",
    "span_front_to_back": "front to back (deg)",
    "swing": "swing (deg)",
}
oat_index = {str(q): i for i, q in enumerate(unc.quantity.values)}
oat_places = {q: decimals(pub[q]["tolerance"]["abs"]) + 1 for q in oat_ids}
INPUT_LABEL = {
    "sixbar.l4_m": "l4 (m)",
    "sixbar.l7_m": "l7 (m)",
    "sixbar.theta4_deg": "θ4 (deg)",
    "sixbar.theta7_deg": "θ7 (deg)",
}
oat_low, oat_high = (
    unc[v].isel(scenario=0).values if "scenario" in unc[v].dims else unc[v].values for v in ("oat_low", "oat_high")
)
oat = pd.DataFrame(
    {
        "input": [INPUT_LABEL.get(str(n), str(n)) for n in unc.input.values],
        "range": unc.input_range.values,
        **{
            label: [
                f"{oat_low[k, oat_index['|' + q]]:.{oat_places[q]}f} …"
                f" {oat_high[k, oat_index['|' + q]]:.{oat_places[q]}f}"
                for k in range(unc.input.size)
            ]
            for q, label in oat_ids.items()
        },
    }
)
table(
    oat,
    caption=(
        f"Each printed parameter moved alone over its rounding, {sense} ({design_text(unc)}); values to one digit"
        f" beyond the published tolerance (± {pub['front_dead_centre']['tolerance']['abs']:g}°), so that the ranges can"
        " be read against it"
    ),
)
consistent_sets_table(unc, cmp)
md(
    f"The dead centres are located as zeros of θ6' (Brent's method, x-tolerance {ds.attrs['root_xtol_rad']:.0e} rad)."
    f" The back dead centre is at θ1 = {f('back_dead_centre'):.2f}°. The velocity peaks are zeros of θ6'' located the"
    f" same way; for the {esc(sense)} they fall {f('rate_peak_1'):.2f}° and {f('rate_peak_2'):.2f}° after the front"
    f" dead centre. The largest |θ6''| ({f('theta6_accel_abs_max'):.4f} rad/rad²) lies {f('accel_peak'):.1f}° from the"
    " front dead centre; θ6'' and that distance are the same in both senses."
)

# %% [markdown]
# ### Fig. 3 regenerated: sley motion from the front dead centre
#
# The crank angle φ is measured from the front dead centre in the crank sense of the verdicts (section 3). Table 1's θ6'
# is
# dθ6/dθ1 (θ1 increasing); the sley's rate per unit φ is θ6' times the sign of the crank's turn, drawn so; θ6'' is the
# same in both senses.

# %%
front = f("front_dead_centre")
phi = np.mod(SIGN[chosen] * (ds.crank_angle_fine.values - front), 360.0)
order = np.argsort(phi)
fig, axes = plt.subplots(3, 1, figsize=(9, 8), sharex=True, constrained_layout=True)
for ax, var, ylabel in (
    (axes[0], "theta6", "sley angle θ6 (deg)"),
    (axes[1], "theta6_rate", f"dθ6/dφ = {'−' if SIGN[chosen] < 0 else ''}θ6' (rad/rad)"),
    (axes[2], "theta6_accel", "θ6'' (rad/rad²)"),
):
    sign = SIGN[chosen] if var == "theta6_rate" else 1  # a rate changes sign with the sense of rotation
    ax.plot(phi[order], sign * ds[var + "_fine"].values[order], "C0", label="ours")
    p_phi = np.mod(SIGN[chosen] * (ds.crank_angle.values - front), 360.0)
    ax.plot(p_phi, sign * printed[var], "kx", ms=5, label="Table 1 (printed)")
    ax.set_ylabel(ylabel)
    ax.grid(alpha=0.3)
for x in (pub["rate_peak_1"]["value"], pub["rate_peak_2"]["value"]):
    axes[1].axvline(x, color="C3", ls=":", lw=1)
axes[1].text(pub["rate_peak_1"]["value"] + 2, axes[1].get_ylim()[1] * 0.8, "published peaks", color="C3", fontsize=8)
axes[2].set_xlabel(f"crank angle φ from the front dead centre (deg, {sense})")
axes[2].set_xticks(range(0, 361, 30))
axes[0].legend(fontsize=8)
plt.show()
caption(
    f"Sense and signs: crank angle φ (deg) from the front dead centre, counted for the {sense} (the sense of the"
    " verdicts). Sley angle θ6 (deg), its rate dθ6/dφ (rad/rad; Table 1's θ6' is per unit of increasing θ1, so "
    + (
        "its printed values appear with the sign reversed"
        if SIGN[chosen] < 0
        else "its printed values appear as printed"
    )
    + ") and its acceleration θ6'' (rad/rad², the same in both senses), all per unit crank angle. Crosses: Table 1 as"
    " printed; red dotted lines: the published velocity peaks."
)

# %% [markdown]
# ## 4. Which printed equations do not follow from (3) and (10)
#
# Differentiating the loop equations (3) and (10) ourselves, with θ1' = 1 and θ1'' = 0:
#
# * **(3)**: printed … − 2l₁l₄cos(θ1 − θ4) = 2l₁l₃cos(θ1 − θ3);
#   corrected … − 2l₁l₄cos(θ1 − θ4) − 2l₁l₃cos(θ1 − θ3) (a line-break garble of the extraction or of the print).
# * **(4)**: printed A₁ sin θ1 + B₁ cos θ1 = C₁;
#   corrected A₁ sin **θ3** + B₁ cos **θ3** = C₁ (θ3 is the unknown; (5) solves for it).
# * **The unnumbered equation before (7)** (the second derivative of (3)): printed
#   0 = −l₃l₄θ3''cos(θ3−θ4) − l₃l₄θ3''sin(θ3−θ4) + l₁l₄θ1''cos(θ1−θ4) + …; corrected
#   0 = −l₃l₄**θ3'²**cos(θ3−θ4) − l₃l₄θ3''sin(θ3−θ4) + l₁l₄**θ1'²**cos(θ1−θ4) + … (where the error of (7) starts).
# * **(7)**: printed numerator (l₄/l₃)θ1''cos(θ1−θ4) − (l₄/l₁)θ1''cos(θ3−θ4) + …;
#   corrected (l₄/l₃)**θ1'²**cos(θ1−θ4) − (l₄/l₁)**θ3'²**cos(θ3−θ4) + (θ1'−θ3')²cos(θ1−θ3).
# * **Text before (12)**: printed "θ7 = 0"; corrected θ7' = 0 (θ7, the frame angle of DF, is constant and not zero).
# * **(13)**: printed … + (l₇/l₆)θ3'cos(θ3−θ7) − (l₇/l₃)θ3'cos(θ6−θ7) …;
#   corrected … + (l₇/l₆)**θ3'²**cos(θ3−θ7) − (l₇/l₃)**θ6'²**cos(θ6−θ7) ….
# * **Table 1 headers**: printed θ3''(θ1''), θ6''(θ1''); corrected: units of θ1'².
#
# Eqs. (5), (6), (11) and (12) are correct as printed. Below are the paper's closed forms, corrected and as printed,
# against our chain solver on the Table 1 grid.

# %%
rows_eq = [
    (labels[n], "corrected (5)-(7), (11)-(13) vs ours", f(f"{n}_eqs_max_difference"))
    for n in ("theta3", "theta3_rate", "theta3_accel", "theta6", "theta6_rate", "theta6_accel")
]
for name in ("theta3_accel", "theta6_accel"):
    rows_eq.append((labels[name], "as printed (7), (13) vs ours", f(f"{name}_eqs_printed_max_difference")))
    rows_eq.append((labels[name], "as printed vs Table 1", float(fnd[f"{name}_printed_eqs_vs_table"])))
    rows_eq.append((labels[name], "corrected vs Table 1", float(fnd[f"{name}_corrected_eqs_vs_table"])))
table(pd.DataFrame(rows_eq, columns=["quantity", "closed form", "max |difference|"]), {"max |difference|": "{:.2e}"})
md(
    "The corrected closed forms agree with the chain solver to rounding error. Table 1 follows the corrected forms:"
    f" the printed ones are about {float(fnd.printed_eqs_worse_factor):.0f} times as far from it as the corrected ones"
    " (for the closer of the two accelerations; the other is further still)."
)

# %% [markdown]
# ## 5. Six-bar vs four-bar weft window
#
# As in the paper, the six-bar's crank is scaled from 55 to 62 mm. We solve for the cloth-fell radius on the sword that
# gives a horizontal reed stroke of 153.5 mm. The four-bar is a parametric 1511M-type mechanism: crank R, connecting arm
# L, pin radius r on the sword, and a pivot offset, with the sword vertical at the front dead centre. Its cloth-fell
# radius is solved for the same stroke. The weft window is the crank angle during which the reed is more than S_w behind
# its foremost position.

# %%
fb = {k: assumed(files)[f"fourbar.{k}"] for k in win_cfg["fourbar"]}  # with their reasons
table(
    pd.DataFrame(
        [(k, v["value"], v["status"], v["reason"]) for k, v in fb.items()]
        + [
            ("scaled six-bar crank (m)", win_cfg["comparison"]["scaled_crank_m"], "sourced", "paper, Sec. 3"),
            ("reed stroke S (m)", win_cfg["comparison"]["stroke_m"], "sourced", "paper, Sec. 3 (1511M value)"),
        ],
        columns=["config key of the four-bar, or quantity", "number", "status", "reason"],
    ),
    caption=(
        "The four-bar's assumed inputs (the first column lists config keys of the four-bar section, then two printed"
        " quantities)"
    ),
)
md(
    f"Solved cloth-fell radii: six-bar {float(win.reed_radius_sixbar):.1f} mm (scaled swing"
    f" {float(win.swing_sixbar_scaled):.2f}°), four-bar {float(win.reed_radius_fourbar):.1f} mm. At the assumed S_w ="
    f" {fb['weft_clearance_m']['value'] * 1e3:.0f} mm the windows are {float(win.window_sixbar):.1f}° (six-bar) and"
    f" {float(win.window_fourbar):.1f}° (four-bar, L/R = {fb['arm_to_crank']['value']:g}): a difference of"
    f" {float(win.window_difference):.1f}°, against the printed {pub['window_sixbar']['value']:g}°,"
    f" {pub['window_fourbar']['value']:g}° and {pub['window_difference']['value']:g}°. These values rest on the"
    " assumptions above, so they are not verdicts."
)

# %%
sw = fb["weft_clearance_m"]["value"] * 1e3
fig, ax = plt.subplots(figsize=(9, 4), constrained_layout=True)
x = np.mod(
    SIGN[chosen] * win.angle_from_front.values, 360.0
)  # the window study counts towards increasing θ1; shown in the sense of section 3
order4 = np.argsort(x)
x = x[order4]
ax.plot(x, win.reed_sixbar.values[order4], "C0-", label="six-bar (crank 62 mm)")
ax.plot(x, win.reed_fourbar.values[order4], "C1--", label=f"four-bar, L/R = {fb['arm_to_crank']['value']:g} (assumed)")
ax.axhline(sw, color="k", lw=1)
ax.text(2, sw + 2, f"S_w = {sw:.0f} mm (assumed)", fontsize=8)
for name, colour in (("reed_sixbar", "C0"), ("reed_fourbar", "C1")):
    values = win[name].values[order4]
    ax.fill_between(x, 0, values, where=values > sw, color=colour, alpha=0.12)
ax.set_xlabel(f"crank angle from the front dead centre (deg, {sense})")
ax.set_ylabel("reed distance from its front position S (mm)")
ax.set_title(
    "Fig. 4 regenerated: reed displacement at cloth-fell height, equal stroke"
    f" {win_cfg['comparison']['stroke_m'] * 1e3:g} mm"
)
ax.set_xticks(range(0, 361, 30))
ax.grid(alpha=0.3)
ax.legend(fontsize=8)
plt.show()
caption(
    "Reed distance (mm) behind its front position at cloth-fell height over a crank turn, against the crank angle"
    f" (deg) from the front dead centre counted for the {sense} (the sense of section 3; the assumed four-bar's crank"
    " is taken to turn the same way), for the scaled six-bar and the assumed four-bar at equal stroke; shaded: where"
    " the reed is further back than S_w (the weft window, a total crank angle that does not depend on the sense)."
)

# %% [markdown]
# ### What the published 168°, 147° and 21° constrain
#
# The left panel shows the window against S_w for the six-bar and for four-bars of several L/R. The dotted lines mark
# the printed 168° and 147°. The right panel takes, for each S_w, the six-bar window minus the four-bar window,
# against L/R.

# %%
sw_grid = win.weft_clearance.values
w6 = win.window_sixbar_sweep.values
w4 = win.window_fourbar_sweep.values
ratios = win.arm_to_crank.values
sw168 = float(fnd.sw_for_printed_sixbar_window)
w4_at = fnd.fourbar_window_at_that_sw.values
fig, axes = plt.subplots(1, 2, figsize=(12, 4.3), constrained_layout=True)
axes[0].plot(sw_grid, w6, "k-", lw=2, label="six-bar")
for i, r in enumerate(ratios):
    axes[0].plot(sw_grid, w4[i], lw=1, label=f"four-bar L/R = {r:g}")
for val in (pub["window_sixbar"]["value"], pub["window_fourbar"]["value"]):
    axes[0].axhline(val, color="C3", ls=":", lw=1)
axes[0].axvline(sw168, color="C3", ls="--", lw=1)
axes[0].set_xlabel("S_w (mm)")
axes[0].set_ylabel("weft window (deg of crank)")
axes[0].legend(fontsize=7, ncol=2)
axes[0].grid(alpha=0.3)
for j in range(0, sw_grid.size, max(1, sw_grid.size // 6)):
    axes[1].plot(ratios, w6[j] - w4[:, j], "o-", ms=3, label=f"S_w = {sw_grid[j]:.0f} mm")
axes[1].axhline(pub["window_difference"]["value"], color="C3", ls=":", lw=1)
axes[1].set_xlabel("four-bar L/R")
axes[1].set_ylabel("six-bar window − four-bar window (deg)")
axes[1].legend(fontsize=7)
axes[1].grid(alpha=0.3)
plt.show()
caption(
    "Left: weft window versus S_w for the six-bar (black) and four-bars of several L/R; dotted: the printed windows;"
    " dashed: the S_w at which our six-bar gives the printed six-bar window. Right: six-bar minus four-bar window"
    " versus L/R for several S_w; dotted: the printed difference. A window is a total crank angle (degrees of crank"
    " rotation), the same in both senses."
)
band = float(fnd.fourbar_window_band)
lo, hi = float(fnd.arm_to_crank_in_band_min), float(fnd.arm_to_crank_in_band_max)
md(
    f"Our six-bar reaches the printed {pub['window_sixbar']['value']:g}° at S_w ≈ {sw168:.1f} mm. At that S_w our"
    " four-bar family gives the windows of the table below. "
    + (
        f"A window of {pub['window_fourbar']['value']:g} ± {band:g}° (the band is"
        f" {esc(fnd.fourbar_window_band.attrs['tolerance_source'])}, not the paper's) needs L/R in {lo:g}–{hi:g}."
        if np.isfinite(lo)
        else (
            f"No swept L/R gives {pub['window_fourbar']['value']:g} ± {band:g}° (the band is"
            f" {esc(fnd.fourbar_window_band.attrs['tolerance_source'])})."
        )
    )
    + " So the published comparison is consistent with a 1511M-type four-bar only within that range. We make no "
    "claim beyond this, because the 1511M dimensions are not in the paper."
)
table(
    pd.DataFrame({"L/R": ratios, "four-bar window at that S_w (deg)": w4_at}),
    {"four-bar window at that S_w (deg)": "{:.1f}", "L/R": "{:g}"},
)

# %% [markdown]
# ## 6. Accuracy: analytic derivatives vs finite differences
#
# What each step costs in time is in the accuracy report: wall times are measurements of the machine, kept in that
# one report so that this one is the same to the byte on every rerun.

# %%
steps = acc.fd_step.values
fig, ax = plt.subplots(figsize=(7, 4), constrained_layout=True)
derivative_label = {"theta6_rate": "sley rate θ6' (rad/rad)", "theta6_accel": "sley acceleration θ6'' (rad/rad²)"}
for k, name in enumerate(acc.derivative.values):
    ax.loglog(steps, acc.error.values[k], "o-", label=derivative_label[str(name)])
ax.axvline(cfg["numerics"]["fd_step_deg"], color="k", ls=":", lw=1, label="step used for the Table 1 checks")
show_log_log(
    ax,
    "central-difference step (deg of crank)",
    "max |FD − analytic| over a turn\n(rad/rad for θ6', rad/rad² for θ6'')",
    "Central-difference error of the sley rate and acceleration against the analytic ones versus the step; the dotted"
    " line is the step used for the Table 1 checks. Derivatives per unit of increasing θ1 (Table 1's convention); the"
    " errors do not depend on the sense.",
)
md(
    f"Central differences reach at best {float(acc.best_error.sel(derivative='theta6_rate')):.1e} for θ6' and"
    f" {float(acc.best_error.sel(derivative='theta6_accel')):.1e} for θ6''. Truncation error falls as h² until"
    " round-off takes over. One FD evaluation needs three position solves where the analytic rates need one, and the"
    " analytic rates are exact to rounding. The pipeline therefore uses analytic rates and keeps FD only as a check."
)

# %% [markdown]
# ## 7. Beyond the paper: a clearance at the sley pin
#
# The paper treats the six-bar as ideal. A worn pin where the link CE drives the sley (joint E) lets the sley lag and
# strike at each reversal. We ask what that does to the sley's acceleration, above all around the front dead centre
# where the reed beats up the weft, at an assumed loom speed, beside the four-bar's. The six-bar is written as a
# linkage description for the shared multibody engine (crank, coupler, rocker, link and the sley as one rigid body
# about the rocking shaft F), the pin at E a dry clearance joint (Hertz contact with Lankarani–Nikravesh damping and
# Ambrosio's friction, as in the clearance paper). **Every physical value is assumed**: the paper gives no masses, no
# loom speed and no pin (the assumptions table lists them with their reasons and ranges; the ranges are not propagated
# here: the answer is at the assumed values). How wide "around the front dead centre" is, is our choice too, so the
# peaks are given for several widths. The dry scene is run turn by turn until its state is found, as the clearance
# scenes are; the crank turns in the paper's sense (section 1's scenario) from the front dead centre.

# %%
fig, ax = plt.subplots(figsize=(9, 4.5), constrained_layout=True)
x = sley.crank_angle.values
for k, turn in enumerate(sley.judged_turn.values):
    ax.plot(x, sley.sley_acceleration_pin.sel(judged_turn=turn).values, color="C3", lw=0.8, alpha=0.7,
            label="six-bar, clearance at the sley pin (last judged turns)" if k == 0 else None)
ax.plot(x, sley.sley_acceleration_ideal.values, color="k", lw=1.5, label="six-bar, ideal pin")
ax.plot(
    x, sley.sley_acceleration_fourbar.values, color="C0", ls="--", lw=1.2, label="four-bar (ideal), the same loom speed"
)
ax.set_xlabel("crank angle from the front dead centre (deg)")
ax.set_ylabel("sley angular acceleration (rad/s²)")
ax.legend(fontsize=8)
ax.grid(alpha=0.3)
plt.show()
caption(
    f"Sley angular acceleration over a crank turn at {sley.attrs['loom_speed_rev_min']:g} rev/min (assumed), centred on"
    " the front dead centre: the six-bar with an ideal pin (black), with a radial clearance of"
    f" {sley.attrs['radial_clearance_m'] * 1e3:g} mm at the sley pin (red, the last judged turns of its settled state)"
    " and the four-bar of section 5 (dashed, from its own front dead centre; its swing is not the six-bar's, see"
    " below)."
)
names = list(sley.mechanism.values)
rows = [
    (
        f"{w:g}",
        f"{float(sley.peak_in_window.sel(mechanism=names[0], window=w)):.0f}",
        (
            f"{float(sley.peak_in_window.sel(mechanism=names[1], window=w)):.0f}"
            f" ({float(sley.pin_peak_in_window_low.sel(window=w)):.0f}–"
            f"{float(sley.pin_peak_in_window_high.sel(window=w)):.0f};"
            f" ± {float(sley.pin_peak_in_window_spread.sel(window=w)):.0f} turn to turn;"
            f" {float(sley.pin_peak_in_window_numerical_error.sel(window=w)):.1f} numerical)"
        ),
        f"{float(sley.peak_in_window.sel(mechanism=names[2], window=w)):.0f}",
    )
    for w in sley.window.values
]
table(
    pd.DataFrame(
        rows,
        columns=[
            "within ± (deg of crank)", "six-bar, ideal pin",
            f"six-bar, clearance: mean (range over the {int(sley.judged_turns)} judged turns; spread; numerical error)",
            "four-bar",
        ],
    ),
    {},
    caption=(
        "Largest |sley angular acceleration| (rad/s²) within a window of crank angle about the front dead centre, per"
        " window width"
    ),
)
turn_peak = dict(zip(names, sley.turn_peak.values))
turn_at = dict(zip(names, sley.turn_peak_at.values))
swing = dict(zip(sley.linkage.values, sley.swing.values))
per_swing = dict(zip(sley.linkage.values, sley.ideal_turn_peak_per_swing.values))
state = (
    "settles into a periodic motion"
    if int(sley.state_period) > 0
    else (
        "does not settle into a periodic motion: it is irregular from turn to turn, and only stationary in the"
        " statistical sense (its measures' last third of turns agrees with their middle third)"
    )
)
halves = dict(zip(sley.half_turn.values, zip(sley.pin_half_turn_peak.values, sley.pin_half_turn_peak_at.values)))
before, after = halves["before the front dead centre"], halves["after the front dead centre"]
md(
    f"The clearance scene {state}; it is judged on {int(sley.judged_turns)} turns after a transient of"
    f" {int(sley.state_transient)}, and every range and spread below is over those turns only (in an irregular motion a"
    " longer record can widen them). The pin strikes in two groups: before the front dead centre, up to"
    f" {before[0]:.0f} rad/s² (at {before[1]:.0f}° of crank angle), and after it, up to {after[0]:.0f} rad/s² (at"
    f" {after[1]:.0f}°), against {turn_peak[names[0]]:.0f} rad/s² (at {turn_at[names[0]]:.0f}°) for the ideal pin over"
    " the whole turn. About the front dead centre the answer depends on how far back the window reaches: within ±"
    f" {float(sley.window.values[0]):g}° the clearance's mean peak is"
    f" {float(sley.pin_over_ideal_in_window.values[0]):.2f} times the ideal's, within ±"
    f" {float(sley.window.values[-1]):g}° {float(sley.pin_over_ideal_in_window.values[-1]):.2f} times; the jumps"
    " between the widths come from where a window's edge falls relative to the impacts, not from a change at the dead"
    " centre. Where a window's numerical error is as large as its turn-to-turn spread, its mean is not resolved: in a"
    " motion that does not repeat, the check rerun's change is the divergence of the trajectory as much as the"
    f" solver's error. The pin's largest contact force is {float(sley.max_contact_force):.0f} N and its deepest"
    f" penetration {float(sley.max_penetration) * 1e6:.1f} µm (maxima over all impacts, not necessarily the same one);"
    " over a whole turn the clearance moves the sley's acceleration by"
    f" {float(sley.rms_deviation):.0f} rad/s² (RMS, mean over the judged turns) from the ideal six-bar's. The four-bar"
    f" (its dimensions assumed, arm to crank {win_cfg['fourbar']['arm_to_crank']['value']:g}) is not the same stroke:"
    f" its sword swings {swing['four-bar']:.1f}° against the six-bar's {swing['six-bar']:.1f}°, so its accelerations"
    f" are not a like-for-like ranking; per degree of swing the ideal peaks are {per_swing['six-bar']:.1f} (six-bar)"
    f" and {per_swing['four-bar']:.1f} rad/s² per degree (four-bar). Every number here holds for the assumed masses,"
    " speed and pin only: it shows what a worn sley pin can do to the beat-up, not what the GN721 does."
)

# %% [markdown]
# ## Appendix: Table 1, all 144 cells against the fitted model
#
# Verdict *reproduced* if |printed − fitted| ≤ half a unit of the printed digit + our numerical error (section 2); the
# class says why
# a cell does not match. Derivatives per unit of increasing θ1, as Table 1 prints them.

# %%
ev["verdict"] = np.where(ev["class"] == "matches the fitted model", "reproduced", "differs")
show = ev[
    [
        "theta1", "quantity", "printed", "ours", "deviation", "tolerance", "numerical_error", "nominal_model",
        "verdict", "class",
    ]
]
show = show.sort_values(["theta1", "quantity"], key=lambda c: c if c.name == "theta1" else c.map(order_q.index))
table(
    show.rename(
        columns={
            "theta1": "θ1 (deg)",
            "ours": "fitted model",
            "deviation": "printed − fitted",
            "tolerance": "half a printed digit",
            "numerical_error": "numerical error",
            "nominal_model": "printed parameters",
        }
    ),
    {
        "printed": "{:.4f}",
        "fitted model": "{:.5f}",
        "printed − fitted": "{:+.5f}",
        "half a printed digit": "{:.0e}",
        "numerical error": "{:.0e}",
        "printed parameters": "{:.5f}",
        "θ1 (deg)": "{:.0f}",
    },
    caption=(
        "Table 1, every cell, against the joint fit within rounding (and, for comparison, the model at the printed"
        " parameters)"
    ),
)

# %% [markdown]
# ## Provenance

# %%
provenance(ds)
