"""Execute a jupytext percent script and render it to self-contained HTML.

Usage: render_report.py NOTEBOOK.py OUTPUT.html [--input KEY=PATH ...] [--param KEY=JSON ...]

Inputs are exported to the kernel as absolute paths in the environment variable
LINKWORK_REPORT (JSON: {"inputs": {...}, "params": {...}}), because the kernel
runs in the notebook's folder.  Code cells are hidden in the HTML; figures are
embedded as data URIs.  The HTML is written atomically.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path

import jupytext
from nbclient import NotebookClient
from nbconvert import HTMLExporter


def _pairs(items: list[str], what: str) -> dict[str, str]:
    out = {}
    for item in items:
        key, sep, value = item.partition("=")
        if not sep:
            sys.exit(f"render_report: {what} {item!r} is not KEY=VALUE")
        out[key] = value
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("notebook", type=Path)
    parser.add_argument("output", type=Path)
    parser.add_argument("--input", action="append", default=[])
    parser.add_argument("--param", action="append", default=[])
    parser.add_argument("--timeout", type=int, default=600, help="per-cell timeout (s)")
    args = parser.parse_args()

    inputs = {k: str(Path(v).resolve()) for k, v in _pairs(args.input, "--input").items()}
    params = {k: json.loads(v) for k, v in _pairs(args.param, "--param").items()}
    os.environ["LINKWORK_REPORT"] = json.dumps({"inputs": inputs, "params": params})
    os.environ.setdefault("MPLBACKEND", "module://matplotlib_inline.backend_inline")

    start = time.perf_counter()
    nb = jupytext.read(args.notebook)
    nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3", "language": "python"}
    print(f"render_report: executing {args.notebook} ...", flush=True)
    NotebookClient(
        nb, timeout=args.timeout, kernel_name="python3", resources={"metadata": {"path": str(args.notebook.parent.resolve())}}
    ).execute()
    html, _ = HTMLExporter(exclude_input=True, exclude_input_prompt=True, exclude_output_prompt=True).from_notebook_node(nb)

    args.output.parent.mkdir(parents=True, exist_ok=True)
    tmp = args.output.with_name(args.output.name + ".tmp")
    tmp.write_text(html, encoding="utf-8")
    os.replace(tmp, args.output)
    print(f"render_report: wrote {args.output} in {time.perf_counter() - start:.1f} s", flush=True)


if __name__ == "__main__":
    main()
