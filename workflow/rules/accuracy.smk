# Across the pipeline: what accuracy costs in time, for every numerical method.

ACCURACY_PAPERS = [
    p for p in PAPERS if (LIB / "linkwork" / "papers" / p / "accuracy.py").is_file()
]  # the papers with an accuracy study


rule accuracy_summary:
    input:
        **{p: f"results/{p}/accuracy.nc" for p in ACCURACY_PAPERS},
        **{f"{p}_t": f"results/{p}/accuracy_timings.json" for p in ACCURACY_PAPERS},
        code=code("linkwork.pipeline.accuracy"),
    output:
        result="results/accuracy/summary.nc",
        timings="results/accuracy/timings.json",
    params:
        study="linkwork.pipeline.accuracy:summary",
        cfg={},
    script:
        STUDY
