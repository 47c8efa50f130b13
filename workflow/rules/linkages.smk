# Linkages of your own (config `linkages`): each a scene written in config, run by the shared multibody engine.

LINKAGES = list(config.get("linkages") or {})


rule linkage:
    input:
        code=code("linkwork.pipeline.linkages"),
    output:
        "results/linkages/{name}.nc",
    wildcard_constraints:
        name="|".join(LINKAGES) or "(?!)",
    params:
        study="linkwork.pipeline.linkages:study",
        paper="linkages",
        cfg=lambda wc: config["linkages"][wc.name],
        args=lambda wc: {"name": wc.name},
    script:
        STUDY
