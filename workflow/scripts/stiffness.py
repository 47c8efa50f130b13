"""Rule stiffness: config section -> K_h, K_c, beta, gamma -> results/stiffness/stiffness.nc."""

from linkwork import results
from linkwork.stiffness_dataset import build_dataset

section = snakemake.params.section  # noqa: F821 (provided by snakemake)
print(
    f"stiffness: {len(section['forms'])} forms on {section['grids']['paper_step_deg']:g} deg "
    f"and {section['grids']['fine_step_deg']:g} deg grids",
    flush=True,
)
ds = build_dataset(section)
ds.attrs.update(
    results.provenance(
        "stiffness",
        section,
        title="Equivalent stiffness of the needle crank-rocker (energy method)",
        source=section["source"],
        assembly_tol=section["numerics"]["assembly_tol"],
    )
)
results.write(ds, snakemake.output[0])  # noqa: F821
