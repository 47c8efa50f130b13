# ---
# jupyter:
#   jupytext:
#     formats: py:percent
#     text_representation:
#       extension: .py
#       format_name: percent
# ---

# %% [markdown]
# # Heald paper (Grigoriev & Kheylo 2021): mechanical chains of a heald motion mechanism with joint clearance

# %%
import json

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from _common import (
    answer, assumed, caption, comparison_table, consistent_sets_table, design_text, esc, inputs, loaded, md, oat_table,
    provenance, show_log_log, table, verdict_figure,
)

from linkwork.papers.heald import CITATION
from linkwork.units import RAD_S_PER_RPM

files, got = inputs(), loaded()
ds, acc, contact, cmp, fnd, unc = got.result, got.accuracy, got.contact, got.comparison, got.findings, got.uncertainty
cfg = json.loads(ds.attrs["config_json"])
models = [str(m) for m in ds.model.values]
many = float(fnd.many_times)
limit = float(fnd.limit_rad_s)
entries = assumed(files)  # reasons, ranges and choices of the labelled config entries
drive_labels = dict(
    zip(entries["drive.frequency"]["choices"], entries["drive.frequency"]["choice_labels"], strict=True)
)
model_names = {"A": "physical linkage (model A)", "B": "chain of eq. (2) (model B)"}
MODEL_INPUTS = {m: fnd.attrs[f"inputs_of_model_{m}"].split(",") for m in models}  # the parameters each model reads

answer("heald", fnd, cmp)

# %%
claims_drawn = [
    (
        "force_E_many_times_F",
        f"force in E over force in F, smallest over the band (1); the paper: 'many times', read as ≥ {many:g}", "log",
    ),
    (
        "forces_grow_with_frequency",
        "fraction of the speed band over which both joint forces grow (1); the paper: they grow (all of it)", "linear",
    ),
    (
        "limit_41_89",
        (
            f"shaft frequency at which the drive meets the lowest resonance (rad/s); the paper's limit {limit:g} rad/s"
            " ± 10 %"
        ),
        "log",
    ),
]
fig, axes = plt.subplots(3, 1, figsize=(10, 6.5), layout="constrained")
ys = {m: len(models) - 1 - i for i, m in enumerate(models)}
for ax, (cid, label, scale) in zip(axes, claims_drawn, strict=True):
    rows_c = cmp[cmp.id == cid].set_index("model")
    if cid == "force_E_many_times_F":
        ax.axvspan(many, 1e3, color="0.85", lw=0, label="the paper's claim, as we read it")
    elif cid == "forces_grow_with_frequency":
        ax.axvspan(0.995, 1.005, color="0.85", lw=0, label="the paper's claim, as we read it")
    else:
        ax.axvspan(
            limit - float(fnd.limit_band), limit + float(fnd.limit_band), color="0.85", lw=0,
            label="the paper's claim, as we read it",
        )
    for m in models:
        y = ys[m]
        rows_m = cmp[(cmp.id == cid) & (cmp.model == m)]
        # one row per drive scenario once the comparison has a scenario column; else one row over both drives
        groups = list(rows_m.groupby("scenario", sort=False)) if "scenario" in rows_m else [("", rows_m)]
        offsets = np.linspace(-0.12, 0.12, len(groups)) if len(groups) > 1 else [0.0]
        for (scen, r), dy, colour in zip(groups, offsets, ("C0", "C9", "C2"), strict=False):
            ax.hlines(
                y + dy,
                float(r.input_low.iloc[0]),
                float(r.input_high.iloc[0]),
                color=colour,
                lw=6,
                alpha=0.5,
                label=(
                    f"over the assumed inputs' ranges{', ' + drive_labels.get(str(scen), str(scen)) if scen else ''}"
                    if m == models[0]
                    else None
                ),
            )
        for d, marker in zip(fnd.drive.values, ("o", "s"), strict=False):
            ax.plot(
                float(fnd.value_by_drive.sel(model=m, claim=cid, drive=d)), y, marker,
                mfc="k" if marker == "o" else "none", mec="k", ms=7,
                label=f"assumed values, {drive_labels[str(d)]}" if m == models[0] else None,
            )
        ax.text(
            1.01, y, " / ".join(dict.fromkeys(str(v) for v in rows_m.verdict)), transform=ax.get_yaxis_transform(),
            va="center", fontsize=8,
        )
    ax.set_xscale(scale)
    ax.set_yticks([ys[m] for m in models], [model_names[m] for m in models])
    ax.set_ylim(-0.6, len(models) - 0.4)
    ax.set_title(label, fontsize=9, loc="left")
    ax.grid(alpha=0.3, which="both", axis="x")
axes[0].set_xlim(
    min(0.1, 0.5 * min(cmp[cmp.id == "force_E_many_times_F"].input_low)), 100
)  # room for the lowest range end
axes[1].set_xlim(-0.02, 1.05)
handles, labels = axes[0].get_legend_handles_labels()
fig.legend(handles, labels, loc="outside lower center", ncol=2, fontsize=8)
plt.show()
per_scenario = "scenario" in cmp
caption(
    "The paper's three claims against our two chain models. Grey: what each claim says, as we read it; bars: our value"
    " over the ranges of every "
    + (
        "assumed input, one bar per drive frequency (legend); "
        if per_scenario
        else "assumed input (both drive frequencies sampled); "
    )
    + "dot: at the assumed values with the drive at the shaft frequency; open square: with the drive at half the shaft "
    "frequency. The verdict over the ranges is at the right"
    + (" (per drive frequency, in the legend's order)" if per_scenario else "")
    + ". Units: force ratio and band fraction dimensionless, frequency in rad/s."
)

# %%
md(f"**Paper.** {esc(CITATION)}")
if fnd.attrs.get("notes"):
    md(f"**What the counts do not show.** {esc(fnd.attrs['notes'])}")

# %% [markdown]
# **What the paper does.** It models the heald motion of an STB loom as a mechanical chain in Druzhinsky's sense.
# Lumped masses and springs are two-terminal elements with complex mobilities K = V/Q (mass 1/(jωm), spring jω/k).
# The motion is kinematically excited at joint D, and the joints E and F get Vulfson's clearance stiffness
# k_τ = kₙ|R|/(kₙΔ + |R|). The total mobility is stated as eq. (2), the input force as Q = V/K, and the joint forces
# are plotted against the main-shaft frequency (Figs. 5–6). **No parameter is printed**, so the figures cannot be
# reproduced number for number. What can be checked is the structure of eq. (2) and, for each claim, the parameter
# ranges under which it holds.
#
# **What we do.** We use a general chain solver with three independent routes (complex network with multipliers; real
# mass, stiffness and damping matrices with the constraints eliminated; series/parallel reduction) and two chain models:
#
# * **Model A, the physical linkage.** The rigid rod DEF is driven at D. The clearance springs E and F lead into the
#   bell cranks, whose levers (ratios η7, η8) drive the rigid rods GH and KL and the heald frame, held by the warp
#   spring. This is a bridge network, not a series/parallel one.
# * **Model B, the form of eq. (2).** Three spring→mass branches hang on the driven node: joint E with the
#   bell-crank-7 side reduced to E, joint F likewise, and the warp spring with the heald frame. The driven node carries
#   no mass: eq. (2) holds only then (section 3).
#
# An "ideal" joint is Vulfson's Δ → 0 limit (the pin's own bending stiffness kₙ). With perfectly rigid joints model A
# is a redundant closed loop, in which the split of force between E and F is undefined.
#
# **The drive frequency is a scenario.** The paper drives its chain at the main-shaft frequency. In plain weave a heald
# frame rises and falls once every two picks, one pick per main-shaft turn, so its drive may run at half the shaft
# frequency. Both are judged (section 2b); the frequency axes of the figures are main-shaft frequencies.

# %% [markdown]
# ## Summary: each claim, per model

# %%
def inputs_table(unc, model, quantities):
    """Each input the model reads moved alone over its range, in the first drive scenario: the range it gives each
    claim's measure.  The inputs the model does not read are left out (they do not move it: a test checks the list)."""
    left_out = [
        str(p).removesuffix(".value")
        for p in unc.input.values
        if str(p).startswith("parameters.")
        and str(p).removesuffix(".value").rsplit(".", 1)[-1] not in MODEL_INPUTS[model]
    ]
    words = ", ".join(INPUT_WORDS.get(n.rsplit(".", 1)[-1], n) for n in left_out)
    scenario = str(unc.scenario.values[0]) if "scenario" in unc.dims else ""
    oat_table(
        unc,
        quantities,
        entries,
        model=model,
        skip=set(left_out),
        caption=f"Model {model}"
        + (f", {scenario}" if scenario else "")
        + f": each input it reads moved alone over its range ({design_text(unc)}). "
        + (f"Not listed, because model {model} does not read them: {words}." if left_out else ""),
    )


#: Plain names of the inputs a model may leave out (for the captions' prose).
INPUT_WORDS = {
    "m_D": "the rod's mass at D",
    "m_E6": "the rod's mass at E",
    "m_F6": "the rod's mass at F",
    "reaction_E": "the assumed reaction at E",
    "reaction_F": "the assumed reaction at F",
    "operating_speed_rpm": "the operating speed",
    "stroke_D": "the heald stroke at D",
}


figure_labels = {
    "force_E_many_times_F": f"force in E many times that in F (min |Q_E|/|Q_F| ≥ {many:g} over the band)",
    "forces_grow_with_frequency": "joint forces grow with frequency (over the whole band)",
    "limit_41_89": (
        f"limit {float(fnd.limit_rpm):.0f} min⁻¹ = {limit:g} rad/s: the lowest resonance under the drive lies within"
        f" ±{float(fnd.limit_band):.2g} rad/s"
    ),
}
claim_short = {
    "force_E_many_times_F": "E many times F",
    "forces_grow_with_frequency": "forces grow",
    "limit_41_89": f"limit {limit:g} rad/s",
}
for m in models:
    rows_m = cmp[cmp.model == m]
    comparison_table(
        rows_m,
        caption=f"model {m}: our value at the assumed parameters and its range over every assumed parameter's range",
    )
    drawn = rows_m[rows_m.tolerance > 0]
    left_out = [claim_short[i] for i in rows_m.id if i not in set(drawn.id)]
    cam_changed = [
        f"'{claim_short[str(c)]}' is {fnd.verdict_sine_nominal.sel(model=m, claim=c).item()} with the harmonic drive"
        f" but {fnd.verdict_cam_nominal.sel(model=m, claim=c).item()} with a dwell cam's drive (section 4b)"
        for c in fnd.claim.values
        if fnd.verdict_sine_nominal.sel(model=m, claim=c).item() != fnd.verdict_cam_nominal.sel(model=m, claim=c).item()
    ]
    note = (
        f"Only the claims with a tolerance band are drawn; not drawn: {', '.join(left_out)} (one-sided readings, 'at"
        " least', with no tolerance to scale by: their verdicts are in the table above). "
        if left_out
        else ""
    ) + (f"Note: {'; '.join(cam_changed)}." if cam_changed else "")
    verdict_figure(
        drawn.assign(quantity=[figure_labels[i] for i in drawn.id]), f"Heald, model {m}: published claims against ours",
        note=note,
    )
    inputs_table(
        unc,
        m,
        {
            "force_E_many_times_F": "smallest |Q_E|/|Q_F|",
            "forces_grow_with_frequency": "growth fraction",
            "limit_41_89": "shaft frequency meeting the lowest resonance (rad/s)",
        },
    )
consistent_sets_table(
    unc, cmp, reads={m: {*MODEL_INPUTS[m], "displacement_amplitude_m"} for m in models}
)  # inputs a model does not read: left out

# %%
sweep_labels = {
    "reaction_ratio": "|R_E|/|R_F| (|R_F| assumed)",
    "clearance": "clearance Δ_E = Δ_F, both moved together (m), grid cells",
    "heald_mass": "heald mass M_P (kg)",
    "warp_stiffness": "warp stiffness k_O (N/m)",
}
claim_labels = {
    "force_E_many_times_F": "force in E many times that in F",
    "forces_grow_with_frequency": "forces grow with frequency",
    "limit_41_89": f"limit 400 min⁻¹ = {limit:g} s⁻¹ (lowest resonance within ±{float(fnd.limit_band):.2g} rad/s)",
}
at_params = {
    "force_E_many_times_F": lambda s: f"|Q_E|/|Q_F| = {float(s.ratio_EF_min):.2f}–{float(s.ratio_EF_max):.2f}",
    "forces_grow_with_frequency": lambda s: f"grow over {float(s.growth_fraction):.0%} of the band",
    "limit_41_89": lambda s: f"lowest resonance {float(s.first_resonance):.2f} rad/s",
}
# one verdict per drive scenario, in the comparison's order, joined for the table
verdicts = cmp.groupby(["model", "id"], sort=False).apply(
    lambda g: (
        "; ".join(f"{sc}: {v}" for sc, v in zip(g.get("scenario", [""] * len(g)), g.verdict, strict=True))
        if len(g) > 1
        else g.verdict.iloc[0]
    ),
    include_groups=False,
)
rows = []
for m in models:
    for claim in fnd.claim.values:
        row = {
            "model": m,
            "claim": claim_labels[claim],
            "verdict (over the assumed inputs' ranges), per drive scenario": verdicts[(m, claim)],
            "at the assumed parameters": at_params[claim](ds.sel(model=m)),
        }
        for sweep in fnd.sweep.values:
            text = str(fnd.holds_for.sel(model=m, claim=claim, sweep=sweep).values)
            row[f"holds for {sweep_labels[sweep]} in"] = text or "–"
        rows.append(row)
table(pd.DataFrame(rows))
flips = fnd[[v for v in fnd.data_vars if v.startswith("flip_")]].to_dataframe()
md(f"""
**Reading.** "Many times" is read as a ratio of at least {many:g} over the whole speed band
({cfg['speeds']['min_rpm']:g}–{cfg['speeds']['max_rpm']:g} min⁻¹),
and the {limit:g} s⁻¹ limit as the model's lowest resonance under the kinematic drive (a velocity resonance, K = 0,
where the
drive force peaks) lying within the band above; a force resonance is an antiresonance of a velocity-driven chain and is
not
counted (section 3). The verdicts hold at the assumed parameters; the range columns say where each claim would hold
instead,
"independent" where the joint forces do not move along that sweep at all. Along the reaction ratio, the heald mass and
the warp
stiffness (each one input moved alone) the ends of a range are the bisection's flip values of the next table, not grid
cells. The
clearance column moves both clearances together and names the cells of its grid where the claim holds (none): moving the
clearance at E alone does flip the claim (next table). In model A the E/F force ratio follows the ratio of
the joint stiffnesses k_E/k_F, so the first claim needs Vulfson's k_τ at E to be several times that at F: a larger
reaction or
a smaller clearance at E. In model B each joint carries only its own branch, so the ratio follows the reduced masses of
the
two sides, and the reactions are the branches' own kinetostatic ones (section 1b).
""")

# %% [markdown]
# ### Where each verdict flips
#
# For every verdict that one assumed input decides alone, the value of that input (the others at their assumed values)
# at
# which the verdict flips, found by bisection between its assumed value and the end of its range that flips it, with the
# drive at
# the shaft frequency (the nominal scenario).

# %%
flips["flip_claim"] = [claim_short[c] for c in flips.flip_claim]
table(
    flips.rename(
        columns={
            "flip_model": "model",
            "flip_claim": "claim",
            "flip_input": "assumed input (config key)",
            "flip_nominal": "assumed value",
            "flip_end": "range end",
            "flip_value": "verdict flips at",
            "flip_measure": "measure there",
            "flip_nominal_state": "at the assumed value the claim",
        }
    ),
    {"assumed value": "{:.4g}", "range end": "{:.4g}", "verdict flips at": "{:.4g}", "measure there": "{:.4g}"},
)
if "threshold_reaction_ratio_A" in fnd:
    md(
        "Named thresholds. Model A: the E/F claim holds once |R_E|/|R_F| exceeds"
        f" **{float(fnd.threshold_reaction_ratio_A):.4g}** (|R_F| at its assumed value), close to the ratio {many:g}"
        " itself, because k_τ ≈ |R|/Δ while |R| ≪ kₙΔ. Model B: the lowest resonance under the drive is the warp"
        " branch √(k_O/M_P); the limit claim holds between the flip values of M_P and k_O in the table (the band is"
        " the limit ± 10 %)."
    )

# %% [markdown]
# ## 1. Parameters (all assumed: the paper prints none)

# %%
rows = [
    (k, entries[f"parameters.{k}"]["value"], entries[f"parameters.{k}"]["status"], entries[f"parameters.{k}"]["reason"])
    for k in cfg["parameters"]
]
amplitude = entries["excitation.displacement_amplitude_m"]
rows.append(("displacement amplitude at D (m)", amplitude["value"], amplitude["status"], amplitude["reason"]))
table(pd.DataFrame(rows, columns=["parameter (config key)", "value", "status", "reason"]), {"value": "{:g}"})
md(
    f"Joint stiffnesses from Vulfson's model: k_E = {float(ds.k_E.sel(joints='elastic')):.3g} N/m and k_F ="
    f" {float(ds.k_F.sel(joints='elastic')):.3g} N/m with clearance; kₙ = {float(ds.k_E.sel(joints='ideal')):.3g} N/m"
    " without (the ideal joint). The excitation is a harmonic drive displacement X at D, so V = jωX.\n\n**Two drive"
    " amplitudes, two uses.** The joint-force curves and every claim measure (sections 2–4b) use the small"
    f" displacement amplitude X = {float(ds.attrs['displacement_amplitude_m']) * 1e3:g} mm at D, comparable with the"
    " clearance, as the paper's linear chain presumes; the forces scale linearly with it. The heald stroke"
    f" ({float(ds.stroke_D) * 1e3:g} mm at D, first harmonic) is used only for the kinetostatic reactions of section"
    " 1b, which set Vulfson's joint stiffness."
)

# %% [markdown]
# ### 1b. The joint reactions from the mechanism's own kinetostatics
#
# Vulfson's k_τ needs the reaction |R| in each joint. Kinetostatics gives it: the forces of the ideal-joint chain (pins
# of
# stiffness kₙ, no clearance) when the heald stroke at D (first harmonic, assumed) is driven at the operating speed
# (assumed).

# %%
rk = ds.reaction_kinetostatic
md(
    f"At {float(ds.omega_op):.1f} rad/s with a stroke of {float(ds.stroke_D) * 1e3:.0f} mm at D the ideal-joint chains"
    f" give |R_E| = {float(rk.sel(model='A', joint='E')):.0f} N, |R_F| = {float(rk.sel(model='A', joint='F')):.0f} N in"
    f" model A and {float(rk.sel(model='B', joint='E')):.0f} N, {float(rk.sel(model='B', joint='F')):.0f} N in model"
    f" B.\n\n**Model B uses them** (|R_E| = {float(ds.reaction_model_B.sel(joint='E')):.0f} N, |R_F| ="
    f" {float(ds.reaction_model_B.sel(joint='F')):.0f} N, in closed form, checked against the network in the tests):"
    " each joint carries only its own branch, whose ideal pin does not depend on the reaction, so nothing is circular,"
    " and the assumed reactions do not enter model B.\n\n**Model A cannot use them: the split is circular.** With both"
    " joints rigid the frame is driven from both sides, a statically indeterminate loop: the ideal chain splits the"
    " load evenly only because both pins are given the same kₙ. With clearance the load splits by k_E : k_F, and k_τ"
    " depends on the share each joint carries. Solving R = |Q(ω_op; k_τ(R))| gives the self-consistent reactions |R_E|"
    f" = {float(ds.reaction_self_consistent_A.sel(joint='E')):.0f} N, |R_F| ="
    f" {float(ds.reaction_self_consistent_A.sel(joint='F')):.0f} N (converged:"
    f" {'yes' if int(ds.self_consistent_converged_A) else 'no'}), and with them the smallest E/F force ratio over the"
    f" band is {float(ds.ratio_EF_min_self_consistent_A):.3f}. But the fixed point is weak: along the split the map has"
    f" slope {float(ds.self_consistent_split_slope_A):.3f} (at 1 every split would reproduce itself), because k_τ ≈"
    f" |R|/Δ while |R| ≪ kₙΔ (kₙΔ = {float(ds.clearance_pin_product.sel(joint='E')):.0f} N here). Quasi-statically the"
    " fixed point is |R_E| − |R_F| = kₙ(Δ_F − Δ_E): the split is set by the difference of the two clearances, not by"
    " the mechanism's kinetostatics. A split of "
    + (
        f"{many:g} : 1 needs Δ_F − Δ_E = {float(fnd.threshold_clearance_difference_A) * 1e6:.1f} µm, "
        if "threshold_clearance_difference_A" in fnd
        else ""
    )
    + "well inside the assumed clearance range"
    f" ({entries['parameters.clearance_E']['range'][0] * 1e6:g}–{entries['parameters.clearance_E']['range'][1] * 1e6:g}"
    " µm) and unknowable for a worn mechanism.\n\n**What this does to model A's E/F claim.** With the mechanism's"
    " own reactions (kinetostatic, or self-consistent: equal at equal clearances) model A's E/F ratio is"
    f" {float(ds.ratio_EF_min_self_consistent_A):.3f}, and the claim **fails**. It holds only if the reactions are"
    " split at least "
    + (
        f"{float(fnd.threshold_reaction_ratio_A):.4g} : 1, "
        if "threshold_reaction_ratio_A" in fnd
        else "several to one, "
    )
    + "which the kinetostatics of a symmetric linkage do not give. The assumed reactions |R_E|, |R_F|"
    f" ({entries['parameters.reaction_E']['range'][0]:g}–{entries['parameters.reaction_E']['range'][1]:g} N, below"
    " the kinetostatic magnitudes) stand for that split: while |R| ≪ kₙΔ, Vulfson's k_τ ≈ |R|/Δ and a common factor"
    " on both reactions leaves the ratio nearly unchanged; at the kinetostatic magnitudes, a good fraction of kₙΔ, it"
    " does move it, and the split needed there is larger. With self-consistent reactions the split follows from the"
    " clearances: unequal clearances give it. Model A's 'decided by an unprinted input' on this claim therefore"
    " means: it holds only for unequal clearances or reactions, which the paper does not print."
)

# %% [markdown]
# ## 2. Figs. 5–6 regenerated: joint forces with ideal and elastic joints

# %%
fig, axes = plt.subplots(2, 2, figsize=(12, 7), sharex=True, constrained_layout=True)
speed = ds.shaft_speed.values
for i, m in enumerate(models):
    for j, (var, label) in enumerate((("Q_E", "joint E (Fig. 5)"), ("Q_F", "joint F (Fig. 6)"))):
        ax = axes[i, j]
        for variant, style in (("ideal", "--"), ("elastic", "-")):
            ax.plot(speed, ds[var].sel(model=m, joints=variant), style, label=f"{var} {variant}")
        ax.axvline(float(fnd.limit_rpm), color="C3", ls=":", lw=1)
        ax.set_title(f"model {m}: {label}")
        ax.set_ylabel("force amplitude (N)")
        ax.set_yscale("log")
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=8)
for ax in axes[-1]:
    ax.set_xlabel("main-shaft speed (min⁻¹)")
plt.show()
caption(
    "Force amplitudes in joints E (Fig. 5) and F (Fig. 6) against the main-shaft speed, ideal joints dashed, elastic"
    " (Vulfson) joints solid, for both chain models; red dotted: the paper's speed limit. In model B the two curves"
    f" lie on top of each other: they differ by at most {float(ds.ideal_elastic_difference.sel(model='B')):.1%} over"
    " the band, because each of its joint branches resonates far above the band, so the branch moves nearly rigidly"
    " and its joint force is set by its mass, not by the joint's stiffness; in model A by up to"
    f" {float(ds.ideal_elastic_difference.sel(model='A')):.0%}."
)
md(
    f"The dotted line marks the paper's {float(fnd.limit_rpm):.0f} min⁻¹. Force amplitudes are for the assumed drive"
    " amplitude and scale linearly with it."
)

# %% [markdown]
# ## 2b. The drive frequency: at the shaft frequency or at half of it
#
# The same claims with the drive at each frequency, every other input at its assumed value. At half the shaft frequency
# a resonance is met at twice the shaft speed, and model B's kinetostatic reactions are those at half the operating
# speed. (The comparison table of the summary spans both drives with the ranges of the other inputs.)

# %%
rows = []
for m in models:
    for c in fnd.claim.values:
        row = {"model": model_names[m], "claim": claim_labels[str(c)]}
        for d in fnd.drive.values:
            row[f"{drive_labels[str(d)]}: measure"] = float(fnd.value_by_drive.sel(model=m, claim=c, drive=d))
            row[f"{drive_labels[str(d)]}: verdict"] = str(fnd.verdict_by_drive.sel(model=m, claim=c, drive=d).values)
        rows.append(row)
table(pd.DataFrame(rows), {c: "{:.4g}" for c in rows[0] if c.endswith("measure")})
same = bool((fnd.verdict_by_drive.values == fnd.verdict_by_drive.values[..., :1]).all())
md(
    f"Does the drive frequency change a verdict at the assumed inputs? **{'no' if same else 'yes'}**. The measures are"
    " the smallest force ratio E/F over the band, the fraction of the band over which both joint forces grow, and the"
    " shaft frequency (rad/s) at which the drive meets the lowest resonance."
)

# %% [markdown]
# ## 3. Eq. (2): exact for model B, and only while the driven node has no mass
#
# A driven node carrying three spring→mass branches, with no mass of its own, has
# 1/K = Σ_i jω kᵢ/(ωᵢ² − ω²) with ωᵢ² = kᵢ/mᵢ. Putting this over a common denominator gives exactly the form of eq. (2).
# The numerator is Π(ω_i² − ω²), three factors (ω09, ω010, ω011, the velocity resonances where K = 0). The denominator
# is jω(k_E7 + k_F8 + k_O)(ω07² − ω²)(ω08² − ω²): degree 5 in ω against the numerator's 6. Here ω07 and ω08 are the
# roots of Σ_i kᵢ Π_(j≠i) (ω_j² − ω²), the force resonances where K → ∞. Each root lies between two consecutive ω_i,
# because the sum runs from −∞ to +∞ between its poles, so zeros and poles interlace.

# %%
freqs = pd.DataFrame(
    [(w, "zero (velocity resonance)") for w in ds.eq2_numerator_frequencies.values]
    + [(w, "pole (force resonance)") for w in ds.eq2_denominator_frequencies.values],
    columns=["frequency (rad/s)", "kind"],
).sort_values("frequency (rad/s)")
table(freqs, {"frequency (rad/s)": "{:.2f}"})
md(
    "Interlacing ω09 ≤ ω07 ≤ ω010 ≤ ω08 ≤ ω011 (equality where the E and F branches are equal, as at the assumed"
    f" parameters: the pole then cancels a zero): **{'yes' if int(ds.eq2_interlaced) else 'no'}**. Numerator degree 6"
    " and denominator degree 5 in ω (the mobility is spring-like at high frequency and mass-like at low frequency)."
    " Eq. (2) with these frequencies against the network solution of model B: max relative difference"
    f" {float(ds.eq2_relative_difference):.1e}. The eigen-solver's resonances of model B (undamped) are velocity"
    f" {', '.join(f'{x:.2f}' for x in ds.velocity_resonance.sel(model='B', joints='elastic').dropna('mode').values)}"
    " and force"
    f" {', '.join(f'{x:.2f}' for x in ds.force_resonance.sel(model='B', joints='elastic').dropna('mode').values)}"
    " rad/s. Model A does not have the form of eq. (2): a warp spring on the frame behind both levers is a bridge, not"
    " three branches on the driven node."
)
md(
    "**The condition: no mass on the driven node.** Eq. (2) has no mass term of the driven node, and the linkage puts"
    f" the rod DEF there (m_D + m_E6 + m_F6 = {float(ds.eq2_node_mass):.1f} kg at the assumed values; the rod is rigid,"
    " so all of it moves with D). A node mass m adds one more branch in parallel, 1/K = 1/K₂ + jωm, which eq. (2) does"
    " not have. With the rod's mass on the node the network's mobility differs from eq. (2) by up to"
    f" **{float(ds.eq2_node_mass_difference):.0f} times eq. (2)'s own value** on our frequency grid, at"
    f" {float(ds.eq2_node_mass_difference_at):.1f} rad/s. That is next to the chain's shifted antiresonance at"
    f" {float(ds.eq2_node_mass_antiresonance):.2f} rad/s, where the chain's mobility is infinite and eq. (2)'s is not,"
    " so the difference has no upper bound and its grid maximum depends on how close a grid point falls. Model B as"
    " built keeps the node massless, so it is eq. (2)'s chain exactly; the rod's masses therefore do not enter model"
    " B, and its input table leaves them out."
)

# %% [markdown]
# ### Resonance and antiresonance under a kinematic drive
#
# The chain is driven by a velocity V at D (kinematic excitation), and the force Q = V/K follows. Where K = 0
# (Druzhinsky's
# *velocity resonance*) a finite V needs an infinite Q: these are the **resonances** of the driven mechanism, the
# natural
# frequencies with D held, where the drive force and the internal forces peak. Where K → ∞ (*force resonance*) a finite
# V needs
# no force at all: these are **antiresonances**, the natural frequencies with D free, where the drive force dips to
# zero.

# %%
def freq_list(var, m):
    return ", ".join(f"{x:.1f}" for x in ds[var].sel(model=m, joints="elastic").dropna("mode").values) or "none"


def zeta_list(m, kind):
    f, z = (
        ds[f"mode_frequency_{kind}"].sel(model=m).dropna("mode").values,
        ds[f"damping_ratio_{kind}"].sel(model=m).dropna("mode").values,
    )
    return ", ".join(f"ζ = {zeta_text(b)} at {a:.1f} rad/s" for a, b in zip(f, z)) or "–"


def zeta_text(z):
    return "0 (undamped)" if z == 0 else (f"{z:.4f}" if z >= 1e-3 else f"{z:.1e}")


table(
    pd.DataFrame(
        [
            (
                m, freq_list("velocity_resonance", m), freq_list("force_resonance", m), zeta_list(m, "held"),
                zeta_list(m, "free"),
            )
            for m in models
        ],
        columns=[
            "model", "resonances, K = 0 (rad/s)", "antiresonances, K → ∞ (rad/s)", "damping of the resonances",
            "damping of the antiresonances",
        ],
    )
)
caption_text = (
    "The damping ratios are the complex eigenvalues of the damped chains (−Re λ/|λ|), from the assumed warp damping"
    f" c_O = {cfg['parameters']['c_O']['value']:g} N s/m and joint damping c_J ="
    f" {cfg['parameters']['c_joint']['value']:g} N s/m; in model B the warp resonance has ζ = c_O/(2√(k_O M_P)) ="
    f" {float(ds.damping_ratio_held.sel(model='B', mode=0)):.4f}, the joint branches none at the assumed joint damping"
    " (the paper's chain has no joint damper; section 4b takes the joint damping over its range). Antiresonances of"
    " model B are not given a damping ratio: its driven node is massless, so with D free the chain has no such mode."
    " Model B's joint resonances are undamped (ζ = 0), and model A's antiresonance near"
    f" {float(ds.mode_frequency_free.sel(model='A', mode=1)):.0f} rad/s has ζ ="
    f" {zeta_text(float(ds.damping_ratio_free.sel(model='A', mode=1)))}: a mode in which the warp damper, the only"
    " damper, barely moves."
)
md(caption_text)
md(
    "**What this means for the speed limit.** In model A the lowest natural frequency,"
    f" {float(ds.force_resonance.sel(model='A', joints='elastic', mode=0)):.1f} rad/s, is an antiresonance: the frame"
    " swinging on the warp together with the free rod. Under the kinematic drive the joint forces *dip* there. A dip"
    " lowers the loads at that speed, so if the paper's limit means loads grown too large (as it says), this"
    " antiresonance, although it lies near the limit (where, rests on the assumed k_O and M), is unlikely to be its"
    " origin; the model cannot decide more. With the drive at the shaft frequency model A's lowest resonance under the"
    f" drive is {float(ds.first_resonance.sel(model='A')):.1f} rad/s"
    f" ({float(ds.first_resonance_rpm.sel(model='A')):.0f} min⁻¹), far above the limit. The paper's own introduction"
    " gives the likelier source of its number: it cites measurements [2] showing that kinetostatic calculations hold"
    " only up to about its limit speed, which its chain does not derive."
)

# %% [markdown]
# ### Model B: the joint forces do not see the warp branch
#
# Under a velocity drive every branch on the driven node sees the same prescribed motion, so Q_E and Q_F depend only on
# their
# own branches. The table gives the largest relative change of |Q_E| and |Q_F| over the band between the two ends of
# each sweep.

# %%
sweep_keys = ["reaction_ratio", "clearance", "heald_mass", "warp_stiffness"]
table(
    pd.DataFrame(
        [(m, *[float(ds[f"joint_force_change_vs_{k}"].sel(model=m)) for k in sweep_keys]) for m in models],
        columns=["model", *[f"change along {k.replace('_', ' ')}" for k in sweep_keys]],
    ),
    {f"change along {k.replace('_', ' ')}": "{:.2e}" for k in sweep_keys},
)
md(
    "In model B the heald mass and the warp stiffness change the joint forces only by the round-off of the solve (the"
    " tests vary M_P, k_O and c_O and find the E and F responses unchanged), and the assumed reactions not at all"
    " (model B takes its own). Along these sweeps model B can show nothing about the E/F claims: the table of"
    " supporting ranges says 'independent' there, and the only model-B claim the heald mass and warp stiffness bear on"
    " is the limit (the warp branch's resonance, which shows in the drive force Q at D, not in Q_E, Q_F)."
)

# %% [markdown]
# ## 4. The supporting ranges

# %%
fig, axes = plt.subplots(1, 3, figsize=(14, 4), constrained_layout=True)
for m in models:
    s = ds.sel(model=m)
    flat = float(s.joint_force_change_vs_reaction_ratio) <= 1e-8
    axes[0].semilogx(
        ds.reaction_ratio, s.ratio_EF_min_vs_reaction_ratio, "o-", ms=3,
        label=f"model {m}" + (" (independent of the assumed reactions)" if flat else ""),
    )
    axes[1].plot(ds.heald_mass, s.first_resonance_vs_heald_mass, "o-", ms=3, label=f"model {m}")
    axes[2].semilogx(ds.warp_stiffness, s.first_resonance_vs_warp_stiffness, "o-", ms=3, label=f"model {m}")
axes[0].axhline(many, color="C3", ls=":", lw=1)
axes[0].set_xlabel("|R_E| / |R_F|")
axes[0].set_ylabel("min |Q_E|/|Q_F| over the band")
for ax in axes[1:]:
    ax.axhspan(
        limit - float(fnd.limit_band), limit + float(fnd.limit_band), color="C3", alpha=0.15,
        label=f"{limit:g} s⁻¹ ± {float(fnd.limit_band):.2g}",
    )
    ax.set_ylabel("lowest resonance (rad/s)")
axes[1].set_xlabel("heald-frame mass M_P (kg)")
axes[2].set_xlabel("warp stiffness k_O (N/m)")
for ax in (axes[0], axes[2]):  # labels at 1, 2 and 5 of each decade only: the minor ones run into each other
    ax.xaxis.set_major_locator(plt.LogLocator(subs=(1.0, 2.0, 5.0)))
    ax.xaxis.set_minor_formatter(plt.NullFormatter())
for ax in axes:
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
plt.show()
caption(
    "Claims' measures along the parameter sweeps: the smallest E/F force ratio against |R_E|/|R_F| (red dotted: the"
    " ratio read as 'many times'), and the lowest resonance against the heald-frame mass and the warp stiffness (red"
    " band: the paper's limit with our tolerance)."
)
md(
    "In model B the lowest resonance under the drive is the warp branch, √(k_O/M_P); a heavier frame or a softer warp"
    " than assumed puts it at the paper's limit (the flip values above). It is a peak of the drive force at D only: the"
    " joint forces E and F do not see it. In model A the lowest resonance under the drive is the frame on the warp and"
    " the joint springs with D held, far above the band over the whole range of the inputs. Model B's E/F ratio does"
    " not depend on the reaction ratio (flat line): its reactions are its own kinetostatic ones."
)

# %% [markdown]
# ## 4b. A real heald motion: a dwell cam's harmonics
#
# A heald frame does not move harmonically: it rises, dwells, returns and dwells within a turn. We drive the chains with
# a
# cycloidal dwell-rise-dwell-return profile (its rise fraction assumed) as a Fourier series, the first harmonic scaled
# to the
# excitation amplitude, and judge the claims on the peak joint forces over a turn. The limit becomes the lowest shaft
# speed at
# which a significant harmonic (our reading: at least a set fraction of the first) meets the lowest resonance.

# %%
cam = cfg["cam"]
fig, axes = plt.subplots(1, 3, figsize=(15, 4), constrained_layout=True)
axes[0].bar(ds.harmonic, ds.cam_harmonic_amplitude)
axes[0].axhline(
    float(ds.significant_harmonic), color="C3", ls=":", lw=1,
    label=f"significant: ≥ {float(ds.significant_harmonic):g} of the first (our reading)",
)
axes[0].set_yscale("log")
axes[0].set_ylim(1e-4, 2)
axes[0].set_xlabel("harmonic h of the shaft speed")
axes[0].set_ylabel("|cₕ| / |c₁|")
axes[0].legend(fontsize=8)
for i, m in enumerate(models):
    ax = axes[i + 1]
    ax.plot(speed, ds.Q_E.sel(model=m, joints="elastic"), "C0--", lw=1, label="Q_E, harmonic drive")
    ax.plot(speed, ds.Q_F.sel(model=m, joints="elastic"), "C1--", lw=1, label="Q_F, harmonic drive")
    ax.plot(speed, ds.Q_E_cam.sel(model=m), "C0-", label="peak Q_E over a turn, cam")
    ax.plot(speed, ds.Q_F_cam.sel(model=m), "C1-", label="peak Q_F over a turn, cam")
    ax.set_yscale("log")
    ax.set_title(f"model {m}")
    ax.set_xlabel("main-shaft speed (min⁻¹)")
    ax.set_ylabel("joint force (N)")
    ax.legend(fontsize=8)
for ax in axes:
    ax.grid(alpha=0.3, which="both")
plt.show()
caption(
    f"Left: harmonics of the cam drive (rise fraction {cam['rise_fraction']['value']:g}; the profile is half-wave"
    " symmetric, so the even harmonics vanish). Red dotted: the significance fraction"
    f" {float(ds.significant_harmonic):g} (our reading). Middle and right: joint forces with the harmonic drive"
    " (dashed) and peak joint forces over a turn with the cam drive (solid), elastic joints; a sharp peak of the solid"
    " curve marks a harmonic h meeting a resonance at h times the shaft speed."
)
md(
    "**The speed limit with the cam rests on our significance fraction.** We count a harmonic for the limit if its"
    f" amplitude is at least {float(ds.significant_harmonic):g} of the first; at the nominal rise fraction that keeps h"
    f" ≤ {int(ds.top_harmonic_cam.sel(model=models[0], rise='nominal'))}. The table gives, for every harmonic in the"
    " drive, the shaft speed at which it meets the lowest resonance and the verdict on the limit if it were the"
    " highest harmonic counted (all inputs at their assumed values)."
)
rows = []
for h in ds.harmonic.values:
    if int(ds.cam_harmonic_present.sel(harmonic=h)):
        row = {
            "harmonic h": int(h),
            "|cₕ|/|c₁|": float(ds.cam_harmonic_amplitude.sel(harmonic=h)),
            "counted": (
                "yes" if float(ds.cam_harmonic_amplitude.sel(harmonic=h)) >= float(ds.significant_harmonic) else "no"
            ),
        }
        for m in models:
            row[f"model {m}: meets the lowest resonance at (rad/s)"] = float(
                ds.cam_harmonic_speed.sel(model=m, harmonic=h)
            )
            row[f"model {m}: limit verdict if h is the highest counted"] = str(
                fnd.verdict_limit_by_harmonic.sel(model=m, harmonic=h).values
            )
        rows.append(row)
table(
    pd.DataFrame(rows),
    {"|cₕ|/|c₁|": "{:.2g}", **{f"model {m}: meets the lowest resonance at (rad/s)": "{:.2f}" for m in models}},
)
weak_matches = [
    f"h = {r['harmonic h']} and no higher (a fraction above"
    f" {float(ds.cam_harmonic_window_low.sel(harmonic=r['harmonic h'])):.2g} and at most {r['|cₕ|/|c₁|']:.2g}) would"
    f" put model {m}'s limit"
    for r in rows
    for m in models
    if r["counted"] == "no" and r[f"model {m}: limit verdict if h is the highest counted"] == "reproduced"
]
md(
    ("So the cam's limit verdict depends on the significance fraction: counting " + "; ".join(weak_matches)
     + " at the paper's value, through a harmonic far weaker than the first. " if weak_matches else
     "No harmonic below the significance fraction would put the limit at the paper's value either. ")
    + f"We keep {float(ds.significant_harmonic):g}, an assumption; the cam verdicts below are only as firm as it is."
)
rows = []
for m in models:
    for c in fnd.claim.values:
        rows.append(
            (
                m, claim_short[str(c)], str(fnd.verdict_sine_nominal.sel(model=m, claim=c).values),
                str(fnd.verdict_cam_nominal.sel(model=m, claim=c).values),
                float(fnd.value_cam_nominal.sel(model=m, claim=c)),
                str(fnd.verdict_cam_over_rise.sel(model=m, claim=c).values),
            )
        )
table(
    pd.DataFrame(
        rows,
        columns=[
            "model",
            "claim",
            "verdict, harmonic drive, inputs fixed at their assumed values (no ranges)",
            "verdict, cam drive, inputs fixed",
            "measure, cam drive",
            (
                "cam drive over the rise fraction"
                f" {cam['rise_fraction']['range'][0]:g}–{cam['rise_fraction']['range'][1]:g}"
            ),
        ],
    ),
    {"measure, cam drive": "{:.4g}"},
)
md(
    "Do the harmonics change a verdict at the assumed parameters?"
    f" **{'yes' if int(fnd.cam_changes_a_verdict) else 'no'}**. With the cam the highest significant harmonic is h ="
    f" {int(ds.top_harmonic_cam.sel(model=models[0], rise='nominal'))}, so the lowest resonance is met at a shaft speed"
    " that many times lower. Weak higher harmonics matter where a resonance is undamped: at the assumed values model"
    " B's joint branches have no damper (the paper's chain has none), and a harmonic far below the significance"
    " threshold still raises a sharp peak when h times the shaft speed meets a branch's resonance, so the peak joint"
    " forces no longer grow over the whole band (the next table takes the joint damping over its range). The verdicts"
    " of the summary (with the ranges of every assumed input) are those of the harmonic drive, the paper's own"
    " excitation; where the cam changes one, the summary and its figure say so beside it. The harmonic-drive column"
    " here is the verdict with every input fixed at its assumed value, so it can read 'differs' where the summary,"
    " which also spans the inputs' ranges, reads 'decided by an unprinted input'."
)

# %% [markdown]
# ### Does the cam's verdict survive damped joints?

# %%
cd = fnd.joint_damping.values
zeta_top = float(fnd.joint_branch_damping_ratio.sel(model="B", joint_damping=cd[-1])) if "B" in models else float("nan")
md(
    "The cam's effect on model B rests on weak high harmonics (a fraction of a per cent of the first) meeting joint"
    " branches without damping. The paper's chain has no joint damper; a pinned joint with clearance does dissipate,"
    f" by friction and by impact. We take the joint damping as an assumed input from {cd[0]:g} to {cd[-1]:g} N s/m,"
    f" which gives model B's joint branches a damping ratio of up to {zeta_top:.3f} (jointed steel mechanisms are"
    " damped by a few per cent of critical), and judge the cam's claims at both ends."
)
rows = []
for m in models:
    for c in fnd.claim.values:
        row = {"model": model_names[m], "claim": claim_short[str(c)]}
        for x in cd:
            z = float(fnd.joint_branch_damping_ratio.sel(model=m, joint_damping=x))
            row[f"joint damping {x:g} N s/m (ζ = {z:.3f}): verdict, cam drive"] = str(
                fnd.verdict_cam_by_joint_damping.sel(model=m, claim=c, joint_damping=x).values
            )
        rows.append(row)
table(pd.DataFrame(rows))
dips = ", ".join(
    f"model {m}: {float(fnd.largest_dip_cam_by_joint_damping.sel(model=m, joint_damping=cd[0])):.1%} → "
    f"{float(fnd.largest_dip_cam_by_joint_damping.sel(model=m, joint_damping=cd[-1])):.2%}"
    for m in models
)
stand = bool((fnd.verdict_cam_by_joint_damping.values == fnd.verdict_cam_by_joint_damping.values[..., :1]).all())
dip_b = (
    float(fnd.largest_dip_cam_by_joint_damping.sel(model="B", joint_damping=cd[-1])) if "B" in models else float("nan")
)
md(
    "ζ is the damping ratio of the modes through the joints with D held (in model B the joint branches, in model A its"
    " one mode). Largest fall of a peak joint force between neighbouring speeds of the grid, from no joint damping to"
    f" the top of its range: {dips}.\n\n**Judgement of the cam clause.** "
    + (
        "Under our strict reading (the forces grow over the whole band) the cam's verdicts are the same at both ends"
        " of the damping range, so the clause stands in that reading; but with damped joints the falls that break"
        f" model B's growth are at most {dip_b:.2%} of the force, which no figure of the forces would show. The clause"
        " is therefore kept only as a statement about the strict reading, not as a visible effect of the cam."
        if stand
        else (
            "The cam's verdicts differ between the ends of the damping range: the clause depends on the joints'"
            " damping, which the paper does not give."
        )
    )
)

# %% [markdown]
# ## 5. Inconsistencies in the text and how we resolved them
#
# * **K7 is missing** from the list (1) of mobilities. By symmetry with K3 = 1/(jω m_E7) it is 1/(jω m_F8), the
#   bell-crank-8 mass at F, and both our models include it.
# * **The E/F labels.** K12 = jω/k_E7 is the elastic joint E and K13 = jω/k_F8 the joint F. The text then calls Q13 the
#   force in E and Q12 the force in F. Following the definitions in (1), the labels in the text are swapped. We report
#   Q_E and Q_F by joint, not by number.
# * **"M_P — mass of the rubber"** (масса резинки) is read as the heald frame (ремизка), the only heavy body on the
# output.
# * **The loom type** is "Sulzer-СТБ" in the introduction and "Sulzer-СБТ" in the conclusions; STB is meant.
# * **The speed limit is printed in two units**, min⁻¹ and s⁻¹ (meaning rad/s); the two printed values agree through
#   the factor 2π/60, so the conversion is right.

# %% [markdown]
# ## 6. Accuracy: frequency-grid resolution near a resonance
#
# What each grid costs in time is in the accuracy report: wall times are measurements of the machine, kept in that
# one report so that this one is the same to the byte on every rerun.

# %%
pts = acc.grid_points.values
fig, ax = plt.subplots(figsize=(7, 4), constrained_layout=True)
ax.loglog(pts, acc.peak_error, "o-")
ax.axvline(float(acc.pipeline_density), color="k", ls=":", lw=1, label="density of the pipeline's grid")
show_log_log(
    ax,
    "points of a uniform grid over the band",
    "relative error of the peak force",
    "Relative error of the peak input force on a uniform frequency grid over the study band, against the number of"
    " points; dotted: the density of the pipeline's grid.",
)
md(
    f"The reference is the peak of |{acc.attrs['quantity']}| (model {acc.attrs['model']}) located by bounded Brent "
    f"search in {int(acc.reference_evaluations)} force evaluations: {float(acc.reference_peak):.3f} N at "
    f"{float(acc.reference_omega):.4f} rad/s. A uniform grid approximates the peak with an error that falls roughly "
    "as (spacing)² / (peak width)², and it jumps with the alignment of grid points to the peak. Each point is one "
    "solve of the chain, so the work grows linearly with the number of points. "
    + (
        f"The peak is within 0.1 % from {float(acc.points_for_0_1_percent):.0f} points over the band onwards. "
        if np.isfinite(float(acc.points_for_0_1_percent))
        else ""
    )
    + "When the peak force is what matters, a coarse grid plus a local Brent refinement"
    f" ({int(acc.reference_evaluations)} evaluations here) costs far less than a fine grid."
)

# %% [markdown]
# ## 7. Beyond the paper: real clearance joints at E and F
#
# Both chains assume that the pins E and F keep contact in their clearances: Vulfson's elastic link is a spring
# loaded by a reaction that never lets go. Here the heald linkage is simulated with real clearance joints instead.
# It is written as a linkage description for the shared multibody engine:
#
# * the cam lever, driven with the dwell cam's motion of section 4, drives D through a short level link;
# * the rod DEF carries model A's masses at D, E and F, and its pins sit in the bell cranks' bushings at E and F
#   (dry, frictionless as the chain, Hertz contact with Lankarani–Nikravesh damping);
# * the bell cranks carry their masses at E and G (F and K), with the lever ratios η7 and η8;
# * the rods GH and KL lift the heald frame, which hangs on the warp (spring k_O with damping c_O) and under gravity;
# * a level guide link keeps the frame from swaying (the engine has no sliding joint).
#
# Every length is assumed (config `heald.contact`); the masses, stiffness, damping, clearances and stroke are
# model A's nominal parameters. Assumptions that decide the outcome:
#
# * the warp spring is unstretched at the cam's mean position, so the frame's whole weight hangs on the bell cranks;
# * the journals start centred in their bearings (the first cycles are a transient and are not judged);
# * the pins' radius and restitution set the size of the impact forces; they were not varied;
# * the radial clearance (heald.parameters) is also the largest gap a journal can open from its bearing's wall.
#
# At each speed the motion is run cycle by cycle until its state is found: **periodic** (the state repeats every
# k cycles), **stationary** (not periodic, but its measures are statistically steady), or **cycle cap reached**
# (neither found within the cycles allowed). Over the judged cycles a journal **has lost contact** when it is in
# free flight at some stored point. Two named cases are run:
#
# * the nominal parameters;
# * **weight dominant**: a soft warp, a short stroke and a heavy frame (k_O and stroke_D at the low ends of their
#   ranges, M_P at the high end, the others nominal), where the frame's weight outweighs the warp's pull.

# %%
cases = [str(c) for c in contact.case.values]
case_label = {c: c.replace("_", " ") for c in cases}  # config names, read as words
speeds = contact.speed.values
fig, axes = plt.subplots(1, 2, figsize=(11, 4.2), constrained_layout=True)
for i, case in enumerate(cases):
    sel = contact.sel(case=case)
    for joint, ls in (("E", "-"), ("F", "--")):
        axes[0].plot(
            speeds, sel[f"flight_{joint}"], ls, marker="o", color=f"C{i}", label=f"{case_label[case]}, joint {joint}"
        )
        axes[1].semilogy(
            speeds, sel[f"force_{joint}"], ls, marker="o", color=f"C{i}",
            label=f"{case_label[case]}, joint {joint}: clearance joint",
        )
        axes[1].semilogy(
            speeds, sel[f"chain_{joint}"], ls, marker="x", color=f"C{i}", alpha=0.5,
            label=f"{case_label[case]}, joint {joint}: model A's chain",
        )
for ax in axes:
    ax.axvline(limit / RAD_S_PER_RPM, color="k", ls=":", lw=1)
    ax.set_xlabel("main-shaft speed (rev/min)")
    ax.grid(alpha=0.3, which="both")
axes[0].set_ylabel("fraction of a cycle in free flight")
axes[1].set_ylabel("largest joint force over a cycle (N)")
axes[0].legend(fontsize=7)
axes[1].legend(fontsize=6, ncol=2)
plt.show()
caption(
    "The heald linkage with clearance joints at E and F, per named case (colour) and joint (solid E, dashed F). Left:"
    " the largest fraction of a judged cycle in which the journal is in free flight (zero: contact held). Right: the"
    " largest contact force over the judged cycles (circles) beside model A's linear chain under the same cam drive"
    " (crosses, peak |Q| over a cycle). Dotted: the paper's speed limit."
)
rows = []
for case in cases:
    for v in speeds:
        sel = contact.sel(case=case, speed=v)
        rows.append(
            (
                case_label[case],
                f"{v:g}",
                str(sel.state_status.values)
                + (f" (period {int(sel.state_period)})" if int(sel.state_period) > 0 else ""),
                f"{float(sel.flight_E):.3f} / {float(sel.flight_F):.3f}",
                f"{float(sel.gap_E) * 1e6:.0f} / {float(sel.gap_F) * 1e6:.0f}",
                f"{float(sel.force_E):.0f} / {float(sel.force_F):.0f} ({float(sel.force_numerical_error):.0f})",
                f"{float(sel.chain_E):.0f} / {float(sel.chain_F):.0f}",
            )
        )
table(
    pd.DataFrame(
        rows,
        columns=[
            "case", "speed (rev/min)", "state", "free flight, E / F (fraction of a cycle)", "largest gap, E / F (µm)",
            "largest contact force, E / F (N; in brackets: its sensitivity)", "model A's chain: peak |Q_E| / |Q_F| (N)",
        ],
    ),
    caption=(
        "Per case and speed: the settled state, the free flight and the largest gap of each journal, its largest"
        " contact force, and model A's linear chain under the same drive. In brackets: the change of the mean per-cycle"
        " peak (the larger of E and F) when the first judged cycles are rerun at a tighter tolerance. Where the"
        " journals fly it measures how sensitive the impact peaks are, not an error bar on the largest force: the"
        " impact peaks are good to their order of magnitude only."
    ),
)


chosen = str(entries["drive.frequency"]["value"])  # the drive scenario the linkage was run at


def _loss_text(case: str) -> str:
    sel = contact.sel(case=case)
    held, lost = float(sel.held_up_to_rpm.sel(drive=chosen)), float(sel.first_lost_rpm.sel(drive=chosen))
    margin = float(sel.reversal_margin)
    static = (
        "the warp's largest pull on the frame (k_O η7 max|x_D|, quasi-static, x_D the cam's displacement at D, whose"
        f" first harmonic has the amplitude stroke_D) is {float(sel.warp_pull):.1f} N against the"
        f" {float(sel.weight_held):.1f} N of weight the bell cranks hold up, a margin of {margin:.2f}, so "
        + (
            "the load at E and F along the drive reverses within every cycle even at the slowest speed"
            if margin > 1
            else "the load at E and F along the drive does not reverse quasi-statically"
        )
    )
    if np.isnan(held) and np.isfinite(lost):
        where = f"contact is lost already at the lowest speed simulated, {lost:g} rev/min"
    elif np.isfinite(lost):
        where = (
            f"contact holds up to {held:g} rev/min and is lost from {lost:g} rev/min on (no speed between the two was"
            " simulated)"
        )
        at = sel.sel(speed=held)
        if str(at.state_status.values) not in ("periodic", "stationary"):
            where += (
                f"; at {held:g} rev/min the state was not found within the {int(at.cycles_run)} cycles run (status:"
                f" {at.state_status.values}), but contact held in every judged cycle"
            )
    else:
        where = f"contact holds at every speed simulated, up to {held:g} rev/min"
    return f"**{case_label[case]}**: {static}; {where}. {_rigid_text(sel)}"


def _rigid_text(sel) -> str:
    """Where the rigid linkage's reaction at E and F reverses along the rod, in two dimensions."""
    rigid = "In the rigid linkage (E and F closed)"
    least, most = (float(sel.rigid_turn_range.sel(bound=b)) for b in ("least", "most"))
    if int(sel.rigid_reverses_quasi_statically.sum()) == 2:
        return (
            f"{rigid} the reaction at each joint turns through {least:.0f}–{most:.0f}° within every cycle at every"
            " speed simulated: the journals are carried across their clearances."
        )
    speeds = sel.rigid_reversal_rpm.sel(drive=chosen)
    e, f_ = float(speeds.sel(joint="E")), float(speeds.sel(joint="F"))
    if not (np.isfinite(e) or np.isfinite(f_)):
        return f"{rigid} the reaction along the rod keeps its sense at every speed simulated."
    side = sel.rigid_sideways_at_reversal
    held_rpm, lost_rpm = float(sel.held_up_to_rpm.sel(drive=chosen)), float(sel.first_lost_rpm.sel(drive=chosen))
    same = held_rpm < min(e, f_) and max(e, f_) <= lost_rpm
    return (
        f"{rigid} the reaction's component along the rod first changes sense at {e:.1f} rev/min at E and {f_:.1f} at"
        " F. The reaction does not pass through zero there: it swings round past a sideways force of"
        f" {float(side.sel(joint='E')):.1f} N at E and {float(side.sel(joint='F')):.1f} N at F, turning through up to"
        f" {float(sel.rigid_turn_above_reversal):.0f}° per cycle at the speeds simulated above (at most"
        f" {float(sel.rigid_turn_below_reversal):.0f}° below). "
        + (
            "The simulated contact loss falls in the same bracket: it is this reversal."
            if same
            else "That is outside the simulated bracket of contact loss."
        )
    )


limit_rpm = limit / RAD_S_PER_RPM
other = [str(d) for d in contact.drive.values if str(d) != chosen]
band_rpm = float(fnd.limit_band) / RAD_S_PER_RPM  # the limit claim's tolerance band (section 1)


def _reaches_band(c: str, d: str) -> bool:
    """Whether the bracket (held, lost] of the contact-loss shaft speed reaches the limit's tolerance band."""
    h, f_ = float(contact.held_up_to_rpm.sel(case=c, drive=d)), float(contact.first_lost_rpm.sel(case=c, drive=d))
    return np.isfinite(f_) and f_ >= limit_rpm - band_rpm and not h >= limit_rpm + band_rpm


straddle = [
    (
        case_label[c], str(d), float(contact.held_up_to_rpm.sel(case=c, drive=d)),
        float(contact.first_lost_rpm.sel(case=c, drive=d)),
    )
    for c in cases
    for d in other
    if _reaches_band(c, d)
]
held = contact.where(~contact.contact_lost)  # the cases and speeds at which contact holds (NaN elsewhere)
held_points = [(str(c), float(v)) for c in cases for v in speeds if not bool(contact.contact_lost.sel(case=c, speed=v))]
beyond_weight = (  # the largest forces at E and F less the weight's static share at each
    held.force_E + held.force_F - contact.weight_share.sel(joint="E") - contact.weight_share.sel(joint="F")
)
held_text = (
    (
        "Where contact holds ("
        + "; ".join(
            f"{case_label[c]} at {v:g} rev/min: E/F ="
            f" {float(held.force_E.sel(case=c, speed=v) / held.force_F.sel(case=c, speed=v)):.2f} in the linkage,"
            f" {float(held.chain_E.sel(case=c, speed=v) / held.chain_F.sel(case=c, speed=v)):.2f} in the chain; the"
            " largest forces at E and F less the weight's static share"
            f" ({float(contact.weight_share.sel(case=c, joint='E')):.0f} and"
            f" {float(contact.weight_share.sel(case=c, joint='F')):.0f} N) sum to"
            f" {float(beyond_weight.sel(case=c, speed=v)):.0f}"
            " N against the chain's"
            f" {float(held.chain_E.sel(case=c, speed=v) + held.chain_F.sel(case=c, speed=v)):.0f} N"
            for c, v in held_points
        )
        + "), the linkage carries the frame's weight, which the chain leaves out; less that weight the two agree on the"
        " total, and they differ in the split between E and F: the linkage's follows its own geometry, model A's the"
        " reactions assumed at E and F."
    )
    if held_points
    else "Contact is lost at every case and speed simulated."
)
below = [
    c for c in cases if float(contact.first_lost_rpm.sel(case=c, drive=chosen)) < limit_rpm - band_rpm
]  # NaN (never lost) is not below
md(
    "\n\n".join(_loss_text(c) for c in cases)
    + f"\n\n**Does contact loss explain the paper's {limit_rpm:.0f} min⁻¹ limit?** In the chosen scenario"
    f" ({drive_labels[chosen]}): "
    + (
        "not under these assumed parameters. In"
        f" {'every case' if len(below) == len(cases) else ', '.join(case_label[c] for c in below)} a journal leaves its"
        f" bearing's wall below the limit's tolerance band ({limit_rpm - band_rpm:.0f}–{limit_rpm + band_rpm:.0f}"
        " min⁻¹), and at the higher speeds simulated the journals fly for part of every cycle (the table); nothing in"
        f" these results singles out {limit_rpm:.0f} min⁻¹ beyond the scatter of the impacts. "
        if below
        else "no case loses contact below the limit's tolerance band. "
    )
    + "The linkage sees only the drive frequency, so under another drive scenario the same states fall at other shaft"
    " speeds. "
    + (
        "; ".join(
            f"In the scenario '{drive_labels[d]}', in the {c} case contact holds up to {h:g} and is lost from {f_:g}"
            " shaft rev/min: that bracket reaches the limit's tolerance band, so the speeds simulated cannot decide"
            " whether contact loss marks the limit there"
            for c, d, h, f_ in straddle
        )
        + ". "
        if straddle
        else "Under the other drive scenarios no bracket of the contact-loss speed reaches the limit's tolerance band"
        + "".join(
            f" (in the scenario '{drive_labels[d]}' the rigid reaction of the {case_label[c]} case reverses at"
            f" {float(contact.rigid_reversal_rpm.sel(case=c, drive=d, joint=j)):.0f} shaft rev/min at {j})"
            for c in cases
            for d in other
            for j in ("E",)
            if np.isfinite(float(contact.rigid_reversal_rpm.sel(case=c, drive=d, joint=j)))
        )
        + ". "
    )
    + "**Joint forces.** "
    + held_text
    + " Once the journals fly, the largest forces are those of impacts. They differ from the chain's in either"
    " direction (the table: the chain has its own resonances), their size varies from cycle to cycle, and the"
    " bracketed column shows how much the peaks move when the same cycles are rerun at a tighter tolerance. The chain"
    " assumes held contact, so it does not describe the linkage where contact is lost. Every number here holds for"
    " the assumed lengths, pin and parameters only."
)

# %% [markdown]
# ## Provenance

# %%
provenance(ds)
md("Section 7 (the heald linkage with clearance joints):")
provenance(contact)
