# Reports: jupytext percent scripts executed and rendered to self-contained HTML.
# REPORT_INPUTS (common.smk: each paper's rule file registers its report's, this file the reports across papers) is
# the one place that says which files a report reads; the renderer passes them by name.
# Wall times (the *timings.json side files) are read by the accuracy report alone (MEASURED_REPORTS): every other
# report is a function of deterministic results and renders to the same bytes on every rerun and every machine.


rule assumptions:
    input:
        code=code("linkwork.pipeline.assumptions"),
    output:
        "results/{paper}/assumptions.nc",
    wildcard_constraints:
        paper="|".join(PAPERS),
    # the one rule that reads the reasons: an edit of a reason reruns this step and its paper's report, nothing else
    priority: GATE_PRIORITY
    params:
        study="linkwork.pipeline.assumptions:assumptions",
        paper=lambda wildcards: wildcards.paper,
        cfg=lambda wildcards: assumptions_cfg(wildcards.paper),
    script:
        STUDY


# the reports across papers (each paper's own report is registered by its rule file)
REPORT_INPUTS["accuracy"] = {
    "result": "results/accuracy/summary.nc",
    "timings": "results/accuracy/timings.json",
    **ACCURACY_REPORT_INPUTS,
}
REPORT_INPUTS["sweeps"] = {"result": "results/sweeps/clearance.nc", "heald": "results/sweeps/heald.nc"}
# the index links to the paper reports but reads only their comparison files: it renders beside them
REPORT_INPUTS["index"] = {
    **{f"comparison_{p}": f"results/{p}/comparison.csv" for p in PAPERS},
    **{f"findings_{p}": f"results/{p}/findings.nc" for p in PAPERS},
}


# Each paper's statements (its findings as text with placeholders and conditions, linkwork.pipeline.statements),
# rendered by its report, the index and the README block: an edit of a statement re-renders only those.
STATEMENTS = {p: f"lib/linkwork/papers/{p}/statements.yaml" for p in PAPERS}


def report_inputs(wildcards):
    notebook = f"reports/{wildcards.report}.py"
    statements = (
        list(STATEMENTS.values()) if wildcards.report == "index" else [STATEMENTS[wildcards.report]]
        if wildcards.report in STATEMENTS else []
    )
    return {
        "notebook": notebook,
        "template": "reports/templates/linkwork/index.html.j2",
        "code": code_of(notebook, RENDERER),
        **({"statements": statements} if statements else {}),
        **REPORT_INPUTS[wildcards.report],
    }


rule report:
    input:
        unpack(report_inputs),
    output:
        report(
            "results/reports/{report}.html",
            caption="../report/report.rst",
            category="Reports",
            labels={"report": "{report}"},
        ),
    wildcard_constraints:
        report="|".join(REPORT_INPUTS),
    priority: lambda wildcards: REPORT_PRIORITY.get(wildcards.report, 0)
    script:
        "../scripts/render_report.py"


rule readme_findings:
    input:
        **{f"findings_{p}": f"results/{p}/findings.nc" for p in PAPERS},
        **{f"comparison_{p}": f"results/{p}/comparison.csv" for p in PAPERS},
        statements=list(STATEMENTS.values()),
        code=code("linkwork.project.readme"),
    output:
        "results/readme_findings.md",
    params:
        study="linkwork.project.readme:generated",
        cfg={},
    script:
        STUDY
