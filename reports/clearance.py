# ---
# jupyter:
#   jupytext:
#     formats: py:percent
#     text_representation:
#       extension: .py
#       format_name: percent
# ---

# %% [markdown]
# # Four-bar with clearance joints and lubrication: reproduction report
#
# **Paper.** Li Yuanyuan, Chen Guoping, Gao Yong, Sun Dongyang, "Dynamics analysis of no-load four-link mechanism with
# multiple clearance and lubrication joints", *J. Nanjing Univ. Aeronautics & Astronautics* 49(6), 2017. The
# extracted text is garbled; the values were decoded with the project digest's key.
#
# **What the paper does.** It models a four-bar (ground, crank, coupler, rocker) as a planar multibody system with
# Baumgarte stabilisation and gives joint 1 (crank–coupler) and/or joint 2 (coupler–rocker) a radial clearance. Dry
# contact follows Lankarani–Nikravesh with a modified Coulomb friction; lubricated joints follow Sommerfeld's
# long-bearing film. It integrates with RK4 and plots the rocker's angular acceleration (Figs. 5–7) and the crank
# torque (Figs. 8–10) against the ideal. **No number is printed**, so the paper's three claims are judged with robust
# measures.
#
# **What we do.** Bodies are in (x, y, φ). The ideal joints and the driver are constraints with the paper's Baumgarte
# stabilisation (α = β = 250). Clearance joints are force elements. Each scene names its effects, and its right-hand
# side is generated from exactly those effects and compiled. Dry scenes use adaptive Dormand–Prince 5(4). The
# lubricated scenes are stiff (the squeeze film is a damper of about 1e7–1e8 N·s/m on bodies of about 1 kg) and use
# BDF. The ideal scene is inverse dynamics, with no time integration.

# %%
import json
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
from _common import load, md, report_context, table

inputs, _ = report_context(
    {
        "result": "results/clearance/claims.nc",
        "accuracy": "results/clearance/accuracy.nc",
        "timings": "results/clearance/accuracy_timings.json",
        "comparison": "results/clearance/comparison.csv",
        "published": "config/published/clearance.yaml",
        "scenes": "results/clearance/decoded/ideal.nc",
    }
)
claims = load(inputs["result"])
wp = load(inputs["accuracy"])
timings = load(inputs["timings"])
cmp = load(inputs["comparison"])
section = json.loads(claims.attrs["config_json"])
root = Path(inputs["scenes"]).parent.parent
variants = [str(v) for v in claims.variant.values]
scenes = {
    (v, s): load(root / v / f"{s}.nc") for v in variants for s in section["scenes"]
}

# %% [markdown]
# ## Summary: each claim per parameter variant
#
# A claim holds only if it holds for both the RMS and the peak deviation from the ideal curve, in both recorded
# cycles, and at both integrator tolerances (pipeline and tight).

# %%
verd = cmp.pivot(index="quantity", columns="model", values="verdict").reset_index()
table(verd.rename(columns={v: f"verdict ({v})" for v in variants}))
md(
    "*decoded*: the inertias as decoded from the text (their radii of gyration exceed the link lengths). "
    "*slender*: J = mL²/12. Each verdict is broken down below by measure, cycle and tolerance."
)

# %%
rows = []
for v in variants:
    for measure in ("rms_deviation", "peak_deviation"):
        for qi, q in enumerate(claims.quantity.values):
            x = claims[measure].sel(variant=v, quantity=q)
            for tol in claims.tolerance_set.values:
                for c in claims.cycle.values:
                    vals = x.sel(tolerance_set=tol, cycle=c).values
                    rows.append((v, measure.split("_")[0], q, tol, int(c), *vals))
det = pd.DataFrame(rows, columns=["variant", "measure", "quantity", "tolerance", "cycle", *claims.scene.values])
order_ok = []
for _, r in det.iterrows():
    if r.quantity == "rocker_acceleration":
        order_ok.append(bool(r.dry_2 > r.dry_1 and r.dry_both > max(r.dry_1, r.dry_2)))
    else:
        order_ok.append(bool(r.dry_1 > r.dry_2 and r.dry_both > max(r.dry_1, r.dry_2)))
det["order as claimed"] = np.where(order_ok, "matches", "deviates")
det["lubricated / dry (max)"] = [max(r.lubricated_1 / r.dry_1, r.lubricated_2 / r.dry_2, r.lubricated_both / r.dry_both) for _, r in det.iterrows()]
fmt = {s: "{:.3g}" for s in claims.scene.values} | {"lubricated / dry (max)": "{:.3f}"}
table(det, fmt, caption="Deviation from the ideal curve (rad/s² for the acceleration, N·m for the torque), per cycle and tolerance")

# %% [markdown]
# ## 1. Model, parameters and the defects of the printed model

# %%
b, j, a = section["bodies"], section["joints"], section["assumed"]
rows = [(f"{k} (L, m, J)", f"{v['length_m']:.4g} m, {v['mass_kg']:g} kg, {v['inertia_kg_m2']:g} kg·m²", "decoded") for k, v in b.items()]
rows += [("ground", f"{section['ground_m']} m", "decoded"), ("crank speed", f"{section['crank_speed_rad_s']:.4g} rad/s", "decoded (20π)"),
         ("journal / bearing radius", f"{j['journal_radius_m'] * 1e3:g} / {j['bearing_radius_m'] * 1e3:g} mm", "decoded"),
         ("E, ν", f"{j['youngs_modulus_Pa'] / 1e9:g} GPa, {j['poisson']}", "decoded"),
         ("restitution, friction", f"{j['restitution']}, {j['friction']}", "decoded"),
         ("viscosity", f"{j['viscosity_Pa_s']} Pa·s", "decoded"), ("contact law", j["contact_law"], "paper")]
rows += [(k, f"{v['value']:g}", f"{v['status']}: {v['reason']}") for k, v in a.items()]
rows += [("centres of mass", "mid-link", "assumed"), ("gravity", "on (the scenes name it)", "assumed: the paper's 'no-load' means no external load"),
         ("start", "crank and coupler extended (rocker dead point), journals centred", "paper / assumed")]
table(pd.DataFrame(rows, columns=["parameter", "value", "source"]))
ideal = scenes[(variants[0], "ideal")]
md(
    f"""
**Resolved defects of the printed model:**

* *Sign of the contact force (eqs. 4/17).* As printed, the eccentricity runs from bearing to journal while the force is
  assigned so that it pushes the journal outward. We define e = journal − bearing centre and put −F_N n on the journal,
  pushing it back into the bearing. The printed sign would make the contact attract the surfaces, i.e. pull the journal
  further into the wall, so it cannot represent an impact.
* *Wedge term (eq. 22).* The text speaks of "the relative angular velocity", but both journal and bearing rotate, so we
  use ω_journal + ω_bearing − 2γ̇ in the fixed frame.
* *Transition (eq. 23).* As printed it is infinite at e = c and undefined beyond. We cap the film force at
  ε_lim = 1 − e0/c = {1 - a['e0_m']['value'] / j['journal_radius_m'] * 0 - a['e0_m']['value'] / (j['bearing_radius_m'] - j['journal_radius_m']):.3f}, which keeps it continuous
  and bounded. The dry contact, named in the lubricated scenes too, takes over past e = c.
* *"Pure squeeze film"* (text) against the printed wedge term (eq. 22): we keep both the squeeze and the wedge term.

Hertz stiffness of eq. (9): K = {scenes[(variants[0], 'dry_1')].attrs['hertz_stiffness']:.3g} N/m^1.5. The
ideal joint forces reach {float(ideal.ideal_joint_force_A.max()):.3g} N at A and {float(ideal.ideal_joint_force_B.max()):.3g} N at B
(decoded inertias): at such forces the Hertz penetration exceeds the 0.05 mm clearance (section 4).
"""
)

# %% [markdown]
# ## 2. Figs. 5–10 regenerated

# %%
for v in variants:
    fig, axes = plt.subplots(2, 3, figsize=(15, 7), sharex=True, constrained_layout=True)
    for col, (jt, dry, lub) in enumerate((("joint 1", "dry_1", "lubricated_1"), ("joint 2", "dry_2", "lubricated_2"), ("both joints", "dry_both", "lubricated_both"))):
        for row, (var, unit) in enumerate((("rocker_acceleration", "rad/s²"), ("crank_torque", "N·m"))):
            ax = axes[row, col]
            ideal_s = scenes[(v, "ideal")]
            x = ideal_s.crank_angle.values - ideal_s.crank_angle.values[0]
            ax.plot(x, scenes[(v, dry)][var], "C1", lw=0.7, label="dry clearance")
            ax.plot(x, scenes[(v, lub)][var], "C2", lw=1.0, label="lubricated")
            ax.plot(x, ideal_s[var], "k--", lw=1.0, label="ideal")
            ax.set_title(f"{v}: {var.replace('_', ' ')}, {jt}")
            ax.set_ylabel(f"{var.replace('_', ' ')} ({unit})")
            ax.grid(alpha=0.3)
        axes[1, col].set_xlabel("crank angle over two steady cycles (deg)")
    axes[0, 0].legend(fontsize=8)
    plt.show()

# %% [markdown]
# ## 3. Settling, drift and cost per scene

# %%
rows = []
for (v, s), ds in scenes.items():
    if s == "ideal":
        continue
    ch = ds.cycle_change.values
    rows.append((v, s, ds.attrs["integrator"], int(ds.attrs["steps"]), f"{ch[0]:.2f} → {ch[-1]:.3f}", float(ds.constraint_drift.max()),
                 int(ds.attrs["evaluations_contact"]), int(ds.attrs["evaluations_friction"]), int(ds.attrs["evaluations_lubrication"])))
table(
    pd.DataFrame(rows, columns=["variant", "scene", "integrator", "steps", "cycle-to-cycle change (first → last)", "max drift |Φ| (m)",
                                "contact evaluations", "friction evaluations", "lubrication evaluations"]),
    {"max drift |Φ| (m)": "{:.1e}"},
)
md(
    f"The first {section['numerics']['settle_cycles']} cycles are discarded. The cycle-to-cycle change of the rocker "
    "acceleration falls from the start-up transient to the level of the persistent impact-to-impact variation of the dry "
    "scenes, which never becomes exactly periodic. The two recorded cycles therefore show that variation, and the claims "
    "are judged on each cycle separately. The evaluation counters show that an effect a scene does not name is never "
    "evaluated: the lubrication count is zero in every dry scene, and friction is zero in every lubricated one."
)

# %% [markdown]
# ## 4. Joint forces and penetration against the clearance

# %%
rows = []
c = section["joints"]["bearing_radius_m"] - section["joints"]["journal_radius_m"]
for (v, s), ds in scenes.items():
    if s == "ideal":
        rows.append((v, s, np.nan, np.nan, float(ds.ideal_joint_force_A.max()), float(ds.ideal_joint_force_B.max())))
        continue
    for jn in (1, 2):
        pen = ds.penetration.sel(joint=jn)
        if np.isfinite(pen).any():
            rows.append((v, f"{s} (joint {jn})", float(pen.max()) / c, float(ds.eccentricity.sel(joint=jn).max()) / c,
                         float(ds.contact_force.sel(joint=jn).max()), float(np.abs(ds.film_radial_force.sel(joint=jn)).max())))
table(
    pd.DataFrame(rows, columns=["variant", "scene", "max penetration / c", "max eccentricity / c", "max dry contact force or joint-A force (N)",
                                "max film force or joint-B force (N)"]),
    {"max penetration / c": "{:.2f}", "max eccentricity / c": "{:.2f}", "max dry contact force or joint-A force (N)": "{:.3g}",
     "max film force or joint-B force (N)": "{:.3g}"},
)
md(
    "With the decoded inertias the dry penetration exceeds the 0.05 mm clearance itself, so the Hertz law is well outside "
    "its range: the decoded parameter set is not physically consistent. The slender-rod variant keeps the penetration "
    "below the clearance, and its lubricated joints never touch (eccentricity below c)."
)

# %% [markdown]
# ## 5. Accuracy vs time (work-precision)

# %%
fig, axes = plt.subplots(1, len(wp.scene), figsize=(13, 4.5), constrained_layout=True)
for ax, scene in zip(np.atleast_1d(axes), wp.scene.values):
    for method in np.unique(wp.method.values):
        sel = [i for i, m in enumerate(wp.method.values) if m == method]
        err = wp.error.sel(scene=scene).values[sel]
        t = np.array([timings["runs"].get(f"{scene}/{wp.setting.values[i]}", np.nan) for i in sel])
        ok = np.isfinite(err)
        ax.loglog(t[ok], err[ok], "o-", label=method)
        for ti, ei, lab in zip(t[ok], err[ok], wp.setting.values[sel][ok]):
            ax.annotate(lab.split()[1], (ti, ei), fontsize=6)
    pipeline = section["integrators"]["stiff" if "lubricated" in scene else "explicit"]
    label = f"{pipeline['method']} rtol={pipeline['rtol']:.0e}"
    if label in list(wp.setting.values):
        i = list(wp.setting.values).index(label)
        ax.plot(timings["runs"][f"{scene}/{label}"], float(wp.error.sel(scene=scene).values[i]), "k*", ms=14, label="pipeline setting")
    ax.set_title(f"{scene} ({wp.attrs['variant']}, {wp.attrs['horizon_cycles']} cycle)")
    ax.set_xlabel(f"wall time (s; {timings['method']})")
    ax.set_ylabel("relative error of the RMS deviation from ideal")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
plt.show()
lines = []
for scene in wp.scene.values:
    e = wp.error.sel(scene=scene)
    best = {}
    for i, lab in enumerate(wp.setting.values):
        if np.isfinite(e.values[i]):
            t_i = timings["runs"][f"{scene}/{lab}"]
            m = lab.split()[0]
            best.setdefault(m, []).append((t_i, float(e.values[i]), lab))
    parts = [f"{m}: {min(v, key=lambda x: x[1])[1]:.1e} at best ({min(v, key=lambda x: x[1])[2]}, {min(v, key=lambda x: x[1])[0]:.2f} s)" for m, v in best.items()]
    pw = wp.pointwise_error.sel(scene=scene)
    lines.append(f"* **{scene}**: " + "; ".join(parts) + f". Pointwise error {np.nanmin(pw):.1e}–{np.nanmax(pw):.1e}.")
md(
    f"Reference: {wp.attrs['reference']}. The pipeline settings are {wp.attrs['pipeline_settings']}.\n\n" + "\n".join(lines) + "\n\n"
    "The error shown is that of the RMS deviation from the ideal curve, the measure the claims use. The pointwise error "
    "of the rocker acceleration stays large for every setting in the dry scene: once contacts start, the impact sequence "
    "is sensitive to the smallest difference. That is why the claims are judged per cycle, on RMS and peak, at two "
    "tolerances. In the lubricated scene RK4 would need steps below 1e-8 s, because the film damping makes the "
    "problem stiff, so it is not run there."
)

# %% [markdown]
# ## Provenance

# %%
md("\n".join(f"* **{k}**: `{claims.attrs[k]}`" for k in ("paper_id", "source", "linkwork_version", "git_commit", "config_sha256") if k in claims.attrs))
