"""Rule sweep_point: one grid point of a sweep -> results/sweeps/<sweep>/point_<i>.nc."""

from linkwork import results
from linkwork.sweeps import point_dataset

sweep, index = snakemake.wildcards.sweep, int(snakemake.wildcards.index)  # noqa: F821
print(f"sweep {sweep}: point {index}", flush=True)
ds = point_dataset(snakemake.params.config, snakemake.params.sweeps, sweep, index)  # noqa: F821
ds.attrs.update(results.provenance(sweep, {"point": index, "sweeps": snakemake.params.sweeps[sweep]}, title=f"{sweep} sweep, point {index}"))  # noqa: F821
results.write(ds, snakemake.output[0])  # noqa: F821
