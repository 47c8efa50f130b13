# Paper "beatup": six-bar beating-up mechanism kinematics (Table 1) and the weft window vs a four-bar.

# The six-bar without its crank (the window study scales the crank to comparison.scaled_crank_m).
SIXBAR_FRAME = [
    f"sixbar.{k}"
    for k in (
        "l2_m",
        "l3_m",
        "l4_m",
        "l5_m",
        "l6_m",
        "l7_m",
        "theta4_deg",
        "theta7_deg",
        "branch_rocker",
        "branch_sley",
    )
]
# The whole mechanism; the crank sense (a named scenario) is read only where a sense-dependent number is: its value
# by the motion study, its choices and labels by the comparison (which computes both senses), never its reason.
SIXBAR_MECHANISM = ["sixbar.l1_m", *SIXBAR_FRAME]
SENSE_CHOICE = ["sixbar.crank_sense.value", "sixbar.crank_sense.choices", "sixbar.crank_sense.choice_labels"]
UNCERTAINTY["beatup"] = {
    "cfg": lambda index: section(
        "beatup",
        "sixbar",
        "printed_rounding",
        "grids",
        "numerics.scan_points",
        "numerics.root_xtol_rad",
        "uncertainty",
        design=True,
    ),
}


rule beatup_sixbar:
    input:
        code=code("linkwork.papers.beatup.studies"),
    output:
        "results/beatup/sixbar.nc",
    params:
        study="linkwork.papers.beatup.studies:sixbar",
        cfg=section("beatup", *SIXBAR_MECHANISM, "sixbar.crank_sense.value", "closed_form_signs", "grids", "numerics"),
    script:
        STUDY


rule beatup_window:
    input:
        code=code("linkwork.papers.beatup.studies"),
    output:
        "results/beatup/window.nc",
    params:
        study="linkwork.papers.beatup.studies:window",
        cfg=section(
            "beatup",
            *SIXBAR_FRAME,
            "comparison.stroke_m",
            "comparison.scaled_crank_m",
            "fourbar",
            "sweep",
            "grids.fine_step_deg",
        ),
    script:
        STUDY


rule beatup_sley_pin:
    input:
        code=code("linkwork.papers.beatup.sley_pin"),
    output:
        "results/beatup/sley_pin.nc",
    priority: LONG_JOB_PRIORITY
    params:
        study="linkwork.papers.beatup.sley_pin:study",
        cfg=section("beatup", *SIXBAR_MECHANISM, "sixbar.crank_sense.value", "fourbar", "sley_pin"),
    script:
        STUDY


rule beatup_accuracy:
    input:
        code=code("linkwork.papers.beatup.accuracy"),
    output:
        result="results/beatup/accuracy.nc",
        timings="results/beatup/accuracy_timings.json",
    params:
        study="linkwork.papers.beatup.accuracy:accuracy",
        cfg=section("beatup", *SIXBAR_MECHANISM, "accuracy"),
    script:
        STUDY


rule beatup_compare:
    input:
        published="config/published/beatup.yaml",
        sixbar="results/beatup/sixbar.nc",
        window="results/beatup/window.nc",
        uncertainty="results/beatup/uncertainty.nc",
        code=code("linkwork.papers.beatup.findings"),
    output:
        comparison_table("beatup"),
        "results/beatup/findings.nc",
    params:
        study="linkwork.papers.beatup.findings:compare",
        cfg=section(
            "beatup",
            *SIXBAR_MECHANISM,
            *SENSE_CHOICE,
            "printed_rounding",
            "table1_fit",
            "grids.paper_step_deg",
            "comparison.fourbar_window_band_deg",
            "numerics.scan_points",
            "numerics.root_xtol_rad",
        ),
    script:
        STUDY


# the inputs of the paper's report (reports.smk renders it)
REPORT_INPUTS["beatup"] = paper_report(
    "beatup",
    result="results/beatup/sixbar.nc",
    window="results/beatup/window.nc",
    accuracy="results/beatup/accuracy.nc",
    sley_pin="results/beatup/sley_pin.nc",
)
