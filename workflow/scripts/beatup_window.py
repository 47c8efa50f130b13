"""Rule beatup_window: config section -> reed displacement, weft windows and sweeps -> window.nc."""

from linkwork import results
from linkwork.beatup_dataset import window_dataset

section = snakemake.params.section  # noqa: F821
print(f"beatup: weft windows over {len(section['sweep']['arm_to_crank'])} L/R values x {section['sweep']['weft_clearance_m']['num']} S_w values", flush=True)
ds = window_dataset(section)
ds.attrs.update(results.provenance("beatup", section, title="Six-bar vs four-bar weft window", source=section["source"]))
results.write(ds, snakemake.output[0])  # noqa: F821
