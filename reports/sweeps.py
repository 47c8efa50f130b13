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
# Each grid point is an independent Snakemake job (`results/sweeps/<sweep>/point_<i>.nc`), gathered into one netCDF.
# The grid size is chosen by `sweeps.grid` in `config/config.yaml`: `small` runs here, `large` is meant for a cluster
# (`--profile profiles/slurm`).

# %%
import json

import matplotlib.pyplot as plt
import numpy as np
from _common import caption, inputs, load, md

files = inputs()
cl = load(files["result"])
he = load(files["heald"])
cl_spec = json.loads(cl.attrs["config_json"])["spec"]
he_spec = json.loads(he.attrs["config_json"])["spec"]

# %%
fig, axes = plt.subplots(2, 2, figsize=(12, 9), constrained_layout=True)
panels = [
    (cl, "peak_joint_force", "crank_speed_rad_s", "clearance_m", 1.0, 1e6, "crank speed (rad/s)", "clearance (µm)"),
    (cl, "rms_rocker_acceleration", "crank_speed_rad_s", "clearance_m", 1.0, 1e6, "crank speed (rad/s)", "clearance (µm)"),
    (he, "peak_Q_E", "heald_mass_kg", "clearance_m", 1.0, 1e6, "heald-frame mass (kg)", "clearance (µm)"),
    (he, "ratio_EF_min", "heald_mass_kg", "clearance_m", 1.0, 1e6, "heald-frame mass (kg)", "clearance (µm)"),
]
for ax, (ds, var, xdim, ydim, xs, ys, xl, yl) in zip(axes.flat, panels):
    data = ds[var].transpose(ydim, xdim)
    im = ax.pcolormesh(np.arange(ds[xdim].size), np.arange(ds[ydim].size), data.values, shading="nearest")
    ax.set_xticks(np.arange(ds[xdim].size), [f"{v * xs:.3g}" for v in ds[xdim].values])
    ax.set_yticks(np.arange(ds[ydim].size), [f"{v * ys:.3g}" for v in ds[ydim].values])
    for i in range(ds[ydim].size):
        for j in range(ds[xdim].size):
            ax.text(j, i, f"{data.values[i, j]:.3g}", ha="center", va="center", fontsize=8, color="w")
    ax.set_xlabel(xl)
    ax.set_ylabel(yl)
    ax.set_title(f"{ds[var].attrs['long_name']} ({ds[var].attrs['units']})", fontsize=9)
    fig.colorbar(im, ax=ax)
plt.show()
caption("Heat maps of the sweeps (value in each cell): top, the clearance sweep (peak joint force and RMS rocker acceleration over clearance and crank speed); bottom, the heald sweep (peak |Q_E| and the smallest E/F ratio over clearance and frame mass).")
md(
    f"Clearance sweep: scene `{cl_spec['scene']}`, variant `{cl_spec['variant']}`, {cl_spec['settle_cycles']} settling and "
    f"{cl_spec['record_cycles']} recorded cycle(s) per point. Heald sweep: model {he_spec['model']}, "
    "elastic joints, over the configured speed band."
)
