# Paper "stiffness": equivalent stiffness of the needle crank-rocker (energy method).


rule stiffness:
    input:
        code=lib("kinematics", "stiffness", "stiffness_dataset", "from_config", "results"),
    output:
        "results/stiffness/stiffness.nc",
    params:
        section=config["stiffness"],
    script:
        "../scripts/stiffness.py"


rule stiffness_compare:
    input:
        result="results/stiffness/stiffness.nc",
        published="config/published/stiffness.yaml",
        code=lib("compare", "results"),
    output:
        "results/stiffness/comparison.csv",
    params:
        section=config["stiffness"],
    script:
        "../scripts/compare.py"
