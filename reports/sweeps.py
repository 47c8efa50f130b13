# ---
# jupyter:
#   jupytext:
#     formats: py:percent
#     text_representation:
#       extension: .py
#       format_name: percent
# ---

# %% [markdown]
# # Parameter sweeps
#
# Each sweep's grid is split into independent Snakemake jobs (`results/sweeps/<sweep>/job_<i>.nc`, several points
# each), gathered into one netCDF together with the facts the paragraphs below state: how each output changes along
# each axis, where a claim's threshold is crossed, and the colour range of each map. The grid size is chosen by
# `sweeps.grid` in `config/config.yaml`: `small` runs here, `large` is meant for a cluster (`--profile profiles/slurm`).
#
# **Colour scale.** Every map is coloured on a logarithmic scale centred on a reference value — the claim's
# threshold where the map has one, otherwise the value at the reference point (the cell outlined in black, the
# paper's or config's nominal values) — and symmetric about it: the colour bar runs from the centre divided by a
# factor to the centre times the same factor, the factor being the largest ratio on the map but never less than the
# floor stated in each caption. Equal colour steps are equal ratios, so a 5 % change is a small step, whatever
# the map's own spread. The number in each cell is the value itself.

# %%
import json

import matplotlib.pyplot as plt
import numpy as np
from _common import caption, esc, inputs, load, md, provenance

files = inputs()
cl = load(files["result"])
he = load(files["heald"])
cl_spec = json.loads(cl.attrs["config_json"])["spec"]
he_spec = json.loads(he.attrs["config_json"])["spec"]

AXIS_LABEL = {"clearance_m": ("clearance (µm)", 1e6), "crank_speed_rad_s": ("crank speed (rad/s)", 1.0),
              "reaction_ratio_EF": ("|R_E| / |R_F| (assumed)", 1.0)}


def fmt_axis(dim, value):
    label, scale = AXIS_LABEL[dim]
    return f"{value * scale:.3g}"


def axis_name(dim):
    return AXIS_LABEL[dim][0].split(" (")[0]


def axis_unit(dim):
    label = AXIS_LABEL[dim][0]
    return label[label.index("(") + 1 : -1] if "(" in label and "assumed" not in label else ""


def heat_map(ax, ds, var, xdim, ydim, linear=False, outside=None):
    """One output over the grid: log colour range from the result (``linear``: from 0), reference cell outlined,
    threshold contour; ``outside`` (ydim x xdim booleans): cells outside the model, hatched and their value marked ‡."""
    data = ds[var].transpose(ydim, xdim)
    low, high = float(ds.colour_low.sel(output=var)), float(ds.colour_high.sel(output=var))
    if linear:
        low = np.nan
    scale = (
        {"norm": "log", "vmin": low, "vmax": high}
        if np.isfinite(low)
        else {"vmin": 0.0, "cmap": "Greys"} if linear else {}
    )
    im = ax.pcolormesh(
        np.arange(ds[xdim].size), np.arange(ds[ydim].size), data.values, shading="nearest",
        **{"cmap": "RdBu_r", **scale},
    )
    ax.set_xticks(np.arange(ds[xdim].size), [fmt_axis(xdim, v) for v in ds[xdim].values])
    ax.set_yticks(np.arange(ds[ydim].size), [fmt_axis(ydim, v) for v in ds[ydim].values])
    for i in range(ds[ydim].size):
        for j in range(ds[xdim].size):
            shade = float(im.norm(data.values[i, j]))
            beyond = outside is not None and bool(outside[i, j])
            ax.text(
                j, i, f"{data.values[i, j]:.3g}" + ("‡" if beyond else ""), ha="center", va="center", fontsize=9,
                color="w" if shade > (0.6 if linear else 0.8) or (shade < 0.2 and not linear) else "k",
            )
            if beyond:
                ax.add_patch(plt.Rectangle((j - 0.5, i - 0.5), 1, 1, fill=False, hatch="//", edgecolor="0.35", lw=0))
    rx = list(ds[xdim].values).index(ds.attrs[f"reference_{xdim}"])
    ry = list(ds[ydim].values).index(ds.attrs[f"reference_{ydim}"])
    ax.add_patch(plt.Rectangle((rx - 0.5, ry - 0.5), 1, 1, fill=False, edgecolor="k", linewidth=2))
    threshold = float(ds.threshold_value.sel(output=var))
    if np.isfinite(threshold):
        ax.contour(
            np.arange(ds[xdim].size), np.arange(ds[ydim].size), data.values, levels=[threshold], colors="k",
            linewidths=2, linestyles="--",
        )
    ax.set_xlabel(AXIS_LABEL[xdim][0])
    ax.set_ylabel(AXIS_LABEL[ydim][0])
    ax.tick_params(axis="x", labelrotation=45)
    unit = ds[var].attrs["units"]
    ax.set_title(ds[var].attrs["long_name"] + (f" ({unit})" if unit != "1" else ""), fontsize=8, wrap=True)
    bar = ax.figure.colorbar(im, ax=ax)
    if np.isfinite(
        low
    ):  # five labelled ticks, equal ratios apart: the ends and the centre (threshold or reference value)
        bar.set_ticks(np.geomspace(low, high, 5))
    bar.ax.yaxis.set_major_formatter("{x:.3g}")
    bar.ax.yaxis.set_minor_formatter("")


def heat_row(ds, names, xdim, ydim, width, outside=None):
    """One row of heat maps of ``names`` over ``xdim`` x ``ydim`` (figure ``width`` in inches)."""
    fig, axes = plt.subplots(1, len(names), figsize=(width, 6.0), constrained_layout=True)
    for ax, var in zip(axes.flat, names):
        heat_map(ax, ds, var, xdim, ydim, outside=outside)
    plt.show()


def percent_range(ds, var, dim):
    """'+a to +b %' of the change along ``dim`` (smallest and largest over the other axis)."""
    lo, hi = float(ds.trend_change_low.sel(output=var, axis=dim)), float(ds.trend_change_high.sel(output=var, axis=dim))
    return f"{100 * lo:+.0f} %" if f"{100 * lo:+.0f}" == f"{100 * hi:+.0f}" else f"{100 * lo:+.0f} to {100 * hi:+.0f} %"


def trend_sentence(ds, var, dims, short):
    """How one output changes along each axis (from the result's trend facts)."""
    other = {dims[0]: dims[1], dims[1]: dims[0]}
    parts = []
    for dim in dims:
        lines = ds[other[dim]].size
        monotone = round(float(ds.trend_monotone_fraction.sel(output=var, axis=dim)) * lines)
        unit = axis_unit(dim)
        parts.append(
            f"from {axis_name(dim)} {fmt_axis(dim, ds[dim].values[0])} to"
            f" {fmt_axis(dim, ds[dim].values[-1])}{' ' + unit if unit else ''} it changes by"
            f" {percent_range(ds, var, dim)} (over the {lines} values of {axis_name(other[dim])}; monotone on"
            f" {monotone} of {lines})"
        )
    span = 100 * float(ds.relative_span.sel(output=var))
    ref = float(ds.reference_value.sel(output=var))
    unit = "" if ds[var].attrs["units"] == "1" else " " + esc(ds[var].attrs["units"])
    return (
        f"**{esc(short[0].upper() + short[1:])}** is {ref:.3g}{unit} at the reference point and spans {span:.0f} % of"
        " that over the grid; "
        + "; ".join(parts)
        + "."
    )


def threshold_sentence(ds, var, along, other, what_above, what_below):
    """Where the output crosses its threshold along ``along``, for every value of ``other``."""
    crossing, side = ds[f"{var}_threshold_crossing"], ds[f"{var}_threshold_side"]
    threshold = float(ds.threshold_value.sel(output=var))
    unit = axis_unit(along)
    items = []
    for k in range(ds[other].size):
        at = f"{axis_name(other)} {fmt_axis(other, ds[other].values[k])}"
        s = int(side.values[k])
        if s == 0:
            items.append(f"{at}: {fmt_axis(along, float(crossing.values[k]))}{' ' + unit if unit else ''}")
        else:
            items.append(f"{at}: {what_above if s > 0 else what_below} on the whole grid")
    held = 100 * float(ds.threshold_holds_fraction.sel(output=var))
    ref = float(ds.reference_value.sel(output=var))
    return (
        f"The threshold {threshold:g} ({esc(str(ds.threshold_label.sel(output=var).values))}; dashed line) is crossed"
        f" along {axis_name(along)} at — "
        + "; ".join(items)
        + f". {held:.0f} % of the grid cells are at or above it; at the reference point "
        f"the value is {ref:.3g}, {'at or above' if ref >= threshold else 'below'} the threshold."
    )


# %% [markdown]
# ## Clearance sweep: radial clearance × crank speed
#
# ### Validity map: where the Hertz contact model holds

# %%
dims = ("clearance_m", "crank_speed_rad_s")
cl_valid = ["penetration_over_limit", "peak_joint_force", "peak_force_over_ideal"]
# where the journal penetrates its bushing by more than the clearance itself, the contact model does not apply at all
beyond_clearance = (cl.penetration_over_clearance > 1).transpose("clearance_m", "crank_speed_rad_s").values
heat_row(cl, cl_valid, "crank_speed_rad_s", "clearance_m", width=17, outside=beyond_clearance)
caption(
    f"Validity map of the clearance model: {esc(cl.attrs['scene_description'])},"
    f" {esc(cl.attrs['variant_description'])}, over the judged turns of the state each point settles into (the"
    " clearance scenes' rule, first start). Left: the deepest penetration over the sphere law's penetration limit (eq."
    " (9) holds while the contact arc is short; 1 = the edge of its range, dashed where the map crosses it)."
    " Middle: the peak contact force. Right: the peak contact force over the largest reaction the same joints carry"
    " with ideal (no-clearance) joints."
    " Outlined: the paper's clearance and speed. Hatched and marked ‡: the penetration exceeds the clearance itself,"
    " outside any contact model of a journal in its bushing. Colour: log scale centred on the threshold (left) or the"
    f" reference value, symmetric, at least ×/÷ {cl.attrs['colour_floor_factor']:g}."
)

# %%
md(
    threshold_sentence(
        cl, "penetration_over_limit", "clearance_m", "crank_speed_rad_s", "penetration beyond the sphere law's range",
        "penetration inside the sphere law's range",
    )
    + " Beyond the limit the contact arc is too wide for eq. (9)'s sphere law: the forces and the claims' measures"
    " there describe that law, not a conformal journal in its bushing (the clearance report reruns the scenes under a"
    " conformal law).\n\n"
    + "\n\n".join(trend_sentence(cl, var, dims, cl[var].attrs["long_name"]) for var in cl_valid)
)

# %% [markdown]
# ### The claims' measure and its cycle-to-cycle scatter

# %%
cl_dev = ["rocker_acceleration_deviation", "crank_torque_deviation"]
fig, axes = plt.subplots(2, 2, figsize=(12, 10), constrained_layout=True)
for k, var in enumerate(cl_dev):
    heat_map(axes[0, k], cl, var, "crank_speed_rad_s", "clearance_m", outside=beyond_clearance)
    heat_map(axes[1, k], cl, var + "_relative_cycle_spread", "crank_speed_rad_s", "clearance_m", linear=True,
             outside=beyond_clearance)
plt.show()
caption(
    f"The claims' measure on the same grid ({esc(cl.attrs['scene_description'])},"
    f" {esc(cl.attrs['variant_description'])}): RMS deviation from the ideal joints over the RMS of the ideal response,"
    " per recorded cycle, for the rocker acceleration (left, claim 1) and the crank torque (right, claim 2). Top: mean"
    " over the judged turns of each point's settled state. Bottom: the spread of the same turns (largest − smallest)"
    " over their mean; 0 where the state is a periodic orbit of one turn; linear grey scale from 0. Outlined: the"
    " paper's clearance and speed. Hatched and marked ‡: the penetration exceeds the clearance, outside the model."
)


# %%
def resolved_sentence(ds, var, dims):
    """Along each axis: on how many lines the change exceeds the cycle spread (from the result)."""
    other = {dims[0]: dims[1], dims[1]: dims[0]}
    parts = []
    for dim in dims:
        lines = ds[other[dim]].size
        up = round(float(ds.trend_resolved_up_fraction.sel(output=var, axis=dim)) * lines)
        down = round(float(ds.trend_resolved_down_fraction.sel(output=var, axis=dim)) * lines)
        steps = 100 * float(ds.trend_resolved_step_fraction.sel(output=var, axis=dim))
        parts.append(
            f"along {axis_name(dim)} it **{esc(str(ds.trend_resolved_class.sel(output=var, axis=dim).values))}**: the"
            f" change from the first to the last grid value exceeds the spread on {up + down} of {lines} lines ({up}"
            f" up, {down} down; the change itself is {percent_range(ds, var, dim)}), and {steps:.0f} % of the steps"
            " between neighbouring grid values do"
        )
    ref, lo, hi = (
        100 * float(ds[k].sel(output=var))
        for k in ("relative_scatter_reference", "relative_scatter_low", "relative_scatter_high")
    )
    return (
        f"**{esc(ds[var].attrs['long_name'][:1].upper() + ds[var].attrs['long_name'][1:])}**:"
        f" {float(ds.reference_value.sel(output=var)):.3g} at the reference point, with a cycle spread of {ref:.0f} %"
        f" of that (from {lo:.0f} to {hi:.0f} % over the grid); "
        + "; ".join(parts)
        + "."
    )


md(
    "What this map can show: how far the scene with both joints in clearance departs from the ideal joints, and whether"
    " that departure changes with clearance or speed by more than the response's own cycle-to-cycle scatter. What it"
    " cannot show: the paper's orderings (joint 2 > joint 1 for the acceleration, the reverse for the torque) need the"
    " single-joint scenes, which this sweep does not run (the clearance report judges them from two starts); and a"
    " change counts as a trend below only where it exceeds the sum of the spreads of the two cells it compares (their"
    " cycle ranges are then apart).\n\n"
    + "\n\n".join(resolved_sentence(cl, var, dims) for var in cl_dev)
)

# %% [markdown]
# ## Heald sweep: joint clearance × assumed reaction ratio |R_E| / |R_F|

# %%
he_vars = ["ratio_EF_min", "peak_Q_E", "peak_Q_F"]
he_dims = ("clearance_m", "reaction_ratio_EF")
heat_row(he, he_vars, "reaction_ratio_EF", "clearance_m", width=16)
caption(
    f"Heald sweep, model {esc(he.attrs['model'])}, elastic (Vulfson) joints, over the configured speed band: the"
    " smallest E/F force ratio with the first claim's threshold (dashed where the map crosses it), and the peak joint"
    " forces. |R_F| is held at"
    " its configured value and |R_E| moved with the ratio; both joints get the same clearance. Outlined: the"
    " configured clearance and reaction ratio. Colour: log scale centred on the threshold (left) or the reference"
    f" value, symmetric, at least ×/÷ {he.attrs['colour_floor_factor']:g}."
)

# %%
wb = he.warp_branch_change
md(
    "Both axes act on the E and F branches. The heald-frame mass M_P and the warp stiffness k_O are not swept: under"
    " the velocity drive of the chain, multiplying "
    + ", ".join(f"{esc(str(k))} by {float(f):g}" for k, f in zip(wb.warp_parameter.values, he.warp_factor.values))
    + " changes |Q_E| and |Q_F| at the reference point (relative, over the band) by at most "
    + f"{float(wb.sel(model='B', warp_parameter='M_P')):.1e} (M_P) and"
    f" {float(wb.sel(model='B', warp_parameter='k_O')):.1e} (k_O) in model B (the linear solver's round-off: its E"
    " and F branches hang on the driven node, whose velocity is prescribed, and never see the warp branch), and by"
    f" up to {100 * float(wb.sel(model='A', warp_parameter='M_P')):.0f} % (M_P) and"
    f" {100 * float(wb.sel(model='A', warp_parameter='k_O')):.0f} % (k_O) in model A, where they scale the peak"
    " forces.\n\n"
    + "\n\n".join(trend_sentence(he, var, he_dims, he[var].attrs["long_name"]) for var in he_vars)
    + "\n\n"
    + threshold_sentence(he, "ratio_EF_min", "reaction_ratio_EF", "clearance_m", "the claim holds", "the claim fails")
    + " The claim therefore holds only where the assumed reaction ratio exceeds the crossing value: the smallest E/F"
    " ratio over the band is the ratio of the two joints' Vulfson stiffnesses, which follows the assumed reactions,"
    " so the chain returns nearly the ratio it was given."
)

# %% [markdown]
# ## Provenance
#
# Clearance sweep:

# %%
provenance(cl)

# %% [markdown]
# Heald sweep:

# %%
provenance(he)
