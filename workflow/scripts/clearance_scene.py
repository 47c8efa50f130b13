"""Rule clearance_scene[_tight]: one scene of one parameter variant -> results/clearance/<variant>/[tight/]<scene>.nc."""

from linkwork import results
from linkwork.clearance_dataset import scene_dataset

section = snakemake.params.section  # noqa: F821
variant, scene = snakemake.wildcards.variant, snakemake.wildcards.scene  # noqa: F821
spec = section["scenes"][scene]
kind = spec.get("integrator", "explicit")
integrator = section["integrators" if snakemake.params.tolerance == "pipeline" else "tight_integrators"][kind]  # noqa: F821
print(f"clearance: {variant}/{scene} ({', '.join(spec['effects']) or 'no effects'}; {integrator['method']})", flush=True)
ds = scene_dataset(section, variant, scene, integrator)
ds.attrs.update(results.provenance("clearance", section, title=f"Four-bar with clearance joints: {variant}, {scene}", source=section["source"], tolerance_set=snakemake.params.tolerance))  # noqa: F821
results.write(ds, snakemake.output[0])  # noqa: F821
