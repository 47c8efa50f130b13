# Paper "transplanter": kineto-elastodynamics and penalty-function section optimisation.

TRANSPLANTER_CODE = lib("kinematics", "fem", "transplanter", "optimize", "transplanter_dataset", "from_config", "results", "timing")


rule transplanter_optim:
    input:
        code=TRANSPLANTER_CODE,
    output:
        "results/transplanter/optim.nc",
    params:
        section=config["transplanter"],
    script:
        "../scripts/transplanter_optim.py"


rule transplanter_ked:
    input:
        optim="results/transplanter/optim.nc",
        code=TRANSPLANTER_CODE,
    output:
        "results/transplanter/ked.nc",
    params:
        section=config["transplanter"],
    script:
        "../scripts/transplanter_ked.py"


rule transplanter_at_published:
    # comparison data: our model evaluated at the paper's optimum (reads config/published/)
    input:
        published="config/published/transplanter.yaml",
        code=TRANSPLANTER_CODE,
    output:
        "results/transplanter/at_published.nc",
    params:
        section=config["transplanter"],
    script:
        "../scripts/transplanter_at_published.py"


rule transplanter_accuracy:
    input:
        code=TRANSPLANTER_CODE,
    output:
        result="results/transplanter/accuracy.nc",
        timings="results/transplanter/accuracy_timings.json",
    params:
        paper="transplanter",
        section=config["transplanter"],
    script:
        "../scripts/accuracy.py"


rule transplanter_compare:
    input:
        results=["results/transplanter/optim.nc", "results/transplanter/at_published.nc"],
        published="config/published/transplanter.yaml",
        code=lib("compare", "results"),
    output:
        "results/transplanter/comparison.csv",
    params:
        section=config["transplanter"],
    script:
        "../scripts/compare.py"
