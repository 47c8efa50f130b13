# Paper "heald": mechanical chains of a heald motion, joint forces with clearance.

# the chain's inputs; "drive" is the drive-frequency scenario, read by the chain, the comparison and the uncertainty
# study (the accuracy study and the sweep drive the chain at the shaft frequency: grid studies on its own axis)
HEALD_CHAIN = ["parameters", "excitation", "speeds"]
HEALD_MODEL = [*HEALD_CHAIN, "drive"]
UNCERTAINTY["heald"] = {"cfg": lambda index: section("heald", *HEALD_MODEL, "models", "uncertainty", design=True)}


def heald_sweep_cfg():
    """The paper's config values a point of the heald sweep reads (the swept clearance and reaction come as the
    point)."""
    swept = ("clearance_E", "clearance_F", "reaction_E")
    return section(
        "heald", *(f"parameters.{p}" for p in config["heald"]["parameters"] if p not in swept), "excitation", "speeds"
    )


SWEEP["heald"] = {
    "cfg": heald_sweep_cfg,
    "reference": lambda: {
        "clearance_m": config["heald"]["parameters"]["clearance_E"]["value"],
        "reaction_ratio_EF": config["heald"]["parameters"]["reaction_E"]["value"]
        / config["heald"]["parameters"]["reaction_F"]["value"],
    },
    # the gather draws the map's threshold from the published claim, and shows that the warp branch cannot change
    # Q_E, Q_F in model B (the paper's values it reads itself)
    "gather_inputs": lambda: {"published": "config/published/heald.yaml"},
    "gather_cfg": lambda: {"paper": heald_sweep_cfg()},
}


rule heald_chain:
    input:
        code=code("linkwork.papers.heald.studies"),
    output:
        "results/heald/chain.nc",
    params:
        study="linkwork.papers.heald.studies:chain",
        cfg=section(
            "heald", *HEALD_MODEL, "models", "sweeps", "cam", "cam.rise_fraction.range", "parameters.c_joint.range"
        ),
    script:
        STUDY


rule heald_accuracy:
    input:
        code=code("linkwork.papers.heald.accuracy"),
    output:
        result="results/heald/accuracy.nc",
        timings="results/heald/accuracy_timings.json",
    params:
        study="linkwork.papers.heald.accuracy:accuracy",
        cfg=section("heald", *HEALD_CHAIN, "accuracy"),
    script:
        STUDY


rule heald_compare:
    input:
        published="config/published/heald.yaml",
        chain="results/heald/chain.nc",
        accuracy="results/heald/accuracy.nc",
        uncertainty="results/heald/uncertainty.nc",
        code=code("linkwork.papers.heald.findings"),
    output:
        comparison_table("heald"),
        "results/heald/findings.nc",
    params:
        study="linkwork.papers.heald.findings:compare",
        cfg=section("heald", *HEALD_MODEL, "models", "loom_band_rpm", design=True),  # the flips read the ranges
    script:
        STUDY


rule heald_contact:
    input:
        code=code("linkwork.papers.heald.contact"),
    output:
        "results/heald/contact.nc",
    # one job of about a minute that the heald report waits for: among the first to start, not alone at the end
    priority: CHAIN_HEAD_PRIORITY
    params:
        study="linkwork.papers.heald.contact:study",
        # values and ranges of the parameters (a case sets some to a range's end); the drive's choice, not its labels
        cfg=section(
            "heald",
            "parameters",
            "drive.frequency.value",
            "cam.rise_fraction.value",
            "cam.harmonics",
            "cam.samples",
            "contact",
            design=True,
        ),
    script:
        STUDY


# the inputs of the paper's report (reports.smk renders it)
REPORT_INPUTS["heald"] = paper_report(
    "heald", result="results/heald/chain.nc", accuracy="results/heald/accuracy.nc", contact="results/heald/contact.nc"
)
