# Paper "clearance": four-bar with clearance joints and lubrication (multibody engine, scenes).
import importlib.util
from linkwork.papers.clearance import adapter as clearance_adapter

CLEARANCE = config["clearance"]
CLEARANCE_VARIANTS = list(CLEARANCE["variants"])
CLEARANCE_SCENES = list(CLEARANCE["scenes"])
CLEARANCE_DYNAMIC = [s for s in CLEARANCE_SCENES if CLEARANCE["scenes"][s]["clearance_joints"]]


def scene_cfg(tolerance):
    """A scene's params: exactly the keys its effects, its variant and its integrator read."""
    return lambda wildcards: section("clearance", *clearance_adapter.scene_keys(CLEARANCE, wildcards.variant, wildcards.scene, tolerance))


wildcard_constraints:
    variant="|".join(CLEARANCE_VARIANTS),
    scene="|".join(CLEARANCE_SCENES),


rule clearance_scene:
    priority: CHAIN_HEAD_PRIORITY
    input:
        code=code("linkwork.papers.clearance.studies"),
    output:
        "results/clearance/{variant}/{scene}.nc",
    params:
        study="linkwork.papers.clearance.studies:scene",
        cfg=scene_cfg("pipeline"),
        args=lambda wildcards: {"variant": wildcards.variant, "scene": wildcards.scene, "tolerance": "pipeline"},
    script:
        STUDY


rule clearance_scene_tight:
    priority: CHAIN_HEAD_PRIORITY
    input:
        code=code("linkwork.papers.clearance.studies"),
    output:
        "results/clearance/{variant}/tight/{scene}.nc",
    params:
        study="linkwork.papers.clearance.studies:scene",
        cfg=scene_cfg("tight"),
        args=lambda wildcards: {"variant": wildcards.variant, "scene": wildcards.scene, "tolerance": "tight"},
    script:
        STUDY


rule clearance_claims:
    input:
        scenes=expand("results/clearance/{variant}/{scene}.nc", variant=CLEARANCE_VARIANTS, scene=CLEARANCE_SCENES),
        tight=expand("results/clearance/{variant}/tight/{scene}.nc", variant=CLEARANCE_VARIANTS, scene=CLEARANCE_DYNAMIC),
        code=code("linkwork.papers.clearance.studies"),
    output:
        "results/clearance/claims.nc",
    params:
        study="linkwork.papers.clearance.studies:claims",
        cfg=section("clearance", "numerics.record_cycles", "claims", *(f"variants.{v}" for v in CLEARANCE_VARIANTS)),
    script:
        STUDY


rule clearance_work_precision:
    priority: LONG_JOB_PRIORITY
    input:
        code=code("linkwork.papers.clearance.accuracy"),
    output:
        result="results/clearance/accuracy.nc",
        timings="results/clearance/accuracy_timings.json",
    params:
        study="linkwork.papers.clearance.accuracy:work_precision",
        cfg=section("clearance", "work_precision", "numerics.points_per_cycle", "integrators",
                    *(k for s in CLEARANCE["work_precision"]["scenes"] for k in clearance_adapter.model_keys(CLEARANCE, CLEARANCE["work_precision"]["variant"], s))),
    script:
        STUDY


rule clearance_compare:
    input:
        published="config/published/clearance.yaml",
        claims="results/clearance/claims.nc",
        uncertainty="results/clearance/uncertainty.nc",
        code=code("linkwork.papers.clearance.findings"),
    output:
        "results/clearance/comparison.csv",
        "results/clearance/findings.nc",
    params:
        study="linkwork.papers.clearance.findings:compare",
        cfg={},
    script:
        STUDY


# Exudyn beside linkwork (the optional extra `crosscheck`): only with `crosscheck: true` (`make crosscheck`).
if config["crosscheck"] and not importlib.util.find_spec("exudyn"):
    sys.exit("linkwork: crosscheck: true needs Exudyn, the optional extra: pip install -c constraints.txt -e '.[crosscheck]' (or make crosscheck)")


rule clearance_crosscheck:
    input:
        code=code("linkwork.papers.clearance.crosscheck"),
    output:
        "results/clearance/crosscheck.nc",
    params:
        study="linkwork.papers.clearance.crosscheck:ideal",
        cfg=section("clearance", "ground_m", "crank_speed_rad_s", "bodies", "variants", "scenes.ideal", "crosscheck"),
    script:
        STUDY
