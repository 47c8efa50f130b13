"""Rule <paper>_accuracy: the paper's accuracy-vs-cost study -> error (netCDF) and time (JSON side file).

The study is ``accuracy_dataset(section)`` of ``linkwork.<paper>_dataset``; its timings go to a side
file so that the netCDF stays byte-identical between runs.
"""

import importlib
import json

from linkwork import results

paper = snakemake.params.paper  # noqa: F821
section = snakemake.params.section  # noqa: F821
study = importlib.import_module(f"linkwork.{paper}_dataset").accuracy_dataset
print(f"{paper}: accuracy-vs-cost study", flush=True)
ds, timings = study(section)
ds.attrs.update(results.provenance(paper, section, title=f"Accuracy vs cost ({paper})"))
results.write(ds, snakemake.output.result)  # noqa: F821
results.write_text(json.dumps(timings, indent=2), snakemake.output.timings)  # noqa: F821
