"""Rule transplanter_ked: config section + our optimum -> KED responses (quasi-static, dynamic) -> ked.nc."""

import xarray as xr

from linkwork import results
from linkwork.transplanter_dataset import ked_dataset

section = snakemake.params.section  # noqa: F821
with xr.open_dataset(snakemake.input.optim) as optim:  # noqa: F821
    optimal = optim.d_opt.values
print(f"transplanter: KED for initial and optimal diameters, quasi-static and dynamic ({section['fe']['revolutions']} revolutions)", flush=True)
ds = ked_dataset(section, optimal)
ds.attrs.update(results.provenance("transplanter", section, title="Kineto-elastodynamics of the transplanter", source=section["source"]))
results.write(ds, snakemake.output[0])  # noqa: F821
