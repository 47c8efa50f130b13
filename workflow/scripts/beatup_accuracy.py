"""Rule beatup_accuracy: analytic vs finite-difference derivatives, error (netCDF) and time (JSON side file)."""

import json

from linkwork import results
from linkwork.beatup_dataset import accuracy_dataset

section = snakemake.params.section  # noqa: F821
print(f"beatup: finite-difference step sweep over {len(section['accuracy']['fd_steps_deg'])} steps", flush=True)
ds, timings = accuracy_dataset(section)
ds.attrs.update(results.provenance("beatup", section, title="Accuracy vs cost: analytic vs finite-difference derivatives"))
results.write(ds, snakemake.output.result)  # noqa: F821
results.write_text(json.dumps(timings, indent=2), snakemake.output.timings)  # noqa: F821
