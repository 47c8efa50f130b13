# Paper "stiffness": equivalent stiffness of the needle crank-rocker (energy method).

STIFFNESS_MODEL = ["linkage", "members", "numerics.assembly_tol"]


rule stiffness:
    input:
        code=code("linkwork.papers.stiffness.studies"),
    output:
        "results/stiffness/stiffness.nc",
    params:
        study="linkwork.papers.stiffness.studies:stiffness",
        cfg=section("stiffness", *STIFFNESS_MODEL, "forms", "grids"),
    script:
        STUDY


rule stiffness_accuracy:
    input:
        code=code("linkwork.papers.stiffness.accuracy"),
    output:
        result="results/stiffness/accuracy.nc",
        timings="results/stiffness/accuracy_timings.json",
    params:
        study="linkwork.papers.stiffness.accuracy:quadrature_accuracy",
        cfg=section("stiffness", *STIFFNESS_MODEL, "grids.fine_step_deg", "accuracy"),
    script:
        STUDY


rule stiffness_compare:
    input:
        published="config/published/stiffness.yaml",
        result="results/stiffness/stiffness.nc",
        code=code("linkwork.papers.stiffness.findings"),
    output:
        comparison_table("stiffness"),
        "results/stiffness/findings.nc",
    params:
        study="linkwork.papers.stiffness.findings:compare",
        cfg=section(
            "stiffness", "members.OA.youngs_modulus_Pa", "steel_youngs_modulus_Pa", "axial_negligible_share", "linkage"
        ),
    script:
        STUDY


# the inputs of the paper's report (reports.smk renders it)
REPORT_INPUTS["stiffness"] = paper_report("stiffness", result="results/stiffness/stiffness.nc")
