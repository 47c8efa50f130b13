# Paper "transplanter": kineto-elastodynamics and penalty-function section optimisation.

TRANSPLANTER_MATERIAL = lambda *props: [f"materials.{config['transplanter']['material']['name']}.{p}" for p in props]
TRANSPLANTER_MODEL = [
    "crank_speed_rpm",
    "geometry",
    "material.name",
    *TRANSPLANTER_MATERIAL("youngs_modulus_Pa", "density_kg_m3"),
    "fe.element",
    "fe.elements_per_member",
    "fe.gravity_m_s2",
]
TRANSPLANTER_DYNAMIC = ["fe.damping_ratio", "fe.revolutions", "fe.substeps"]
TRANSPLANTER_COMPARED = [
    "fe.compared_solution",
    *TRANSPLANTER_DYNAMIC,
    "initial_diameters_m",
    "claims",
]  # the solution compared with the paper's numbers, the claims' measures
TRANSPLANTER_PROBLEM = [
    *TRANSPLANTER_MODEL,
    "material.safety_factor",
    *TRANSPLANTER_MATERIAL("yield_Pa"),
    "minimum_diameter_m",
    "fe.angle_step_deg",
    "optimization.angle_step_deg",
    "optimization.peak_spread_steps",
    "optimization.exchange_rounds",
    "optimization.reference_diameter_m",
]
UNCERTAINTY["transplanter"] = {  # its samples and its searches' evaluations start from our optimum
    "cfg": lambda index: section(
        "transplanter",
        *TRANSPLANTER_PROBLEM,
        *TRANSPLANTER_COMPARED,
        "initial_diameters_m",
        "fe.angle_step_deg",
        "optimization.slsqp_ftol",
        "uncertainty",
        design=True,
    ),
    "batch_inputs": lambda index: {
        "published": "config/published/transplanter.yaml",
        "optim": "results/transplanter/optim.nc",
    },
    "gather_inputs": lambda: {"optim": "results/transplanter/optim.nc"},
}


rule transplanter_optim:
    input:
        code=code("linkwork.papers.transplanter.studies"),
    output:
        "results/transplanter/optim.nc",
    priority: CHAIN_HEAD_PRIORITY
    params:
        study="linkwork.papers.transplanter.studies:optim",
        cfg=section("transplanter", *TRANSPLANTER_PROBLEM, "initial_diameters_m", "optimization"),
    script:
        STUDY


rule transplanter_ked:
    input:
        optim="results/transplanter/optim.nc",
        code=code("linkwork.papers.transplanter.studies"),
    output:
        "results/transplanter/ked.nc",
    params:
        study="linkwork.papers.transplanter.studies:ked_responses",
        cfg=section(
            "transplanter",
            *TRANSPLANTER_MODEL,
            *TRANSPLANTER_DYNAMIC,
            "initial_diameters_m",
            "fe.angle_step_deg",
            "fe.resonance_warning_ratio",
            "fe.damping_ratio.range",
            "fe.newmark_study",
            "fe.damping_study",
        ),
    script:
        STUDY


rule transplanter_at_published:
    # comparison data: our model evaluated at the paper's optimum (reads config/published/)
    input:
        published="config/published/transplanter.yaml",
        code=code("linkwork.papers.transplanter.published_point"),
    output:
        "results/transplanter/at_published.nc",
    params:
        study="linkwork.papers.transplanter.published_point:at_published",
        cfg=section(
            "transplanter",
            *TRANSPLANTER_PROBLEM,
            *TRANSPLANTER_COMPARED,
            "numerical_checks",
            "missing_load",
            "optimization.r0",
            "optimization.r_factor",
            "optimization.iterations",
            "optimization.gradient_step_m",
        ),
    script:
        STUDY


rule transplanter_accuracy:
    input:
        code=code("linkwork.papers.transplanter.accuracy"),
    output:
        result="results/transplanter/accuracy.nc",
        timings="results/transplanter/accuracy_timings.json",
    priority: LONG_JOB_PRIORITY
    params:
        study="linkwork.papers.transplanter.accuracy:accuracy",
        cfg=section("transplanter", *TRANSPLANTER_MODEL, "initial_diameters_m", "fe.angle_step_deg", "accuracy"),
    script:
        STUDY


rule transplanter_compare:
    input:
        published="config/published/transplanter.yaml",
        optim="results/transplanter/optim.nc",
        at_published="results/transplanter/at_published.nc",
        ked="results/transplanter/ked.nc",
        accuracy="results/transplanter/accuracy.nc",
        uncertainty="results/transplanter/uncertainty.nc",
        code=code("linkwork.papers.transplanter.findings"),
    output:
        comparison_table("transplanter"),
        "results/transplanter/findings.nc",
    params:
        study="linkwork.papers.transplanter.findings:compare",
        cfg=section("transplanter", "minimum_diameter_m"),
    script:
        STUDY


# the accuracy report shows the Newmark step study beside the other methods
ACCURACY_REPORT_INPUTS["newmark"] = "results/transplanter/ked.nc"

# the inputs of the paper's report (reports.smk renders it)
REPORT_INPUTS["transplanter"] = paper_report(
    "transplanter",
    result="results/transplanter/ked.nc",
    optim="results/transplanter/optim.nc",
    at_published="results/transplanter/at_published.nc",
    accuracy="results/transplanter/accuracy.nc",
)
