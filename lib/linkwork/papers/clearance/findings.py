"""The clearance paper's comparison: each claim per parameter variant (the paper prints no number)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import pandas as pd
import xarray as xr

from ...pipeline.compare import compare_datasets, counts_dataset, findings_attrs
from ...engines.multibody.validity import elastic_law_validity, penetration_limit
from .words import SCENE_WORDS, VARIANT_WORDS, in_words, ripple_bounds, sample_in_words


#: The slender-rod inertias are the defensible variant: with the decoded (printed) ones the Hertz
#: penetration exceeds the clearance itself (``answer`` states by how much).
DEFENSIBLE, PAPER_MODEL = "slender", "decoded"
DRY_SCENES = ("dry_1", "dry_2", "dry_both")
LUBRICATED_SCENES = ("lubricated_1", "lubricated_2", "lubricated_both")


def numerical_errors(claims: xr.Dataset) -> dict[str, dict[str, dict[int, tuple[float, str]]]]:
    """Per variant, claim and start (the comparison's scenarios, in the starts' order): 1 where a margin decides the
    claim from that start (its difference within the confidence interval or the numerical error of an ordering it is
    made of), else 0."""
    source = (
        f"{claims.attrs['confidence']:.0%} interval over the judged cycles (states that are not periodic) and the"
        " numerical error (the same state at the check tolerances,"
        f" {claims.attrs.get('tight_settings', 'see the claims')}, and the state the start reaches at the first of"
        " them, plus the convergence and peak-sampling terms)"
    )
    return {
        str(v): {
            str(c): {
                k: (float(claims.outcome_by_start.sel(variant=v, claim=c).values[k] == -1), source)
                for k in range(claims.sizes["start"])
            }
            for c in claims.claim.values
        }
        for v in claims.variant.values
    }


def compare(
    cfg: Mapping[str, Any],
    published: Mapping[str, Any],
    claims: xr.Dataset,
    uncertainty: xr.Dataset | None = None,
    laws: Sequence[xr.Dataset] = (),
    memory_free: Sequence[xr.Dataset] = (),
) -> tuple[pd.DataFrame, xr.Dataset]:
    """Comparison table per variant and its verdict counts, the physics that interprets them and the verdicts'
    sensitivity to the contact law and its memory (``laws``: ``sensitivity.model_sensitivity`` per variant;
    ``memory_free``: ``sensitivity.memory_free`` per variant)."""
    phys = physics(claims, cfg, uncertainty).merge(claim3_parts(claims))
    law_attrs = {}
    if laws:
        law = law_sensitivity(claims, laws, cfg, phys)
        phys, law_attrs = phys.merge(law), law.attrs
    if memory_free:
        phys = phys.merge(memory_free_claims(claims, memory_free, cfg))
    table = compare_datasets(published, [claims], errors=numerical_errors(claims), uncertainty=uncertainty,
                             causes=memory_causes(claims, phys))
    table = undetermined_ranges(nominal_only(with_reasons(table, claims)), uncertainty)
    findings = counts_dataset(table).merge(phys).merge(failing_orderings(claims))
    findings.attrs.update(law_attrs)
    findings.attrs.update(
        findings_attrs("Clearance paper: comparison findings", DEFENSIBLE, PAPER_MODEL)
    )
    findings.attrs["film_cap_note"] = film_cap_text(findings)
    return table, findings


#: What decides a claim whose starts disagree only through the contact damping's memory.
MEMORY_DECIDES = (
    "the impact velocity the contact damping latched at impact (the starts settle apart only through it: a memory of "
    "the printed contact law, set by the journals' unprinted starting state)"
)


def failing_orderings(claims: xr.Dataset) -> xr.Dataset:
    """Per variant, start and claim: the measures (rms, peak, ripple) of the orderings that decidedly fail, and of those
    left undetermined, each a text joining the distinct measures in the claims' order ('' where none)."""
    def measures(outcome: int, v, st, c) -> str:
        chosen = claims.comparison_outcome.sel(variant=v, start=st).values == outcome
        of_claim = np.asarray(claims.comparison_claim.values).astype(str) == str(c)
        labels = np.asarray(claims.comparison.values).astype(str)[chosen & of_claim]
        return ", ".join(dict.fromkeys(str(label).split()[0] for label in labels))

    dims = ("variant", "start", "claim")
    v_, s_, c_ = (claims[d].values for d in dims)
    return xr.Dataset(
        {
            f"{name}_measures": (
                dims,
                np.array([[[measures(o, v, st, c) for c in c_] for st in s_] for v in v_], dtype=object),
                {"units": "1", "long_name": f"measures of the claim's orderings that {name.replace('_', ' ')}"},
            )
            for name, o in (("fail", 0), ("stay_undetermined", -1))
        },
        coords={d: claims[d] for d in dims},
    )


def memory_causes(claims: xr.Dataset, phys: xr.Dataset) -> dict[str, dict[str, dict[str, str]]]:
    """What the classifier is told per variant: a claim that holds decidedly from one start and fails decidedly from
    another, where swapping the latched impact velocities swaps the dry scenes' states (``memory_explains``), is
    decided by the contact damping's memory, a part of the paper's model, not by the linkage: every scenario's row of
    it is 'decided by the paper's model'.  A claim undetermined from one start and failing from the other is not (no
    start shows it holding).  Needs the law sensitivity's ``memory_explains`` (none: nothing is said)."""
    out: dict[str, dict[str, dict[str, str]]] = {}
    if "memory_explains" not in phys:
        return out
    for v in claims.variant.values:
        if not int(phys.memory_explains.sel(variant=v).sum()):
            continue
        decided = {
            str(c): MEMORY_DECIDES
            for c in claims.claim.values
            if {0, 1} <= set(claims.outcome_by_start.sel(variant=v, claim=c).values.tolist())
        }
        if decided:
            out[str(v)] = {"model_decides": decided}
    return out


#: What decides a verdict in a start the assumed inputs are not propagated in.
NOMINAL_ONLY = "the nominal inputs only (the assumed inputs are propagated from the first start alone)"


#: The input source of a row of a start the assumed inputs are not propagated in.
NOT_PROPAGATED = "none: the assumed inputs are propagated from the first start alone"
#: What decides a decided verdict some of whose samples its margins leave undetermined.
DECIDED_SAMPLES = "the nominal inputs and the decided samples; left undetermined within their margins at"
#: The input source of a row whose samples its margins all leave undetermined.
ALL_UNDETERMINED = "no range: every sample, the nominal one included, is undetermined within its margins"
#: The input source of an undetermined row some of whose samples are decided: their outcomes span no range of the
#: inputs.
PARTLY_UNDETERMINED = "no range: the claim is undetermined, and its margins decide it at"


def nominal_only(table: pd.DataFrame) -> pd.DataFrame:
    """Rows of a start other than the first, where no assumed input was propagated (no input range): a decided verdict
    there holds at the nominal inputs, not 'whatever the assumed inputs'; 'decided by' says so, and the input source
    says that no input was propagated there."""
    out = table.copy()
    first = out.scenario.iloc[0] if len(out) else None
    other = (out.scenario != first) & out.input_low.isna()
    out.loc[other, "input_source"] = NOT_PROPAGATED
    rows = other & out.verdict.isin(["differs", "reproduced"]) & out.decided_by.fillna("").eq("")
    out.loc[rows, "decided_by"] = NOMINAL_ONLY
    return out


def undetermined_ranges(table: pd.DataFrame, uncertainty: xr.Dataset | None) -> pd.DataFrame:
    """Rows of the first start whose samples (the nominal included: ``sample_claim_outcome``) are all undetermined
    within their own margins show no input range: their range cells would hold only the nominal run's outcome on its
    means, which its margins do not decide.  The verdict does not change (such a range is the nominal value alone).  An
    undetermined row some of whose samples are decided shows no range either: the decided few span no range of the
    inputs (the cell says how many).  A decided verdict ('differs', 'reproduced') some of whose samples are undetermined
    holds at the decided ones only: 'decided by' names the others."""
    if uncertainty is None or "sample_claim_outcome" not in uncertainty:
        return table
    out = table.copy()
    first = (
        out.scenario.iloc[0] if len(out) else None
    )  # the start the inputs are propagated in (the others: ``nominal_only``)
    of = np.array([str(x) for x in uncertainty.sample_scenario.values])
    variants, claim_ids = [str(v) for v in uncertainty.variant.values], [str(c) for c in uncertainty.claim.values]
    for i, row in out.iterrows():
        if (
            row.scenario != first
            or row.model not in variants
            or row["id"] not in claim_ids
            or not (of == row.scenario).any()
        ):
            continue
        outcomes = uncertainty.sample_claim_outcome.values[
            of == row.scenario, variants.index(row.model), claim_ids.index(row["id"])
        ]
        if (outcomes == -1).all():
            out.loc[i, ["input_low", "input_high", "input_source"]] = [np.nan, np.nan, ALL_UNDETERMINED]
        elif (outcomes == -1).any() and "undetermined" in str(row.verdict):
            decided = int((outcomes != -1).sum())
            out.loc[i, ["input_low", "input_high", "input_source"]] = [
                np.nan, np.nan, f"{PARTLY_UNDETERMINED} {decided} of {outcomes.size} samples only",
            ]
        elif (
            (outcomes == -1).any()
            and row.verdict in ("differs", "reproduced")
            and not (isinstance(row.decided_by, str) and row.decided_by)
        ):
            left = [sample_in_words(str(x)) for x in uncertainty.sample.values[of == row.scenario][outcomes == -1]]
            out.loc[i, "decided_by"] = f"{DECIDED_SAMPLES}: {', '.join(left)}"
    return out


def with_reasons(table: pd.DataFrame, claims: xr.Dataset) -> pd.DataFrame:
    """The comparison table with 'decided by' filled, where a claim is undetermined, by the margin that leaves
    it so (a scene not settled or not stationary, the statistical margin, the numerical error)."""
    if "claim_decided_by" not in claims:
        return table
    out = table.copy()
    starts = [str(s) for s in claims.start.values] if "claim_decided_by_start" in claims else []
    for i, row in out.iterrows():
        if (
            row.verdict == "undetermined by our numerics"
            and row.model in claims.variant.values
            and row["id"] in claims.claim.values
        ):
            start = str(row.scenario).removeprefix("start ")
            reason = (
                claims.claim_decided_by_start.sel(variant=row.model, claim=row["id"], start=start)
                if start in starts
                else claims.claim_decided_by.sel(variant=row.model, claim=row["id"])
            )  # the row's own start
            out.at[i, "decided_by"] = in_words(reason.item())
    return out


def stray_evaluations(claims: xr.Dataset, scenes: Mapping[str, Any]) -> np.ndarray:
    """Per variant: evaluations of an effect (contact, friction, lubrication) in the runs whose scene does not
    name it (``scenes``: the config's scene -> effects); must be 0."""
    total = np.zeros(claims.sizes["variant"])
    for run in claims.run.values:
        named = scenes.get(str(run), {}).get("effects", [])
        for effect in ("contact", "friction", "lubrication"):
            if effect not in named and f"summary_n_{effect}" in claims:
                total += claims[f"summary_n_{effect}"].sel(run=run).fillna(0.0).values
    return total


def lubricated_friction(claims: xr.Dataset) -> np.ndarray:
    """Per variant and lubricated scene: friction evaluations (nonzero where a journal met its bushing and the
    dry contact's friction acted)."""
    return claims.summary_n_friction.sel(run=list(LUBRICATED_SCENES)).fillna(0.0).values


def e0_dependence(uncertainty: xr.Dataset | None, variants: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per variant: the smallest and largest mean RMS torque deviation of lubricated_2 over the input samples
    (the film cap e0 moves it; NaN without the uncertainty study)."""
    if uncertainty is None or "sample_mean_deviation" not in uncertainty:
        return np.full(len(variants), np.nan), np.full(len(variants), np.nan)
    m = uncertainty.sample_mean_deviation.sel(measure="rms", response="crank_torque", scene="lubricated_2")
    return np.array([float(m.sel(variant=v).min()) for v in variants]), np.array(
        [float(m.sel(variant=v).max()) for v in variants]
    )


def physics(
    claims: xr.Dataset, cfg: Mapping[str, Any] | None = None, uncertainty: xr.Dataset | None = None
) -> xr.Dataset:
    """Per variant: the deepest dry penetration, whether the parameter set is physically consistent, the largest
    crank torque of a dry scene, the largest lubricated eccentricity against the film cap, where friction acted
    in the lubricated scenes, how lubricated_2 moves over the samples (e0), and how often an effect a scene
    does not name was evaluated (must be 0; ``cfg['scenes']`` names them)."""
    dry = claims.summary_max_penetration_ratio.sel(run=list(DRY_SCENES)).max(("run", "joint"))
    ecc = claims.summary_max_eccentricity_ratio.sel(run=list(LUBRICATED_SCENES)).max(("run", "joint"))
    ecc2 = claims.summary_max_eccentricity_ratio.sel(run="lubricated_2").max("joint")
    cap = claims.summary_film_cap.sel(run=list(LUBRICATED_SCENES)).max("run")
    torque = claims.summary_max_abs_torque.sel(run=list(DRY_SCENES)).max("run")
    ideal_torque = claims.summary_max_abs_torque.sel(run="ideal")
    cfg = cfg or {}
    limit = penetration_limit("hertz-sphere", cfg["joints"]["journal_radius_m"], cfg["joints"]["bearing_radius_m"])
    stray = stray_evaluations(claims, cfg.get("scenes", {}))
    lo, hi = e0_dependence(uncertainty, claims.variant.values)
    e0 = cfg.get("assumed", {}).get("e0_m", {})
    e0_high = max(e0.get("range", [np.nan])) if e0 else np.nan
    # the cap at the top of the e0 range: c = e0 / (1 - cap) at the nominal e0
    cap_high = 1.0 - e0_high * (1.0 - cap.values) / e0.get("value", np.nan) if e0 else np.full(cap.shape, np.nan)
    full = (
        claims.summary_beyond_film_cap_fraction.sel(run=list(LUBRICATED_SCENES))
        if "summary_beyond_film_cap_fraction" in claims
        else None
    )
    v = ("variant",)
    return xr.Dataset(
        {
            "dry_penetration_max": (
                v, dry.values, {"units": "1", "long_name": "deepest dry penetration over the radial clearance"},
            ),
            "physically_consistent": (
                v,
                (dry.values < limit).astype(int),
                {
                    "units": "1",
                    "long_name": (
                        f"1 if the dry penetration stays below {limit:.3g} times the clearance (eq. (9)'s sphere law's"
                        " range)"
                    ),
                },
            ),
            "dry_torque_max": (
                v, torque.values, {"units": "N m", "long_name": "largest |crank torque| in a dry scene"},
            ),
            "ideal_torque_max": (
                v, ideal_torque.values, {"units": "N m", "long_name": "largest |crank torque| of the ideal linkage"},
            ),
            "crank_mass": ((), float(claims.attrs["crank_mass_kg"]), {"units": "kg", "long_name": "crank mass"}),
            "lubricated_eccentricity_max": (
                v, ecc.values, {"units": "1", "long_name": "largest eccentricity ratio |e|/c in a lubricated scene"},
            ),
            "lubricated_2_eccentricity_max": (
                v, ecc2.values, {"units": "1", "long_name": "largest eccentricity ratio |e|/c in lubricated_2"},
            ),
            "film_cap": (
                v,
                cap.values,
                {
                    "units": "1",
                    "long_name": "eccentricity ratio at which the film force is capped, 1 - e0/c (nominal e0)",
                },
            ),
            "beyond_film_cap": (
                v, (ecc2.values > cap.values).astype(int),
                {"units": "1", "long_name": "1 if lubricated_2 runs beyond the film cap"},
            ),
            "film_cap_at_e0_high": (
                v, cap_high, {"units": "1", "long_name": "film cap 1 - e0/c at the largest e0 of its range"},
            ),
            "beyond_film_cap_at_e0_high": (
                v,
                (ecc2.values > cap_high).astype(int),
                {
                    "units": "1",
                    "long_name": (
                        "1 if lubricated_2's nominal largest eccentricity ratio exceeds the film cap at the largest e0"
                    ),
                },
            ),
            **(
                {
                    "beyond_film_cap_fraction": (
                        ("variant", "scene"), full.values,
                        {"units": "1", "long_name": "fraction of the recorded time beyond the film cap (nominal e0)"},
                    )
                }
                if full is not None
                else {}
            ),
            "lubricated_2_torque_rms_low": (
                v,
                lo,
                {
                    "units": "N m",
                    "long_name": "smallest mean RMS torque deviation of lubricated_2 over the input samples",
                },
            ),
            "lubricated_2_torque_rms_high": (
                v,
                hi,
                {
                    "units": "N m",
                    "long_name": "largest mean RMS torque deviation of lubricated_2 over the input samples",
                },
            ),
            "lubricated_friction_evaluations": (
                ("variant", "scene"),
                lubricated_friction(claims),
                {
                    "units": "1",
                    "long_name": "friction evaluations in a lubricated scene (dry contact where the film broke down)",
                },
            ),
            "stray_evaluations": (
                v, stray, {"units": "1", "long_name": "evaluations of an effect in a scene that does not name it"},
            ),
        },
        coords={
            "variant": ("variant", claims.variant.values, {"units": "1", "long_name": "parameter variant"}),
            "scene": (
                "scene", np.array(LUBRICATED_SCENES, dtype=object), {"units": "1", "long_name": "lubricated scene"},
            ),
        },
    )


def memory_explains(own: np.ndarray, swap: np.ndarray, share: float = 0.1) -> np.ndarray:
    """Per variant and scene: 1 where the first and last start's measures differ and each state continued with the other
    start's latched velocities lands within ``share`` of that difference from the other start's measure (``own``:
    variant, scene, start; ``swap``: variant, scene, direction [last state with first memory, the reverse])."""
    first, last = own[..., 0], own[..., -1]
    gap = np.abs(first - last)
    to_first = np.abs(swap[..., 0] - first) <= share * gap
    to_last = np.abs(swap[..., 1] - last) <= share * gap
    return ((gap > 0) & to_first & to_last).astype(int)


def law_sensitivity(
    claims: xr.Dataset, laws: Sequence[xr.Dataset], cfg: Mapping[str, Any], phys: xr.Dataset
) -> xr.Dataset:
    """Per variant, start and claim: the outcome under eq. (9)'s sphere law and under the other elastic law, whether
    it survives the change of law, and whether the sphere law stays inside its validity in that variant's dry scenes
    (deepest penetration against its limit); a verdict counts as the paper's where the sphere law is valid or the
    outcome survives the change of law (it does not rest on a law used outside its range).  Per ordering, its
    difference under the other law.  Per dry scene, the claims' measure (RMS rocker acceleration) on each start's
    state continued with the other start's latched impact velocities, beside the two starts' own."""
    from .sensitivity import law_judgement

    j = cfg["joints"]
    sphere = elastic_law_validity("hertz-sphere", j["journal_radius_m"], j["bearing_radius_m"])
    other_law = cfg["sensitivity"]["elastic_law"]
    other = elastic_law_validity(other_law, j["journal_radius_m"], j["bearing_radius_m"])
    by_variant = {str(d.variant.values[0]): d for d in laws}
    variants, starts = [str(v) for v in claims.variant.values], [str(x) for x in claims.start.values]
    ratio, confidence = cfg["claims"]["close_to_ideal_ratio"], cfg["statistics"]["confidence"]
    verdicts = [
        [law_judgement(claims.sel(variant=v), by_variant[v], ratio, confidence, start=k) for k in range(len(starts))]
        for v in variants
    ]
    under = np.array([[vd["outcome"] for vd in row] for row in verdicts])
    diff = np.array([[[r["difference"] for r in vd["rows"]] for vd in row] for row in verdicts])
    nominal = claims.outcome_by_start.values
    limit = sphere.limits["max_penetration_over_clearance"]
    valid = (phys.dry_penetration_max.values <= limit).astype(int)
    survives = (under == nominal).astype(int)
    swapped = [str(x) for x in laws[0].swapped_scene.values]
    swap = np.array(
        [by_variant[v].swap_mean.sel(measure="rms", quantity="rocker_acceleration").values for v in variants]
    )  # variant, scene, direction
    own = np.array(
        [
            [
                claims.mean_deviation.sel(variant=v, scene=n, measure="rms", quantity="rocker_acceleration").values
                for n in swapped
            ]
            for v in variants
        ]
    )
    vsc = ("variant", "start", "claim")
    out = xr.Dataset(
        {
            "law_outcome_sphere": (
                vsc, nominal,
                {"units": "1", "long_name": "claim under eq. (9)'s sphere law: 1 holds, 0 fails, -1 undetermined"},
            ),
            "law_outcome_other": (
                vsc, under,
                {"units": "1", "long_name": f"claim under the {other_law} law: 1 holds, 0 fails, -1 undetermined"},
            ),
            "law_survives": (
                vsc, survives,
                {"units": "1", "long_name": "1 if the claim's outcome is the same under both elastic laws"},
            ),
            "law_difference_other": (
                ("variant", "start", "comparison"), diff,
                {"units": "SI of the quantity", "long_name": f"difference of each ordering under the {other_law} law"},
            ),
            "sphere_law_valid": (
                "variant", valid,
                {"units": "1", "long_name": "1 if the deepest dry penetration stays inside the sphere law's validity"},
            ),
            "verdict_counted": (
                vsc,
                np.maximum(valid[:, None, None], survives),
                {
                    "units": "1",
                    "long_name": (
                        "1 if the verdict counts as the paper's: the sphere law is valid or the outcome survives"
                        " the law"
                    ),
                },
            ),
            "memory_swap_rms": (
                ("variant", "swapped_scene", "direction"),
                swap,
                {
                    "units": "rad s-2",
                    "long_name": (
                        "RMS rocker-acceleration deviation on a start's state continued with the other start's latched"
                        " impact velocities"
                    ),
                    "nan_meaning": "one start only",
                },
            ),
            "memory_own_rms": (
                ("variant", "swapped_scene", "start"), own,
                {"units": "rad s-2", "long_name": "RMS rocker-acceleration deviation on each start's own state"},
            ),
            "memory_explains": (
                ("variant", "swapped_scene"),
                memory_explains(own, swap),
                {
                    "units": "1",
                    "long_name": (
                        "1 if the two starts' measures differ and swapping the latched impact "
                        "velocities swaps them (each within a tenth of their difference)"
                    ),
                },
            ),
        },
        coords={
            "variant": ("variant", np.array(variants, dtype=object), {"units": "1", "long_name": "parameter variant"}),
            "start": (
                "start", np.array(starts, dtype=object), {"units": "1", "long_name": "initial state of the journals"},
            ),
            "claim": ("claim", claims.claim.values, {"units": "1", "long_name": "claim"}),
            "comparison": (
                "comparison", claims.comparison.values, {"units": "1", "long_name": "ordering a claim is made of"},
            ),
            "swapped_scene": (
                "swapped_scene", np.array(swapped, dtype=object), {"units": "1", "long_name": "dry scene"},
            ),
            "direction": (
                "direction", laws[0].direction.values,
                {"units": "1", "long_name": "whose state, whose latched velocities"},
            ),
        },
    )
    out.attrs.update(
        sphere_law_condition=sphere.condition, sphere_law_limit_over_clearance=limit, other_law=other_law,
        other_law_condition=other.condition, other_law_valid=int(other.limits["clearance_in_range"]),
    )
    return out


def memory_free_claims(claims: xr.Dataset, runs: Sequence[xr.Dataset], cfg: Mapping[str, Any]) -> xr.Dataset:
    """The claims under a memory-free contact damping (``runs``: ``sensitivity.memory_free`` per variant), each state
    judged with its own interval and numerical error: per variant, start, fixed impact velocity and claim, the outcome;
    per ordering, its difference; per dry scene, the RMS deviation of each compared response and how far the two
    starts' stay apart (the largest relative difference over the responses: zero where they settle to one state)."""
    from .adapter import DRY
    from .studies import QUANTITIES, judge, read, stats_for_judging

    ratio, confidence = cfg["claims"]["close_to_ideal_ratio"], cfg["statistics"]["confidence"]
    by_variant = {str(d.attrs["variant"]): d for d in runs}
    variants, starts = [str(v) for v in claims.variant.values], [str(x) for x in claims.start.values]
    velocities = runs[0].fixed_impact_velocity.values
    outcome = np.full((len(variants), len(starts), len(velocities), claims.claim.size), -1)
    diff = np.full((len(variants), len(starts), len(velocities), claims.comparison.size), np.nan)
    for i, v in enumerate(variants):
        run = by_variant[v].transpose("fixed_impact_velocity", "start", "measure", "quantity", "scene", "statistic")
        errors = by_variant[v].numerical_error.transpose(
            "fixed_impact_velocity", "start", "measure", "quantity", "scene"
        )
        for k in range(len(starts)):
            for m in range(len(velocities)):
                stats = read(run.judged.values[m, k])
                verdict = judge(stats_for_judging(stats, errors.values[m, k]), ratio, confidence)
                outcome[i, k, m] = verdict["outcome"]
                diff[i, k, m] = [r["difference"] for r in verdict["rows"]]
    rms = np.stack(
        [
            by_variant[v].judged.sel(measure="rms", scene=list(DRY), statistic="judged_mean")
            .transpose("start", "fixed_impact_velocity", "scene", "quantity").values
            for v in variants
        ]
    )  # variant, start, velocity, scene, quantity
    spread = np.nanmax(np.abs(rms[:, 0] - rms[:, -1]) / np.abs(rms).mean(axis=1), axis=-1)  # variant, velocity, scene
    status = np.stack(
        [by_variant[v].state_status.sel(scene=list(DRY)).transpose("start", "fixed_impact_velocity", "scene").values
         for v in variants]
    ).astype(str)
    vs = ("variant", "start", "fixed_impact_velocity")
    return xr.Dataset(
        {
            "memory_free_outcome": (
                (*vs, "claim"), outcome,
                {"units": "1", "long_name": "claim under a memory-free damping: 1 holds, 0 fails, -1 undetermined"},
            ),
            "memory_free_difference": (
                (*vs, "comparison"), diff,
                {"units": "SI of the quantity", "long_name": "difference of each ordering under a memory-free damping"},
            ),
            "memory_free_rms": (
                (*vs, "dry_scene", "quantity"), rms,
                {
                    "units": "SI of the quantity",
                    "long_name": "RMS deviation from the ideal under a memory-free damping",
                },
            ),
            "memory_free_start_spread": (
                ("variant", "fixed_impact_velocity", "dry_scene"), spread,
                {
                    "units": "1",
                    "long_name": (
                        "largest relative difference of the two starts' RMS deviations under a memory-free damping"
                        " (over the compared responses)"
                    ),
                },
            ),
            "memory_free_start_spread_largest": (
                ("variant", "fixed_impact_velocity"), spread.max(axis=-1),
                {"units": "1", "long_name": "the largest of memory_free_start_spread over the dry scenes"},
            ),
            "memory_free_status": (
                (*vs, "dry_scene"), status,
                {"units": "1", "long_name": "how each dry state under a memory-free damping was found"},
            ),
        },
        coords={
            "fixed_impact_velocity": (
                "fixed_impact_velocity", velocities,
                {"units": "m s-1", "long_name": "the impact velocity the memory-free damping divides by"},
            ),
            "dry_scene": ("dry_scene", np.array(DRY, dtype=object), {"units": "1", "long_name": "dry scene"}),
            "quantity": (
                "quantity", np.array(QUANTITIES, dtype=object), {"units": "1", "long_name": "compared response"},
            ),
        },
    )


#: The lubricated scenes claim 3's ripple part compares: joint 2 lubricated (alone, and with joint 1) against joint 1
#: alone.
RIPPLE_SCENES = ("lubricated_1", "lubricated_2", "lubricated_both")


def claim3_parts(claims: xr.Dataset) -> xr.Dataset:
    """Per variant and start: whether claim 3's two parts hold on the measures: the lubricated responses close to
    the ideal (each below the threshold times its dry one) and the ripples left where joint 2 has clearance (the ripple
    orderings' outcome); what the ripple's error bar is made of for joint 2 lubricated (the reruns at the check
    tolerances, and the convergence term); the ripples at the tightest check tolerance (each rerun's own measure) and
    whether the orderings hold there; how large the ripples and the whole lubricated deviations are against the ideal
    response; and per cutoff of the sensitivity list whether the orderings hold on each scene's last turn."""
    from .statistics import conjunction

    labels = [str(x) for x in claims.comparison.values]
    close = [i for i, lab in enumerate(labels) if " < " in lab]
    ripples = [i for i, lab in enumerate(labels) if lab.startswith("ripple ")]
    out = claims.comparison_outcome.values
    ripple_outcome = np.array(
        [[conjunction(out[v, k, ripples].tolist()) for k in range(out.shape[1])] for v in range(out.shape[0])]
    )
    at = dict(measure="ripple", quantity="rocker_acceleration")
    measure = claims.mean_deviation.sel(**at, scene="lubricated_2")
    checks = np.abs(claims.scene_check_delta.sel(**at, scene="lubricated_2")).max("check")
    converging = claims.scene_convergence_error.sel(**at, scene="lubricated_2")
    error = claims.numerical_error.sel(**at, scene="lubricated_2")
    checked = claims.scene_check_mean.sel(**at, scene=list(RIPPLE_SCENES))
    tight = checked.isel(check=-1)  # variant, scene, start
    tight_above = tight.sel(scene="lubricated_2") > tight.sel(scene="lubricated_1")
    ideal = claims.ideal_rms.sel(quantity="rocker_acceleration")
    lubricated = claims.mean_deviation.sel(quantity="rocker_acceleration", scene=list(RIPPLE_SCENES))
    cut = claims.scene_ripple_by_cutoff.sel(quantity="rocker_acceleration")
    cut_holds = (cut.sel(scene="lubricated_2") > cut.sel(scene="lubricated_1")) & (
        cut.sel(scene="lubricated_both") > cut.sel(scene="lubricated_1")
    )
    vs = ("variant", "start")
    return xr.Dataset(
        {
            "claim3_close_holds": (
                vs,
                (out[..., close] == 1).all(axis=-1).astype(int),
                {
                    "units": "1",
                    "long_name": "1 if every lubricated scene is decidedly below the threshold times its dry one",
                },
            ),
            "claim3_ripples_holds": (
                vs,
                (ripple_outcome == 1).astype(int),
                {
                    "units": "1",
                    "long_name": (
                        "1 if the rocker acceleration's ripple (content above the cutoff) with joint 2 lubricated,"
                        " alone and with joint 1, is decidedly above joint 1's alone"
                    ),
                },
            ),
            "claim3_ripples_outcome": (
                vs, ripple_outcome,
                {"units": "1", "long_name": "claim 3's ripple orderings together: 1 hold, 0 fail, -1 undetermined"},
            ),
            "ripple_check_ratio": (
                vs,
                (checks / measure).transpose(*vs).values,
                {
                    "units": "1",
                    "long_name": (
                        "largest change of joint 2 lubricated's ripple at the check tolerances, over the ripple"
                    ),
                },
            ),
            "ripple_convergence_ratio": (
                vs,
                (converging / measure).transpose(*vs).values,
                {
                    "units": "1",
                    "long_name": "convergence term of joint 2 lubricated's ripple error bar, over the ripple",
                },
            ),
            "ripple_error_ratio": (
                vs, (error / measure).transpose(*vs).values,
                {"units": "1", "long_name": "numerical error bar of joint 2 lubricated's ripple, over the ripple"},
            ),
            "ripple_tight_above": (
                vs,
                tight_above.transpose(*vs).values.astype(int),
                {
                    "units": "1",
                    "long_name": (
                        "1 if joint 2 lubricated's ripple is above joint 1's at the tightest check tolerance (the"
                        " reruns' own means)"
                    ),
                },
            ),
            "ripple_tight_joint_1": (
                vs, tight.sel(scene="lubricated_1").transpose(*vs).values,
                {"units": "rad s-2", "long_name": "joint 1 lubricated's ripple at the tightest check tolerance"},
            ),
            "ripple_tight_joint_2": (
                vs, tight.sel(scene="lubricated_2").transpose(*vs).values,
                {"units": "rad s-2", "long_name": "joint 2 lubricated's ripple at the tightest check tolerance"},
            ),
            "ripple_tight_change": (
                vs,
                (checked.sel(scene="lubricated_2").isel(check=-1) / checked.sel(scene="lubricated_2").isel(check=0))
                .transpose(*vs)
                .values,
                {
                    "units": "1",
                    "long_name": "joint 2 lubricated's ripple at the tightest check tolerance over that at the first",
                },
            ),
            "ripple_tight_change_joint_1": (
                vs,
                (checked.sel(scene="lubricated_1").isel(check=-1) / checked.sel(scene="lubricated_1").isel(check=0))
                .transpose(*vs)
                .values,
                {
                    "units": "1",
                    "long_name": "joint 1 lubricated's ripple at the tightest check tolerance over that at the first",
                },
            ),
            "ripple_over_ideal": (
                "variant",
                (lubricated.sel(measure="ripple").max(("start", "scene")) / ideal).values,
                {
                    "units": "1",
                    "long_name": "largest lubricated ripple of the rocker acceleration over the ideal's RMS",
                },
            ),
            "lubricated_deviation_over_ideal": (
                "variant",
                (lubricated.sel(measure="rms").max(("start", "scene")) / ideal).values,
                {
                    "units": "1",
                    "long_name": "largest lubricated RMS deviation of the rocker acceleration over the ideal's RMS",
                },
            ),
            "ripple_cutoff_holds": (
                ("variant", "ripple_cutoff"), cut_holds.transpose("variant", "ripple_cutoff").values.astype(int),
                {"units": "1", "long_name": "1 if the ripple orderings hold on each scene's last turn at this cutoff"},
            ),
        },
        coords={"variant": claims.variant, "start": claims.start, "ripple_cutoff": claims.ripple_cutoff},
    )


#: A ripple that changes by less than this fraction between the two check tolerances is called the same at both.
SAME_AT_BOTH = 0.05


def _tight_words(first: xr.Dataset, variant: str, side: str) -> str:
    """Which side of joint 1's joint 2's ripple lies at the tightest check tolerance in ``variant`` (first start's
    values), and where the two are heading from the first check tolerance to the tightest."""
    two, one = float(first.ripple_tight_change.sel(variant=variant)), float(
        first.ripple_tight_change_joint_1.sel(variant=variant)
    )
    where = (f"{side} joint 1's in {variant} ({float(first.ripple_tight_joint_2.sel(variant=variant)):.2g} against "
             f"{float(first.ripple_tight_joint_1.sel(variant=variant)):.2g} rad/s², first start)")
    if side == "below" and abs(one - 1.0) <= SAME_AT_BOTH and two < 1.0:
        return (
            f"{where}, and while joint 1's is the same at both check tolerances joint 2's keeps falling (by a factor of"
            f" {two:.2g}): the trend at tighter tolerances points against the ordering"
        )
    return f"{where}, both still moving (by factors of {two:.2g} and {one:.2g}): not converged"


def _cutoffs(values) -> str:
    """Cutoffs (Hz) as a short list in words."""
    return ", ".join(f"{float(c):g}" for c in values) + " Hz"


def ripples_text(findings: xr.Dataset) -> str:
    """Where claim 3's first part holds and its ripple part alone fails or is undetermined, what decides it (from the
    first start, the tightest tolerance from every start), how large the ripples are, and whether the cutoff decides."""
    if "claim3_close_holds" not in findings:
        return ""
    first = findings.isel(start=0)
    close = [str(v) for v in findings.variant.values if int(first.claim3_close_holds.sel(variant=v))]
    fails = [v for v in close if int(first.claim3_ripples_outcome.sel(variant=v)) == 0]
    open_ = [v for v in close if int(first.claim3_ripples_outcome.sel(variant=v)) == -1]
    text = ""
    if fails:
        text += (
            f" Claim 3 is made of two parts ({', '.join(fails)}): lubrication brings every scene close to the ideal,"
            " which holds, while the ripples where joint 2 has clearance (the rocker acceleration's content above the"
            " ripple cutoff) are not larger than at joint 1 alone at the nominal inputs."
        )
    if open_:
        moves = " and ".join(f"{float(first.ripple_check_ratio.sel(variant=v)):.2g} ({v})" for v in open_)
        big = [
            v
            for v in open_
            if float(first.ripple_convergence_ratio.sel(variant=v)) > float(first.ripple_check_ratio.sel(variant=v))
        ]
        text += (
            f" Claim 3 is made of two parts ({', '.join(open_)}): lubrication brings every scene close to the ideal,"
            " which holds, while whether ripples are left where joint 2 has clearance (the rocker acceleration's"
            " content above the ripple cutoff, with joint 2 lubricated alone or with joint 1, against joint 1 alone)"
            f" is undetermined: the reruns at the check tolerances move joint 2's ripple by {moves} times itself,"
            " shrinking as the tolerance tightens, which is consistent with integrator noise"
            + (
                f" (in {', '.join(big)} the convergence term, fitted to the ripple's turn-to-turn scatter, is "
                + " and ".join(f"{float(first.ripple_convergence_ratio.sel(variant=v)):.2g}" for v in big)
                + " times it, and the error bar "
                + " and ".join(f"{float(first.ripple_error_ratio.sel(variant=v)):.2g}" for v in big)
                + " times)"
                if big
                else ""
            )
            + "."
        )
        above = {v: set(findings.ripple_tight_above.sel(variant=v).values.tolist()) for v in open_}
        side = {v: "above" if above[v] == {1} else "below" if above[v] == {0} else "" for v in open_}
        said = [v for v in open_ if side[v]]
        if said:
            text += (
                " At the tightest check tolerance, from every start, joint 2's ripple is "
                + "; ".join(_tight_words(first, v, side[v]) for v in said)
                + "."
            )
        text += (
            f" Either way {ripple_bounds(findings, open_)}: the visible fluctuation peaks of the paper's lubricated"
            " curves are absent from every lubricated response of ours."
        )
        for v in open_:
            held = findings.ripple_cutoff_holds.sel(variant=v)
            if len(set(held.values.tolist())) > 1:
                text += (
                    f" The cutoff decides the ordering in {v} (each scene's last turn): it holds at"
                    f" {_cutoffs(held.ripple_cutoff.values[held.values == 1])} and not at"
                    f" {_cutoffs(held.ripple_cutoff.values[held.values == 0])}."
                )
    return text


def film_cap_text(findings: xr.Dataset) -> str:
    """Lubricated scenes beyond the film cap most of the time shown (their claim 3 is judged on the capped film force,
    which the assumed e0 sets)."""
    if "beyond_film_cap_fraction" not in findings:
        return ""
    parts = []
    for v in findings.variant.values:
        frac = findings.beyond_film_cap_fraction.sel(variant=v)
        mostly = [
            f"{SCENE_WORDS[str(s)]} ({100 * float(frac.sel(scene=s)):.0f} %)"
            for s in findings.scene.values
            if float(frac.sel(scene=s)) >= 0.5
        ]
        if mostly:
            who = VARIANT_WORDS.get(str(v), str(v)).capitalize()
            parts.append(
                f" {who}, the scenes with {' and with '.join(mostly)} run beyond the film cap most of the time shown:"
                " claim 3 there is judged on the capped film force, which the assumed e0 sets (e0 is one of the"
                " assumed inputs)."
            )
    return "".join(parts).strip()
