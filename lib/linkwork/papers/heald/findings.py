"""The heald paper's comparison and findings: each claim per chain model at the assumed parameters, and the
ranges of each swept parameter over which it holds."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import pandas as pd
import xarray as xr

from ...pipeline.compare import (
    acceptance, classify, compare_datasets, counts_dataset, findings_attrs, nominal_rows, tolerance_of, where_true,
)
from ...units import RAD_S_PER_RPM
from .adapter import amplitude, omega_grid, parameters
from .dynamics import clearance_difference_for_ratio, flip_point
from .model import MODEL_INPUTS

#: Model A is the physical linkage (defensible); model B is the chain of the form of the paper's eq. (2).
DEFENSIBLE, PAPER_MODEL = "A", "B"
CLAIMS = ("force_E_many_times_F", "forces_grow_with_frequency", "limit_41_89")
SWEEPS = ("reaction_ratio", "clearance", "heald_mass", "warp_stiffness")
#: Claims judged on the joint forces E and F (not on the resonances).
FORCE_CLAIMS = ("force_E_many_times_F", "forces_grow_with_frequency")
#: Largest relative change of the joint forces along a sweep that counts as none (round-off of the solve).
INDEPENDENT = 1e-8
INDEPENDENT_TEXT = "independent (the joint forces do not move along this sweep)"
#: Relative width to which a verdict's flip point is located.
FLIP_RTOL = 1e-3
#: Points scanned between an assumed value and a range end that does not flip the verdict (an interval claim).
SCAN = 9
#: Sweeps that move one assumed input alone (the reaction ratio moves reaction_E with reaction_F at its assumed value);
#: the clearance sweep moves both clearances together and has no single input.
SWEEP_INPUT = {"reaction_ratio": "reaction_E", "heald_mass": "M_P", "warp_stiffness": "k_O"}
#: What the findings carry over from the chain study on eq. (2)'s massless-node condition.
EQ2_NODE_MASS = (
    "eq2_relative_difference", "eq2_node_mass_difference", "eq2_node_mass_difference_at", "eq2_node_mass",
    "eq2_node_mass_antiresonance",
)
#: What the findings carry over from the chain study for the statements: the claims' measures at the assumed values and
#: model A's reactions, assumed and self-consistent.
CHAIN_FACTS = (
    "ratio_EF_min", "growth_fraction", "first_resonance", "reaction_assumed", "reaction_kinetostatic",
    "reaction_self_consistent_A", "ratio_EF_min_self_consistent_A", "eq2_denominator_frequencies",
)

#: Each claim's short name in the notes' prose.
CLAIM_SHORT = {
    "force_E_many_times_F": "E many times F",
    "forces_grow_with_frequency": "forces grow",
    "limit_41_89": "the speed limit",
}


def loom_band(chain: xr.Dataset, band_rpm) -> xr.Dataset:
    """The growth claim read over the loom speeds the paper names (``band_rpm``: low, high, min^-1) beside our whole
    grid, per model (elastic joints, assumed values), and the shaft frequency (rad/s) of the smallest joint force
    over the grid (where |Q_E| passes through its minimum)."""
    w = chain.omega.values
    rpm = w / RAD_S_PER_RPM
    inside = (rpm >= band_rpm[0]) & (rpm <= band_rpm[1])
    growth, lowest = [], []
    for m in chain.model.values:
        q_e = chain.Q_E.sel(model=m, joints="elastic").values
        q_f = chain.Q_F.sel(model=m, joints="elastic").values
        growth.append(float(np.mean((np.diff(q_e[inside]) > 0) & (np.diff(q_f[inside]) > 0))))
        lowest.append(float(w[np.argmin(q_e)]))
    return xr.Dataset(
        {
            "growth_fraction_loom_band": ("model", growth, {
                "units": "1", "long_name": "fraction of the loom speeds where |Q_E| and |Q_F| both grow (elastic)"
            }),
            "loom_band": ("band_end", np.asarray(band_rpm, dtype=float), {
                "units": "min-1", "long_name": "the loom speeds the paper names"
            }),
            "smallest_joint_force_at": ("model", lowest, {
                "units": "rad s-1", "long_name": "shaft frequency of the smallest |Q_E| over the grid (elastic joints)"
            }),
        },
        coords={
            "model": chain.model.values,
            "band_end": ("band_end", ["low", "high"], {"units": "1", "long_name": "end of the loom speeds"}),
        },
    )


def bounded_text(x: np.ndarray, ok: np.ndarray, boundary) -> str:
    """Like ``where_true``, but each change between two grid cells is placed at ``boundary(i)``, the located
    value between cells i and i + 1 (the bisection's flip point), not at a grid cell."""
    if ok.all() or not ok.any():
        return where_true(x, ok, ".4g")
    parts, i, n = [], 0, ok.size
    while i < n:
        if not ok[i]:
            i += 1
            continue
        j = i
        while j + 1 < n and ok[j + 1]:
            j += 1
        left = x[0] if i == 0 else boundary(i - 1)
        right = x[-1] if j == n - 1 else boundary(j)
        parts.append(f"{left:.4g}–{right:.4g}")
        i = j + 1
    return ", ".join(parts)


def support(
    chain: xr.Dataset, many_times: float, limit: float, limit_tolerance: float, boundary=None
) -> dict[str, np.ndarray]:
    """Per model, claim and sweep: where along the sweep the claim holds (text; '' where not swept for that claim).
    ``boundary(model, claim, sweep, a, b)``, if given, locates a change of the claim between the sweep values a
    and b (else the text names grid cells)."""
    models = [str(m) for m in chain.model.values]
    text = np.full((len(models), len(CLAIMS), len(SWEEPS)), "", dtype=object)
    for i, m in enumerate(models):
        s = chain.sel(model=m)
        tests = {
            ("force_E_many_times_F", "reaction_ratio"): s.ratio_EF_min_vs_reaction_ratio >= many_times,
            ("force_E_many_times_F", "clearance"): s.ratio_EF_min_vs_clearance >= many_times,
            ("forces_grow_with_frequency", "heald_mass"): s.growth_fraction_vs_heald_mass >= 1.0,
            ("forces_grow_with_frequency", "warp_stiffness"): s.growth_fraction_vs_warp_stiffness >= 1.0,
            ("limit_41_89", "heald_mass"): np.abs(s.first_resonance_vs_heald_mass - limit) <= limit_tolerance,
            ("limit_41_89", "warp_stiffness"): np.abs(s.first_resonance_vs_warp_stiffness - limit) <= limit_tolerance,
        }
        for (claim, sweep), ok in tests.items():
            if claim in FORCE_CLAIMS and float(s[f"joint_force_change_vs_{sweep}"]) <= INDEPENDENT:
                text[i, CLAIMS.index(claim), SWEEPS.index(sweep)] = INDEPENDENT_TEXT
            elif boundary is not None and sweep in SWEEP_INPUT:
                x = chain[sweep].values
                text[i, CLAIMS.index(claim), SWEEPS.index(sweep)] = bounded_text(
                    x, ok.values, lambda k, m=m, c=claim, w=sweep, x=x: boundary(m, c, w, x[k], x[k + 1])
                )
            else:
                text[i, CLAIMS.index(claim), SWEEPS.index(sweep)] = where_true(chain[sweep].values, ok.values)
    return {"models": models, "text": text}


def numerical_errors(chain: xr.Dataset, accuracy: xr.Dataset) -> dict[str, tuple[float, str]]:
    """Our numerical error bar of each claim's measure (the same for both models, relative ones scaled per model)."""
    pipeline = float(accuracy.wp_error.values[np.flatnonzero(accuracy.wp_pipeline.values)[0]])
    out = {}
    for m in chain.model.values:
        s = chain.sel(model=m)
        out[str(m)] = {
            "force_E_many_times_F": (
                pipeline * float(s.ratio_EF_min),
                "extremes on the frequency grid: the accuracy study's error at the pipeline's density",
            ),
            "forces_grow_with_frequency": (
                float(s.growth_fraction_refinement),
                "change when the frequency grid is halved",
            ),
            "limit_41_89": (1e-9 * float(s.first_resonance), "eigenvalues of the condensed chain (float rounding)"),
        }
    return out


def measure_function(claim: str, model: str, cfg: Mapping[str, Any]):
    """The claim's measure as a function of a parameter dict (the cheapest route to it)."""
    from .dynamics import joint_forces
    from .studies import growth_fraction, lowest_resonance

    w, amp = omega_grid(cfg["speeds"]), amplitude(cfg)
    if claim == "force_E_many_times_F":
        def ratio(p):
            _, q_e, q_f, _ = joint_forces(model, p, "elastic", w, amp)
            return float(np.min(np.abs(q_e) / np.abs(q_f)))
        return ratio
    if claim == "forces_grow_with_frequency":
        return lambda p: growth_fraction(model, p, w, amp)
    return lambda p: lowest_resonance(model, p)


def moved(cfg: Mapping[str, Any], name: str, value: float) -> dict[str, float]:
    """The parameter dict with one labelled parameter set to ``value`` (config units)."""
    section = {**cfg, "parameters": {**cfg["parameters"], name: {**cfg["parameters"][name], "value": value}}}
    return parameters(section)


def sweep_boundary(cfg: Mapping[str, Any], published: Mapping[str, Any], flips: xr.Dataset):
    """A function locating where a claim changes along a one-input sweep between two sweep values: the flip
    point of the flip table if one lies there (the same bisection), else a bisection of its own."""
    pub = {q["id"]: q for q in published["quantities"]}

    def scale(sweep):
        return 1.0 / float(cfg["parameters"]["reaction_F"]["value"]) if sweep == "reaction_ratio" else 1.0

    def boundary(model, claim, sweep, a, b):
        name, k = SWEEP_INPUT[sweep], scale(sweep)
        lo, hi = min(a, b), max(a, b)
        for j in range(flips.sizes["flip"]):
            if (str(flips.flip_model.values[j]), str(flips.flip_claim.values[j]), str(flips.flip_input.values[j])) == (
                model, claim, name,
            ):
                v = float(flips.flip_value.values[j]) * k
                if lo <= v <= hi:
                    return v
        q = pub[claim]
        region = acceptance(float(q["value"]), tolerance_of(q), q.get("relation", "eq"))
        f = measure_function(claim, model, cfg)
        return flip_point(lambda x: bool(region[0] <= f(moved(cfg, name, x / k)) <= region[1]), a, b, FLIP_RTOL)

    return boundary


def thresholds(cfg: Mapping[str, Any], published: Mapping[str, Any], table: pd.DataFrame) -> xr.Dataset:
    """For every verdict that an input decides alone: the value of that input (the others at their assumed
    values) at which the verdict flips, located by bisection between its assumed value and the end of its range
    that flips it.  In the nominal scenario (the drive at the shaft frequency, as ``cfg`` has it) only: the
    bisections move one input of the nominal configuration."""
    pub = {q["id"]: q for q in published["quantities"]}
    rows = []
    table = nominal_rows(table)
    for _, row in table[table.verdict == "decided by an unprinted input"].iterrows():
        names = [] if str(row.decided_by).startswith("jointly") else [n.strip() for n in str(row.decided_by).split(",")]
        region = acceptance(float(row.published), float(row.tolerance), row.relation)
        f = measure_function(row.id, row.model, cfg)
        for name in names:
            nominal = float(cfg["parameters"][name]["value"])
            low, high = (float(x) for x in cfg["parameters"][name]["range"])
            base = region[0] <= float(row.reproduced) <= region[1]

            def holds(x, name=name):
                v = f(moved(cfg, name, x))
                return bool(region[0] <= v <= region[1])

            for end in (low, high):
                if holds(end) != base:
                    brackets = [(nominal, end)]
                elif row.relation != "eq":  # a one-sided claim on a monotone measure: this end does not flip it
                    brackets = []
                else:  # an interval claim can flip and flip back inside the range: scan for the changes
                    grid = (
                        np.geomspace(nominal, end, SCAN) if nominal > 0 and end > 0 else np.linspace(nominal, end, SCAN)
                    )
                    state = [holds(x) for x in grid]
                    brackets = [(grid[i], grid[i + 1]) for i in range(SCAN - 1) if state[i] != state[i + 1]]
                for a, b in brackets:
                    value = flip_point(holds, a, b, FLIP_RTOL)
                    rows.append(
                        (
                            row.model, row.id, name, nominal, end, value, f(moved(cfg, name, value)),
                            "holds" if base else "fails",
                        )
                    )
    cols = list(zip(*rows, strict=True)) if rows else [[] for _ in range(8)]
    dim = "flip"
    ds = xr.Dataset(
        {
            "flip_model": (dim, np.array(cols[0], dtype=object), {"units": "1", "long_name": "chain model"}),
            "flip_claim": (dim, np.array(cols[1], dtype=object), {"units": "1", "long_name": "published claim"}),
            "flip_input": (
                dim, np.array(cols[2], dtype=object), {"units": "1", "long_name": "the assumed input moved alone"},
            ),
            "flip_nominal": (
                dim, np.array(cols[3], dtype=float),
                {"units": "config units of the input", "long_name": "its assumed value"},
            ),
            "flip_end": (
                dim, np.array(cols[4], dtype=float),
                {"units": "config units of the input", "long_name": "the end of its range on the flipping side"},
            ),
            "flip_value": (
                dim,
                np.array(cols[5], dtype=float),
                {
                    "units": "config units of the input",
                    "long_name": f"value at which the verdict flips (bisection to a relative {FLIP_RTOL:g})",
                },
            ),
            "flip_measure": (
                dim, np.array(cols[6], dtype=float),
                {"units": "the claim's unit", "long_name": "the claim's measure at the flip value"},
            ),
            "flip_nominal_state": (
                dim, np.array(cols[7], dtype=object),
                {"units": "1", "long_name": "whether the claim holds at the assumed value"},
            ),
        },
        coords={dim: (dim, np.arange(len(rows)), {"units": "1", "long_name": "flip point"})},
    )
    ds.attrs["flip_rtol"] = FLIP_RTOL
    # the named thresholds: the reaction ratio and, through the kinetostatics, the clearance difference
    many = float(pub["force_E_many_times_F"]["value"])
    p = parameters(cfg)
    if "A" in cfg["models"]:
        at = [r[5] for r in rows if r[0] == "A" and r[1] == "force_E_many_times_F" and r[2] == "reaction_E"]
        ds["threshold_reaction_ratio_A"] = (
            (),
            float(at[0]) / p["reaction_F"] if at else float("nan"),
            {
                "units": "1",
                "long_name": (
                    f"model A: |R_E|/|R_F| (|R_F| assumed) at which min |Q_E|/|Q_F| = {many:g} (the flip point of"
                    " reaction_E)"
                ),
                "nan_meaning": "reaction_E does not decide the verdict alone",
            },
        )
        ds["threshold_clearance_difference_A"] = (
            (),
            clearance_difference_for_ratio(p, many, "A"),
            {
                "units": "m",
                "long_name": (
                    "model A: Delta_F - Delta_E (Delta_E assumed) at which the self-consistent reactions split as"
                    f" {many:g} : 1"
                ),
            },
        )
    return ds


def cam_verdicts(published: Mapping[str, Any], chain: xr.Dataset, accuracy: xr.Dataset) -> xr.Dataset:
    """Verdicts at the assumed parameters with the harmonic drive and with the cam drive (nominal rise fraction;
    and over the rise fraction's range, the other inputs at their assumed values)."""
    errors = numerical_errors(chain, accuracy)
    sine = compare_datasets(published, [chain], errors=errors)
    names = {
        "ratio_EF_min": "ratio_EF_min_cam",
        "growth_fraction": "growth_fraction_cam",
        "first_resonance": "first_resonance_cam",
    }
    cam = xr.Dataset({k: chain[v].sel(rise="nominal", drop=True) for k, v in names.items()})
    cam_table = compare_datasets(published, [cam], errors=errors)
    pub = {q["id"]: q for q in published["quantities"]}
    over = []
    for _, row in cam_table.iterrows():
        var = names[pub[row.id]["measure"]["variable"]]
        values = chain[var].sel(model=row.model).values
        over.append(
            classify(
                float(row.published), float(row.tolerance), row.relation, float(values[0]), float(row.numerical_error),
                float(values.min()), float(values.max()),
            )
        )
    shape = (len(chain.model), len(CLAIMS))
    limit_row = sine[sine.id == "limit_41_89"].set_index("model")
    by_h = np.array(
        [
            [
                classify(
                    float(limit_row.published[str(m)]), float(limit_row.tolerance[str(m)]), limit_row.relation[str(m)],
                    float(v), float(limit_row.numerical_error[str(m)]), float(v), float(v),
                )
                for v in chain.cam_harmonic_speed.sel(model=m).values
            ]
            for m in chain.model.values
        ],
        dtype=object,
    )

    def grid(col):
        return np.array(list(col), dtype=object).reshape(shape)

    damp = []
    for c in chain.joint_damping.values:
        at = xr.Dataset({k: chain[f"{v}_by_joint_damping"].sel(joint_damping=c, drop=True) for k, v in names.items()})
        damp.append(grid(compare_datasets(published, [at], errors=errors).verdict))

    return xr.Dataset(
        {
            "verdict_sine_nominal": (
                ("model", "claim"), grid(sine.verdict),
                {"units": "1", "long_name": "verdict at the assumed parameters, harmonic drive"},
            ),
            "verdict_cam_nominal": (
                ("model", "claim"), grid(cam_table.verdict),
                {"units": "1", "long_name": "verdict at the assumed parameters, cam drive"},
            ),
            "verdict_cam_over_rise": (
                ("model", "claim"),
                grid(over),
                {
                    "units": "1",
                    "long_name": "verdict with the cam drive over the rise fraction's range (other inputs assumed)",
                },
            ),
            "value_cam_nominal": (
                ("model", "claim"), np.array(list(cam_table.reproduced), dtype=float).reshape(shape),
                {"units": "the claim's unit", "long_name": "the claim's measure, cam drive"},
            ),
            "verdict_limit_by_harmonic": (
                ("model", "harmonic"),
                by_h,
                {
                    "units": "1",
                    "long_name": (
                        "verdict on the speed limit at the assumed parameters if harmonic h were the highest one"
                        " counted (cam drive)"
                    ),
                },
            ),
            "verdict_cam_by_joint_damping": (
                ("model", "claim", "joint_damping"),
                np.stack(damp, axis=-1),
                {
                    "units": "1",
                    "long_name": (
                        "verdict with the cam drive at the ends of the joint damping's range (other inputs assumed)"
                    ),
                },
            ),
            "largest_dip_cam_by_joint_damping": chain.largest_dip_cam_by_joint_damping,
            "joint_branch_damping_ratio": chain.joint_branch_damping_ratio,
            "cam_changes_a_verdict": (
                (), int((sine.verdict.values != cam_table.verdict.values).any()),
                {"units": "1", "long_name": "1 if the cam's harmonics change a verdict at the assumed parameters"},
            ),
        }
    )


def drive_verdicts(published: Mapping[str, Any], chain: xr.Dataset, accuracy: xr.Dataset) -> xr.Dataset:
    """Verdicts with the drive at each drive-frequency choice, the other inputs at their assumed values (the
    uncertainty study spans the ranges per scenario)."""
    errors = numerical_errors(chain, accuracy)
    drives = [str(d) for d in chain.drive.values]
    verdict = np.empty((chain.sizes["model"], len(CLAIMS), len(drives)), dtype=object)
    value = np.empty(verdict.shape)
    for j, d in enumerate(drives):
        at = xr.Dataset(
            {
                k: chain[f"{k}_by_drive"].sel(drive=d, drop=True)
                for k in ("ratio_EF_min", "growth_fraction", "first_resonance")
            }
        )
        t = compare_datasets(published, [at], errors=errors)
        verdict[:, :, j] = np.array(list(t.verdict), dtype=object).reshape(verdict.shape[:2])
        value[:, :, j] = np.array(list(t.reproduced), dtype=float).reshape(verdict.shape[:2])
    dims = ("model", "claim", "drive")
    return xr.Dataset(
        {
            "verdict_by_drive": (
                dims,
                verdict,
                {
                    "units": "1",
                    "long_name": "verdict per drive-frequency scenario, the other inputs at their assumed values",
                },
            ),
            "value_by_drive": (
                dims, value,
                {"units": "the claim's unit", "long_name": "the claim's measure per drive-frequency scenario"},
            ),
            "drive_ratio": ("drive", chain.drive_ratio.values, dict(chain.drive_ratio.attrs)),
        },
        coords={
            "drive": ("drive", np.array(drives, dtype=object), {"units": "1", "long_name": "drive-frequency scenario"})
        },
    )


def compare(
    cfg: Mapping[str, Any],
    published: Mapping[str, Any],
    chain: xr.Dataset,
    accuracy: xr.Dataset,
    uncertainty: xr.Dataset,
) -> tuple[pd.DataFrame, xr.Dataset]:
    """Comparison table per model, the support ranges of every claim, the flip points of the verdicts an input
    decides, and the verdicts with a cam's harmonics."""
    table = compare_datasets(published, [chain], errors=numerical_errors(chain, accuracy), uncertainty=uncertainty)
    pub = {q["id"]: q for q in published["quantities"]}
    limit = float(pub["limit_41_89"]["value"])
    many_times = float(pub["force_E_many_times_F"]["value"])
    flips = thresholds(cfg, published, table)
    sup = support(chain, many_times, limit, tolerance_of(pub["limit_41_89"]), sweep_boundary(cfg, published, flips))
    findings = xr.Dataset(
        {
            "holds_for": (
                ("model", "claim", "sweep"), sup["text"],
                {"units": "1", "long_name": "sub-ranges of the swept parameter over which the claim holds"},
            ),
            "limit_rad_s": ((), limit, {"units": "rad s-1", "long_name": "the paper's speed limit"}),
            "limit_rpm": (
                (), limit / RAD_S_PER_RPM, {"units": "min-1", "long_name": "the paper's speed limit as a shaft speed"},
            ),
            "limit_band": (
                (), tolerance_of(pub["limit_41_89"]),
                {"units": "rad s-1", "long_name": "half-width of the band around the limit (our reading)"},
            ),
            "many_times": ((), many_times, {"units": "1", "long_name": "ratio read as 'many times' (our reading)"}),
        },
        coords={
            "model": ("model", np.array(sup["models"], dtype=object), {"units": "1", "long_name": "chain model"}),
            "claim": ("claim", np.array(CLAIMS, dtype=object), {"units": "1", "long_name": "published claim"}),
            "sweep": ("sweep", np.array(SWEEPS, dtype=object), {"units": "1", "long_name": "swept parameter"}),
        },
    )
    findings = findings.merge(chain[list(EQ2_NODE_MASS) + [v for v in CHAIN_FACTS if v in chain]])
    findings = findings.merge(loom_band(chain, cfg["loom_band_rpm"]))
    findings = findings.merge(counts_dataset(table))
    findings = (
        findings.merge(flips)
        .merge(cam_verdicts(published, chain, accuracy))
        .merge(drive_verdicts(published, chain, accuracy))
    )
    findings.attrs.update(
        findings_attrs("Heald paper: comparison findings", DEFENSIBLE, PAPER_MODEL)
    )
    # the parameters each model reads (for the report's tables, which leave the others out)
    findings.attrs.update({f"inputs_of_model_{m}": ",".join(names) for m, names in MODEL_INPUTS.items()})
    findings.attrs["notes"] = notes(chain, findings)
    return table, findings


def notes(chain: xr.Dataset, findings: xr.Dataset) -> str:
    """What the headline counts do not show: model A's E/F verdict with the kinetostatic reactions, the verdicts a
    dwell cam's harmonics change and whether damped joints undo that (plain prose, for the report's summary)."""
    out = []
    if "threshold_reaction_ratio_A" in findings and "ratio_EF_min_self_consistent_A" in chain:
        out.append(
            "Model A's E/F claim holds only for an assumed split of the reactions of at least"
            f" {float(findings.threshold_reaction_ratio_A):.4g} : 1; with the mechanism's own (self-consistent)"
            f" reactions the E/F ratio is {float(chain.ratio_EF_min_self_consistent_A):.3f} and the claim fails."
        )
    if "verdict_cam_nominal" in findings:
        pairs = [
            (m, c)
            for m in findings.model.values
            for c in findings.claim.values
            if findings.verdict_sine_nominal.sel(model=m, claim=c).item()
            != findings.verdict_cam_nominal.sel(model=m, claim=c).item()
        ]
        changed = [
            f"model {m}, {CLAIM_SHORT[str(c)]}: {findings.verdict_sine_nominal.sel(model=m, claim=c).item()} →"
            f" {findings.verdict_cam_nominal.sel(model=m, claim=c).item()}"
            for m, c in pairs
        ]
        if changed:
            out.append(
                "With a dwell cam's harmonics instead of the harmonic drive (all inputs at their assumed values) the"
                " verdict changes for "
                + "; ".join(changed)
                + "."
            )
            out.extend(damped_cam_text(findings, m, c) for m, c in pairs)
    return " ".join(out)


def damped_cam_text(findings: xr.Dataset, model: str, claim: str) -> str:
    """The cam's verdict on one claim at the ends of the joints' damping range, with the largest dip of the forces."""
    d = findings.joint_damping.values
    v = [findings.verdict_cam_by_joint_damping.sel(model=model, claim=claim, joint_damping=x).item() for x in d]
    dip = [float(findings.largest_dip_cam_by_joint_damping.sel(model=model, joint_damping=x)) for x in d]
    zeta = float(findings.joint_branch_damping_ratio.sel(model=model, joint_damping=d[-1]))
    return (
        f"With the joints damped at the top of their assumed range ({d[-1]:g} N s/m, a damping ratio of {zeta:.3f}) the"
        f" cam's verdict on model {model}, {CLAIM_SHORT[str(claim)]}, is {v[-1]}"
        f" {'still' if v[-1] == v[0] else 'instead'}, and the largest fall of a peak joint force between neighbouring"
        f" speeds shrinks from {dip[0]:.0%} to {dip[-1]:.2%}."
    )


