# Across the pipeline: what accuracy costs in time, for every numerical method.


rule accuracy_summary:
    input:
        beatup="results/beatup/accuracy.nc",
        beatup_t="results/beatup/accuracy_timings.json",
        transplanter="results/transplanter/accuracy.nc",
        transplanter_t="results/transplanter/accuracy_timings.json",
        clearance="results/clearance/accuracy.nc",
        clearance_t="results/clearance/accuracy_timings.json",
        heald="results/heald/accuracy.nc",
        heald_t="results/heald/accuracy_timings.json",
        code=lib("accuracy_summary", "stiffness", "kinematics", "from_config", "timing", "results"),
    output:
        result="results/accuracy/summary.nc",
        timings="results/accuracy/timings.json",
    params:
        config={k: config[k] for k in ("stiffness", "transplanter", "clearance", "heald")},
        panels=[2, 4, 8, 16, 32, 64, 128],
        repeats=5,
    script:
        "../scripts/accuracy_summary.py"
