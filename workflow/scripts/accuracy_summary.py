"""Rule accuracy_summary: every method's accuracy-vs-cost points -> summary.nc (errors) + timings.json."""

import json

import xarray as xr

from linkwork import results
from linkwork.accuracy_summary import collect, stiffness_points

inp = snakemake.input  # noqa: F821
cfg = snakemake.params.config  # noqa: F821


def load(nc, js):
    with xr.open_dataset(nc) as ds:
        return ds.load(), json.loads(open(js).read())


print("accuracy: gathering the studies of every paper, timing the stiffness quadrature", flush=True)
stiff = stiffness_points(cfg["stiffness"], snakemake.params.panels, snakemake.params.repeats)  # noqa: F821
ds, times = collect(*load(inp.beatup, inp.beatup_t), *load(inp.transplanter, inp.transplanter_t), *load(inp.clearance, inp.clearance_t),
                    *load(inp.heald, inp.heald_t), cfg, stiff)
ds.attrs.update(results.provenance("accuracy", {"panels": snakemake.params.panels}, title="What accuracy costs in time, per numerical method"))  # noqa: F821
results.write(ds, snakemake.output.result)  # noqa: F821
results.write_text(json.dumps({"method": "median of repeats after a warm-up, time.perf_counter, measured inside each study", "seconds": times}, indent=2), snakemake.output.timings)  # noqa: F821
