"""Rule heald_chain: config section -> chain responses of models A and B, resonances, sweeps -> chain.nc."""

from linkwork import results
from linkwork.heald_dataset import chain_dataset

section = snakemake.params.section  # noqa: F821
print(f"heald: models {section['models']} over {section['speeds']['points']} frequencies, with parameter sweeps", flush=True)
ds = chain_dataset(section)
ds.attrs.update(results.provenance("heald", section, title="Heald motion as mechanical chains", source=section["source"]))
results.write(ds, snakemake.output[0])  # noqa: F821
