"""Rule transplanter_optim: config section -> SUMT iterates and SLSQP cross-check -> optim.nc."""

from linkwork import results
from linkwork.transplanter_dataset import optim_dataset

section = snakemake.params.section  # noqa: F821
opt = section["optimization"]
print(f"transplanter: SUMT over {opt['iterations']} penalty factors from r0 = {opt['r0']:g} (about 30 s), then SLSQP", flush=True)
ds = optim_dataset(section)
ds.attrs.update(results.provenance("transplanter", section, title="Section optimisation (mixed penalty SUMT)", source=section["source"]))
results.write(ds, snakemake.output[0])  # noqa: F821
