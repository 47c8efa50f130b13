"""Pipeline plumbing beside the papers: config validation, results I/O with provenance, comparison
with published numbers and verdicts, sweeps, the accuracy summary, timing and code dependencies."""
