# Reports: jupytext percent scripts executed and rendered to self-contained HTML.
import json

# Per paper: the files its report reads (passed to it by name) and the lib modules it imports.
REPORT_INPUTS = {
    "stiffness": {
        "result": "results/stiffness/stiffness.nc",
        "comparison": "results/stiffness/comparison.csv",
        "published": "config/published/stiffness.yaml",
    },
    "beatup": {
        "result": "results/beatup/sixbar.nc",
        "window": "results/beatup/window.nc",
        "accuracy": "results/beatup/accuracy.nc",
        "timings": "results/beatup/accuracy_timings.json",
        "comparison": "results/beatup/comparison.csv",
        "published": "config/published/beatup.yaml",
    },
    "heald": {
        "result": "results/heald/chain.nc",
        "accuracy": "results/heald/accuracy.nc",
        "timings": "results/heald/accuracy_timings.json",
        "comparison": "results/heald/comparison.csv",
        "published": "config/published/heald.yaml",
    },
    "transplanter": {
        "result": "results/transplanter/ked.nc",
        "optim": "results/transplanter/optim.nc",
        "at_published": "results/transplanter/at_published.nc",
        "accuracy": "results/transplanter/accuracy.nc",
        "timings": "results/transplanter/accuracy_timings.json",
        "comparison": "results/transplanter/comparison.csv",
        "published": "config/published/transplanter.yaml",
    },
    "clearance": {
        "result": "results/clearance/claims.nc",
        "accuracy": "results/clearance/accuracy.nc",
        "timings": "results/clearance/accuracy_timings.json",
        "comparison": "results/clearance/comparison.csv",
        "published": "config/published/clearance.yaml",
        "scenes": "results/clearance/decoded/ideal.nc",
    },
    "accuracy": {
        "result": "results/accuracy/summary.nc",
        "timings": "results/accuracy/timings.json",
    },
    "sweeps": {
        "result": "results/sweeps/clearance.nc",
        "heald": "results/sweeps/heald.nc",
    },
}
REPORT_CODE = {
    "stiffness": lib("from_config", "stiffness", "kinematics"),
    "beatup": lib("beatup", "beatup_dataset", "kinematics"),
    "heald": lib("chains", "heald", "heald_dataset"),
    "transplanter": lib("transplanter"),
    "clearance": lib("clearance_dataset"),
    "accuracy": lib(),
    "sweeps": lib(),
}


def report_inputs(wildcards):
    return {
        "notebook": f"reports/{wildcards.paper}.py",
        "renderer": "workflow/scripts/render_report.py",
        "style": "reports/_common.py",
        "code": REPORT_CODE[wildcards.paper],
        **REPORT_INPUTS[wildcards.paper],
    }


rule report:
    input:
        unpack(report_inputs),
    output:
        "results/reports/{paper}.html",
    wildcard_constraints:
        paper="|".join(BUILT_PAPERS + ["accuracy", "sweeps"]),
    params:
        inputs=lambda wildcards, input: " ".join(f"--input {k}={input[k]}" for k in REPORT_INPUTS[wildcards.paper]),
    shell:
        "python {input.renderer} {input.notebook} {output} {params.inputs}"


rule index:
    input:
        notebook="reports/index.py",
        renderer="workflow/scripts/render_report.py",
        style="reports/_common.py",
        code=lib("compare"),
        comparisons=expand("results/{paper}/comparison.csv", paper=BUILT_PAPERS),
        reports=expand("results/reports/{paper}.html", paper=BUILT_PAPERS),
    output:
        "results/reports/index.html",
    params:
        papers=json.dumps(config["papers"]),
        reference_forms=json.dumps({"stiffness": config["stiffness"]["reference_form"], "beatup": "", "heald": "A", "transplanter": "", "clearance": "decoded"}),
        comparison_args=lambda wildcards, input: " ".join(
            f"--input comparison_{paper}={path}" for paper, path in zip(BUILT_PAPERS, input.comparisons)
        ),
    shell:
        "python {input.renderer} {input.notebook} {output} {params.comparison_args}"
        " --param papers={params.papers:q} --param reference_forms={params.reference_forms:q}"
