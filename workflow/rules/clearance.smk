# Paper "clearance": four-bar with clearance joints and lubrication (multibody engine, scenes).

CLEARANCE_CODE = lib("kinematics", "multibody/kernels", "multibody/model", "clearance_dataset", "timing", "results")
CLEARANCE_VARIANTS = list(config["clearance"]["variants"])
CLEARANCE_SCENES = list(config["clearance"]["scenes"])
CLEARANCE_DYNAMIC = [s for s in CLEARANCE_SCENES if config["clearance"]["scenes"][s]["clearance_joints"]]


wildcard_constraints:
    variant="|".join(CLEARANCE_VARIANTS),
    scene="|".join(CLEARANCE_SCENES),


rule clearance_scene:
    input:
        code=CLEARANCE_CODE,
    output:
        "results/clearance/{variant}/{scene}.nc",
    params:
        section=config["clearance"],
        tolerance="pipeline",
    script:
        "../scripts/clearance_scene.py"


rule clearance_scene_tight:
    input:
        code=CLEARANCE_CODE,
    output:
        "results/clearance/{variant}/tight/{scene}.nc",
    params:
        section=config["clearance"],
        tolerance="tight",
    script:
        "../scripts/clearance_scene.py"


rule clearance_claims:
    input:
        scenes=expand("results/clearance/{variant}/{scene}.nc", variant=CLEARANCE_VARIANTS, scene=CLEARANCE_SCENES),
        tight=expand("results/clearance/{variant}/tight/{scene}.nc", variant=CLEARANCE_VARIANTS, scene=CLEARANCE_DYNAMIC),
        code=CLEARANCE_CODE,
    output:
        "results/clearance/claims.nc",
    params:
        section=config["clearance"],
    script:
        "../scripts/clearance_claims.py"


rule clearance_work_precision:
    input:
        code=CLEARANCE_CODE,
    output:
        result="results/clearance/accuracy.nc",
        timings="results/clearance/accuracy_timings.json",
    params:
        paper="clearance",
        section=config["clearance"],
    script:
        "../scripts/accuracy.py"


rule clearance_compare:
    input:
        results=["results/clearance/claims.nc"],
        published="config/published/clearance.yaml",
        code=lib("compare", "results"),
    output:
        "results/clearance/comparison.csv",
    params:
        section=config["clearance"],
    script:
        "../scripts/compare.py"
