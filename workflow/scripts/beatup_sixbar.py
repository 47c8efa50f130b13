"""Rule beatup_sixbar: config section -> six-bar motion, dead centres, evidence columns -> sixbar.nc."""

from linkwork import results
from linkwork.beatup_dataset import sixbar_dataset

section = snakemake.params.section  # noqa: F821
print(f"beatup: six-bar on {section['grids']['paper_step_deg']:g} and {section['grids']['fine_step_deg']:g} deg grids", flush=True)
ds = sixbar_dataset(section)
ds.attrs.update(results.provenance("beatup", section, title="GN721 six-bar beating-up mechanism: sley motion", source=section["source"]))
results.write(ds, snakemake.output[0])  # noqa: F821
