"""Script of every study rule: call ``params.study`` ("module:function") with the rule's config values (``params.cfg``),
its arguments (``params.args``) and its named inputs (read by file type), and write what it returns to the rule's
outputs in order: a Dataset to netCDF (with provenance), a DataFrame to CSV, a dict to JSON, each with its checksum
beside it (``results.write``); an input that does not match its checksum, or an output that cannot be written, stops the
job with one line naming the file, and a config value the study cannot go on with (``ConfigError``) with one line naming
the key.  Prints one line when it starts and one when it has written its outputs.
"""

import importlib
import inspect
import json
import sys
import time

from linkwork.pipeline import results
from linkwork.pipeline.errors import ConfigError

sm = snakemake  # noqa: F821 (provided by snakemake)
module_name, _, function_name = sm.params.study.partition(":")
function = getattr(importlib.import_module(module_name), function_name)
cfg = sm.params.cfg
args = dict(getattr(sm.params, "args", None) or {})
paper = getattr(sm.params, "paper", None) or (
    module_name.split(".")[2] if module_name.startswith("linkwork.papers.") else module_name.split(".")[-1]
)
label = f"{sm.rule}" + (f" ({', '.join(f'{k}={v}' for k, v in sm.wildcards.items())})" if len(sm.wildcards) else "")
print(f"{label}: {(function.__doc__ or function_name).strip().splitlines()[0]}", flush=True)
start = time.perf_counter()
try:
    inputs = {
        name: [results.load(p) for p in value] if isinstance(value, list) else results.load(value)
        for name, value in sm.input.items()
        if name != "code"
    }
except results.UnreadableResult as exc:
    sys.exit(f"{label}: {exc}")
# a study that can use the rule's threads gets them as worker processes (not provenance: the result does not depend on
# them)
workers = {"workers": sm.threads} if "workers" in inspect.signature(function).parameters else {}
try:
    returned = function(cfg, **args, **workers, **inputs)
except ConfigError as exc:  # a config value the study found it cannot go on with: one line naming the key
    sys.exit(f"{label}: {exc}")
outputs = returned if isinstance(returned, tuple) else (returned,)
if len(outputs) != len(sm.output):
    sys.exit(f"{label}: {module_name}:{function_name} returned {len(outputs)} objects for {len(sm.output)} outputs")
extra = {f"argument_{k}": json.dumps(v, sort_keys=True) for k, v in args.items()}
for obj, path in zip(outputs, sm.output):
    try:
        if hasattr(obj, "to_netcdf"):
            obj.attrs.update(results.provenance(paper, cfg, study=sm.params.study, **extra))
            results.write(obj, path)
        elif hasattr(obj, "to_csv"):
            results.write_text(obj.to_csv(index=False, float_format="%.10g"), path)
        elif isinstance(obj, str):
            results.write_text(obj, path)
        else:
            results.write_text(json.dumps(obj, indent=2, sort_keys=True), path)
    except (
        results.NonFiniteResult,
        results.ResultWriteError,
    ) as exc:  # one line: the variable, or the file and the cure
        sys.exit(f"{label}: {exc}")
print(f"{label}: wrote {', '.join(sm.output)} in {time.perf_counter() - start:.1f} s", flush=True)
results.finish_job()  # no interpreter teardown: the outputs are written and closed
