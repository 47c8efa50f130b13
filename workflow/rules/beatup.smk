# Paper "beatup": six-bar beating-up mechanism kinematics (Table 1) and the weft window vs a four-bar.


rule beatup_sixbar:
    input:
        code=lib("kinematics", "beatup", "beatup_dataset", "timing", "from_config", "results"),
    output:
        "results/beatup/sixbar.nc",
    params:
        section=config["beatup"],
    script:
        "../scripts/beatup_sixbar.py"


rule beatup_window:
    input:
        code=lib("kinematics", "beatup", "beatup_dataset", "timing", "from_config", "results"),
    output:
        "results/beatup/window.nc",
    params:
        section=config["beatup"],
    script:
        "../scripts/beatup_window.py"


rule beatup_accuracy:
    input:
        code=lib("kinematics", "beatup", "beatup_dataset", "timing", "from_config", "results"),
    output:
        result="results/beatup/accuracy.nc",
        timings="results/beatup/accuracy_timings.json",
    params:
        paper="beatup",
        section=config["beatup"],
    script:
        "../scripts/accuracy.py"


rule beatup_compare:
    input:
        results=["results/beatup/sixbar.nc", "results/beatup/window.nc"],
        published="config/published/beatup.yaml",
        code=lib("compare", "results"),
    output:
        "results/beatup/comparison.csv",
    params:
        section=config["beatup"],
    script:
        "../scripts/compare.py"
