"""Rule heald_accuracy: frequency-grid resolution vs peak-force error (netCDF) and time (JSON side file)."""

import json

from linkwork import results
from linkwork.heald_dataset import accuracy_dataset

section = snakemake.params.section  # noqa: F821
print(f"heald: grid-resolution study over {section['accuracy']['points']} points", flush=True)
ds, timings = accuracy_dataset(section)
ds.attrs.update(results.provenance("heald", section, title="Accuracy vs cost: frequency-grid resolution near a resonance"))
results.write(ds, snakemake.output.result)  # noqa: F821
results.write_text(json.dumps(timings, indent=2), snakemake.output.timings)  # noqa: F821
