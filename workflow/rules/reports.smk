# Reports: jupytext percent scripts executed and rendered to self-contained HTML.
# REPORT_INPUTS is the one place that says which files a report reads; the renderer passes them by name.
# Wall times (the *timings.json side files) are read by the accuracy report alone (MEASURED_REPORTS): every other
# report is a function of deterministic results and renders to the same bytes on every rerun and every machine.


def paper_report(paper, **results):
    uncertainty = {"uncertainty": f"results/{paper}/uncertainty.nc"} if paper in UNCERTAIN_PAPERS else {}
    return {**results, **uncertainty, "comparison": f"results/{paper}/comparison.csv", "findings": f"results/{paper}/findings.nc",
            "published": f"config/published/{paper}.yaml", "assumptions": f"results/{paper}/assumptions.nc"}


rule assumptions:
    # the one rule that reads the reasons: an edit of a reason reruns this step and its paper's report, nothing else
    priority: GATE_PRIORITY
    input:
        code=code("linkwork.pipeline.assumptions"),
    output:
        "results/{paper}/assumptions.nc",
    wildcard_constraints:
        paper="|".join(PAPERS),
    params:
        study="linkwork.pipeline.assumptions:assumptions",
        paper=lambda wildcards: wildcards.paper,
        cfg=lambda wildcards: assumptions_cfg(wildcards.paper),
    script:
        STUDY


REPORT_INPUTS = {
    "stiffness": paper_report("stiffness", result="results/stiffness/stiffness.nc"),
    "beatup": paper_report(
        "beatup", result="results/beatup/sixbar.nc", window="results/beatup/window.nc",
        accuracy="results/beatup/accuracy.nc", sley_pin="results/beatup/sley_pin.nc",
    ),
    "heald": paper_report("heald", result="results/heald/chain.nc", accuracy="results/heald/accuracy.nc", contact="results/heald/contact.nc"),
    "transplanter": paper_report(
        "transplanter", result="results/transplanter/ked.nc", optim="results/transplanter/optim.nc",
        at_published="results/transplanter/at_published.nc", accuracy="results/transplanter/accuracy.nc",
    ),
    "clearance": paper_report(
        "clearance", result="results/clearance/claims.nc", accuracy="results/clearance/accuracy.nc",
        scenes=expand("results/clearance/{variant}/{scene}.nc", variant=CLEARANCE_VARIANTS, scene=CLEARANCE_SCENES),
        sweep="results/sweeps/clearance.nc",
        **(CROSSCHECK_RESULTS if config["crosscheck"] else {}),
    ),
    "accuracy": {"result": "results/accuracy/summary.nc", "timings": "results/accuracy/timings.json", **(CROSSCHECK_WP if config["crosscheck"] else {})},
    "sweeps": {"result": "results/sweeps/clearance.nc", "heald": "results/sweeps/heald.nc"},
    # the index links to the paper reports but reads only their comparison files: it renders beside them
    "index": {
        **{f"comparison_{p}": f"results/{p}/comparison.csv" for p in PAPERS},
        **{f"findings_{p}": f"results/{p}/findings.nc" for p in PAPERS},
    },
}


def report_inputs(wildcards):
    notebook = f"reports/{wildcards.report}.py"
    return {
        "notebook": notebook,
        "template": "reports/templates/linkwork/index.html.j2",
        "code": code_of(notebook, RENDERER),
        **REPORT_INPUTS[wildcards.report],
    }


rule report:
    priority: lambda wildcards: REPORT_PRIORITY.get(wildcards.report, 0)
    input:
        unpack(report_inputs),
    output:
        report("results/reports/{report}.html", caption="../report/report.rst", category="Reports", labels={"report": "{report}"}),
    wildcard_constraints:
        report="|".join(REPORT_INPUTS),
    script:
        "../scripts/render_report.py"


rule readme_findings:
    input:
        **{f"findings_{p}": f"results/{p}/findings.nc" for p in PAPERS},
        **{f"comparison_{p}": f"results/{p}/comparison.csv" for p in PAPERS},
        code=code("linkwork.pipeline.readme"),
    output:
        "results/readme_findings.md",
    params:
        study="linkwork.pipeline.readme:generated",
        cfg={},
    script:
        STUDY
