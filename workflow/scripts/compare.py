"""Rule <paper>_compare: result netCDF file(s) + published numbers -> comparison table (CSV), one block per model form."""

import pandas as pd
import xarray as xr
import yaml

from linkwork import results
from linkwork.compare import compare

section = snakemake.params.section  # noqa: F821
with open(snakemake.input.published) as fh:  # noqa: F821
    published = yaml.safe_load(fh)
paths = snakemake.input.results if "results" in snakemake.input.keys() else [snakemake.input.result]  # noqa: F821
datasets = []
for path in paths:
    with xr.open_dataset(path) as ds:
        datasets.append(ds.load())
ds = xr.merge(datasets, combine_attrs="drop")
# one comparison block per model variant: stiffness forms, heald models, clearance parameter variants
dim = next((d for d in ("form", "model", "variant") if d in ds.dims), None)
variants = [str(v) for v in ds[dim].values] if dim else [""]
table = pd.concat([compare(published, ds.sel({dim: v}) if dim else ds, model=v) for v in variants], ignore_index=True)
results.write_text(table.to_csv(index=False, float_format="%.10g"), snakemake.output[0])  # noqa: F821
print(table.groupby("model")["verdict"].value_counts().to_string(), flush=True)
