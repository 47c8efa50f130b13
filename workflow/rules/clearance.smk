# Paper "clearance": four-bar with clearance joints and lubrication (multibody engine, scenes).
import importlib
import importlib.util
from linkwork.papers.clearance import adapter as clearance_adapter

CLEARANCE = config["clearance"]
CLEARANCE_VARIANTS = list(CLEARANCE["variants"])
CLEARANCE_SCENES = list(CLEARANCE["scenes"])
# Its input-uncertainty batches: each moves the samples of one variant that enter the same scenes, continuing those
# scenes from their nominal states; a batch reads only the keys of the scenes its samples move (no check reruns: they
# take the nominal error bar), and its moved values travel as arguments (a range edit reruns its batches).
CLEARANCE_UNCERTAINTY = importlib.import_module("linkwork.papers.clearance.uncertainty").batch_jobs(CLEARANCE)


def clearance_uncertainty_cfg(index):
    job = CLEARANCE_UNCERTAINTY[index]
    keys = {
        k
        for s in job["scenes"]
        for k in clearance_adapter.scene_keys(CLEARANCE, job["variant"], s)
        if not k.startswith("check_integrators.")
    }
    return section("clearance", *sorted(keys))


UNCERTAINTY["clearance"] = {
    "cfg": clearance_uncertainty_cfg,
    "args": lambda index: {
        "samples": CLEARANCE_UNCERTAINTY[index]["samples"],
        "variant": CLEARANCE_UNCERTAINTY[index]["variant"],
    },
    # the gather judges the claims (threshold, variants), so a threshold edit reruns no scene
    "gather_cfg": lambda: section(
        "clearance",
        "claims",
        "assumed",
        "uncertainty",
        "states.starts",
        "statistics.confidence",
        *(f"variants.{v}" for v in CLEARANCE_VARIANTS),
        design=True,
    ),
    "batch_count": lambda: len(CLEARANCE_UNCERTAINTY),
    "batch_inputs": lambda index: {
        "nominal": [
            f"results/clearance/{CLEARANCE_UNCERTAINTY[index]['variant']}/{s}.nc"
            for s in CLEARANCE_UNCERTAINTY[index]["scenes"]
        ]
    },
    "gather_inputs": lambda: {"claims": "results/clearance/claims.nc"},  # the nominal deviations
}


def clearance_sweep_cfg():
    """The paper's config values a point of the clearance sweep reads (the swept clearance and speed come as the
    point)."""
    spec = config["sweeps"]["clearance"]
    scene = CLEARANCE["scenes"][spec["scene"]]
    keys = clearance_adapter.model_keys(CLEARANCE, spec["variant"], spec["scene"])
    keys = [
        k
        for k in keys
        if k != "crank_speed_rad_s" and (k != "joints.journal_radius_m" or "lubrication" in scene["effects"])
    ]
    return section(
        "clearance",
        *keys,
        "numerics.points_per_cycle",
        f"integrators.{clearance_adapter.integrator_kind(scene)}",
        "states",
        "statistics",
        "claims.ripple_cutoff_hz",
    )


SWEEP["clearance"] = {
    "cfg": clearance_sweep_cfg,
    "reference": lambda: {
        "clearance_m": CLEARANCE["joints"]["bearing_radius_m"] - CLEARANCE["joints"]["journal_radius_m"],
        "crank_speed_rad_s": CLEARANCE["crank_speed_rad_s"],
    },
}
REPORT_PRIORITY["clearance"] = GATE_PRIORITY  # the longest report: out of the tail


def clearance_studies_compared():
    """The scenes the claims compare (lib's list)."""
    return list(clearance_adapter.COMPARED)


def scene_cfg(wildcards):
    """A scene's params: exactly the keys its effects, its variant, its settling rule and its integrators read."""
    return section("clearance", *clearance_adapter.scene_keys(CLEARANCE, wildcards.variant, wildcards.scene))


wildcard_constraints:
    variant="|".join(CLEARANCE_VARIANTS),
    scene="|".join(CLEARANCE_SCENES),


rule clearance_scene:
    input:
        code=code("linkwork.papers.clearance.studies"),
    output:
        "results/clearance/{variant}/{scene}.nc",
    priority: CHAIN_HEAD_PRIORITY
    params:
        study="linkwork.papers.clearance.studies:scene",
        cfg=scene_cfg,
        args=lambda wildcards: {"variant": wildcards.variant, "scene": wildcards.scene},
    script:
        STUDY


rule clearance_claims:
    input:
        scenes=expand("results/clearance/{variant}/{scene}.nc", variant=CLEARANCE_VARIANTS, scene=CLEARANCE_SCENES),
        code=code("linkwork.papers.clearance.studies"),
    output:
        "results/clearance/claims.nc",
    priority: GATE_PRIORITY
    params:
        study="linkwork.papers.clearance.studies:claims",
        cfg=section(
            "clearance",
            "statistics.batch_cycles",
            "statistics.confidence",
            "claims",
            *(f"variants.{v}" for v in CLEARANCE_VARIANTS),
        ),
    script:
        STUDY


rule clearance_work_precision:
    input:
        code=code("linkwork.papers.clearance.accuracy"),
    output:
        result="results/clearance/accuracy.nc",
        timings="results/clearance/accuracy_timings.json",
    priority: CHAIN_HEAD_PRIORITY  # the clearance report waits for it: before the sweep points, not after them
    params:
        study="linkwork.papers.clearance.accuracy:work_precision",
        cfg=section(
            "clearance",
            "work_precision",
            # the pipeline's setting of each kind of scene studied (explicit: dry, stiff: lubricated), shown in
            # the accuracy summary
            *sorted(
                {
                    f"integrators.{clearance_adapter.integrator_kind(CLEARANCE['scenes'][s])}"
                    for s in CLEARANCE["work_precision"]["scenes"]
                }
            ),
            *(
                k
                for s in CLEARANCE["work_precision"]["scenes"]
                for k in clearance_adapter.model_keys(CLEARANCE, CLEARANCE["work_precision"]["variant"], s)
            ),
        ),
    script:
        STUDY


CLEARANCE_CONTACT = [s for s in clearance_studies_compared() if "contact" in CLEARANCE["scenes"][s]["effects"]]


rule clearance_contact_law:
    input:
        nominal=expand("results/clearance/{{variant}}/{scene}.nc", scene=CLEARANCE_CONTACT),
        code=code("linkwork.papers.clearance.sensitivity"),
    output:
        "results/clearance/contact_law/{variant}.nc",
    priority: CHAIN_HEAD_PRIORITY
    params:
        study="linkwork.papers.clearance.sensitivity:model_sensitivity",
        cfg=lambda wildcards: section(
            "clearance",
            *sorted(
                {
                    k
                    for s in CLEARANCE_CONTACT
                    for k in clearance_adapter.scene_keys(CLEARANCE, wildcards.variant, s)
                    if not k.startswith("check_integrators.")
                }
                | {"assumed.joint_length_m"}
            ),
        ),
        args=lambda wildcards: {"variant": wildcards.variant, "law": CLEARANCE["sensitivity"]["elastic_law"]},
    script:
        STUDY


rule clearance_memory_free:
    input:
        nominal=expand("results/clearance/{{variant}}/{scene}.nc", scene=CLEARANCE_CONTACT),
        code=code("linkwork.papers.clearance.sensitivity"),
    output:
        "results/clearance/memory_free/{variant}.nc",
    priority: CHAIN_HEAD_PRIORITY
    params:
        study="linkwork.papers.clearance.sensitivity:memory_free",
        cfg=lambda wildcards: section(
            "clearance",
            *sorted(
                {
                    k
                    for s in CLEARANCE_CONTACT
                    for k in clearance_adapter.scene_keys(CLEARANCE, wildcards.variant, s)
                }  # with the check integrators: each state carries its own error bar
            ),
        ),
        args=lambda wildcards: {
            "variant": wildcards.variant,
            "velocities": CLEARANCE["sensitivity"]["fixed_impact_velocity_m_s"],
        },
    script:
        STUDY


rule clearance_compare:
    input:
        published="config/published/clearance.yaml",
        claims="results/clearance/claims.nc",
        uncertainty="results/clearance/uncertainty.nc",
        laws=expand("results/clearance/contact_law/{variant}.nc", variant=CLEARANCE_VARIANTS),
        memory_free=expand("results/clearance/memory_free/{variant}.nc", variant=CLEARANCE_VARIANTS),
        code=code("linkwork.papers.clearance.findings"),
    output:
        comparison_table("clearance"),
        "results/clearance/findings.nc",
    priority: GATE_PRIORITY
    params:
        study="linkwork.papers.clearance.findings:compare",
        cfg=section(
            "clearance",
            *(f"scenes.{s}.effects" for s in CLEARANCE_SCENES),
            "assumed.e0_m",
            "assumed.e0_m.range",  # the named effects: the stray-evaluation check
            "joints",
            "claims.close_to_ideal_ratio",
            "statistics.confidence",
            "sensitivity",
        ),
        # the law sensitivity and the laws' validity
    script:
        STUDY


# Exudyn beside linkwork (the optional extra `crosscheck`): only with `crosscheck: true` (`make crosscheck`).
if config["crosscheck"] and not importlib.util.find_spec("exudyn"):
    sys.exit(
        "linkwork: crosscheck: true needs Exudyn, the optional extra:"
        " pip install -c constraints.txt -e '.[crosscheck]' (or make crosscheck)"
    )
CROSSCHECK_DRY = CLEARANCE["crosscheck"]["dry_scenes"]
for _scene in CROSSCHECK_DRY:
    _spec = CLEARANCE["scenes"].get(_scene, {})
    if not _spec.get("clearance_joints") or "lubrication" in _spec.get("effects", []):
        sys.exit(
            f"linkwork: clearance.crosscheck.dry_scenes: {_scene!r} is not a dry clearance scene of clearance.scenes"
        )
CROSSCHECK_WP = {
    "crosscheck_wp": "results/clearance/crosscheck/work_precision.nc",
    "crosscheck_wp_timings": "results/clearance/crosscheck/work_precision_timings.json",
}  # the accuracy report's
CROSSCHECK_RESULTS = {
    "crosscheck_ideal": "results/clearance/crosscheck/ideal.nc",
    "crosscheck_summary": "results/clearance/crosscheck/dry_summary.nc",
    "crosscheck_dry": expand(
        "results/clearance/crosscheck/{variant}/{scene}.nc", variant=CLEARANCE_VARIANTS, scene=CROSSCHECK_DRY
    ),
}


rule clearance_crosscheck:
    input:
        code=code("linkwork.papers.clearance.crosscheck"),
    output:
        "results/clearance/crosscheck/ideal.nc",
    params:
        study="linkwork.papers.clearance.crosscheck:ideal",
        cfg=section("clearance", "ground_m", "crank_speed_rad_s", "bodies", "variants", "scenes.ideal", "crosscheck"),
    script:
        STUDY


rule clearance_crosscheck_dry:
    input:
        code=code("linkwork.papers.clearance.crosscheck"),
    output:
        "results/clearance/crosscheck/{variant}/{scene}.nc",
    wildcard_constraints:
        variant="|".join(CLEARANCE_VARIANTS),
        scene="|".join(CROSSCHECK_DRY),
    params:
        study="linkwork.papers.clearance.crosscheck:dry",
        cfg=lambda wildcards: section(
            "clearance",
            *clearance_adapter.scene_keys(CLEARANCE, wildcards.variant, wildcards.scene),
            "numerics.settle_cycles",
            "scenes.ideal",
            "crosscheck",
        ),
        args=lambda wildcards: {"variant": wildcards.variant, "scene": wildcards.scene},
    script:
        STUDY


rule clearance_crosscheck_work_precision:
    input:
        code=code("linkwork.papers.clearance.crosscheck"),
    output:
        result="results/clearance/crosscheck/work_precision.nc",
        timings="results/clearance/crosscheck/work_precision_timings.json",
    params:
        study="linkwork.papers.clearance.crosscheck:work_precision",
        cfg=lambda wildcards: section(
            "clearance",
            *sorted(
                set(
                    clearance_adapter.scene_keys(
                        CLEARANCE,
                        CLEARANCE["work_precision"]["variant"],
                        CLEARANCE["crosscheck"]["work_precision"]["scene"],
                    )
                )
            ),
            "scenes.ideal",
            "work_precision",
            "integrators",
            "crosscheck",
        ),
    script:
        STUDY


rule clearance_crosscheck_summary:
    input:
        dry=CROSSCHECK_RESULTS["crosscheck_dry"],
        code=code("linkwork.papers.clearance.crosscheck"),
    output:
        "results/clearance/crosscheck/dry_summary.nc",
    params:
        study="linkwork.papers.clearance.crosscheck:dry_summary",
        cfg=section("clearance", "variants"),
    script:
        STUDY


# the inputs of the paper's report (reports.smk renders it)
REPORT_INPUTS["clearance"] = paper_report(
    "clearance",
    result="results/clearance/claims.nc",
    accuracy="results/clearance/accuracy.nc",
    scenes=expand("results/clearance/{variant}/{scene}.nc", variant=CLEARANCE_VARIANTS, scene=CLEARANCE_SCENES),
    sweep="results/sweeps/clearance.nc",
    **(CROSSCHECK_RESULTS if config["crosscheck"] else {}),
)
ACCURACY_REPORT_INPUTS.update(CROSSCHECK_WP if config["crosscheck"] else {})
