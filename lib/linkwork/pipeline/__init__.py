"""The toolkit the papers use: results I/O with provenance and checksums, comparison with published numbers and
verdicts, input uncertainty and bounded searches, sweeps, the accuracy summary, timing, code dependencies and the YAML
reader.  It knows no paper (what does is ``linkwork.project``)."""
