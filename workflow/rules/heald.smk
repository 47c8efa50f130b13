# Paper "heald": mechanical chains of a heald motion, joint forces with clearance.


rule heald_chain:
    input:
        code=lib("chains", "heald", "heald_dataset", "timing", "results"),
    output:
        "results/heald/chain.nc",
    params:
        section=config["heald"],
    script:
        "../scripts/heald_chain.py"


rule heald_accuracy:
    input:
        code=lib("chains", "heald", "heald_dataset", "timing", "results"),
    output:
        result="results/heald/accuracy.nc",
        timings="results/heald/accuracy_timings.json",
    params:
        paper="heald",
        section=config["heald"],
    script:
        "../scripts/accuracy.py"


rule heald_compare:
    input:
        results=["results/heald/chain.nc"],
        published="config/published/heald.yaml",
        code=lib("compare", "results"),
    output:
        "results/heald/comparison.csv",
    params:
        section=config["heald"],
    script:
        "../scripts/compare.py"
