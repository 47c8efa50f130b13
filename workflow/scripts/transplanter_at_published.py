"""Rule transplanter_at_published: our model at the paper's optimum, for comparison only -> at_published.nc.

The published diameters and SS are read from config/published/ to evaluate our model at the paper's
point; nothing here feeds our own optimum.
"""

import numpy as np
import yaml

from linkwork import results
from linkwork.transplanter_dataset import published_point_dataset

section = snakemake.params.section  # noqa: F821
with open(snakemake.input.published) as fh:  # noqa: F821
    published = yaml.safe_load(fh)
ss = next(q["value"] for q in published["quantities"] if q["id"] == "SS")
print("transplanter: our model at the published optimum (comparison data)", flush=True)
ds = published_point_dataset(section, np.array(published["optimum_diameters_mm"], dtype=float), float(ss))
ds.attrs.update(results.provenance("transplanter", section, title="Our model at the published optimum (comparison)", source=section["source"]))
results.write(ds, snakemake.output[0])  # noqa: F821
