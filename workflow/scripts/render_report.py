"""Execute a jupytext percent script and render it to self-contained HTML.

As a rule script: the notebook is ``input.notebook``; every other named input except ``renderer`` and
``code`` is passed to the report by name.  By hand:
``render_report.py NOTEBOOK.py OUTPUT.html [--input KEY=PATH[,PATH...] ...]``.

Inputs are exported to the kernel as absolute paths in the environment variable LINKWORK_REPORT
(JSON: {"inputs": {...}}), because the kernel runs in the notebook's folder; a list input is a list of
paths.  Code cells are hidden in the HTML; figures are embedded as data URIs.  The kernel is this
interpreter (jupyter_client maps the 'python3' kernel to sys.executable), so an unactivated
environment works.  The HTML is written atomically.
"""

import argparse
import json
import os
import sys
import time
from pathlib import Path

SKIPPED = ("notebook", "renderer", "code")


def render(notebook: Path, output: Path, inputs: dict[str, str | list[str]], timeout: int = 600) -> None:
    import jupytext
    from nbclient import NotebookClient
    from nbconvert import HTMLExporter

    absolute = {k: [str(Path(p).resolve()) for p in v] if isinstance(v, list) else str(Path(v).resolve()) for k, v in inputs.items()}
    os.environ["LINKWORK_REPORT"] = json.dumps({"inputs": absolute})
    os.environ.setdefault("MPLBACKEND", "module://matplotlib_inline.backend_inline")
    start = time.perf_counter()
    nb = jupytext.read(notebook)
    nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3", "language": "python"}
    print(f"render_report: executing {notebook} ...", flush=True)
    NotebookClient(nb, timeout=timeout, kernel_name="python3", resources={"metadata": {"path": str(notebook.parent.resolve())}}).execute()
    html, _ = HTMLExporter(exclude_input=True, exclude_input_prompt=True, exclude_output_prompt=True).from_notebook_node(nb)
    output.parent.mkdir(parents=True, exist_ok=True)
    tmp = output.with_name(output.name + ".tmp")
    tmp.write_text(html, encoding="utf-8")
    os.replace(tmp, output)
    print(f"render_report: wrote {output} in {time.perf_counter() - start:.1f} s", flush=True)


def _cli() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("notebook", type=Path)
    parser.add_argument("output", type=Path)
    parser.add_argument("--input", action="append", default=[], help="KEY=PATH or KEY=PATH1,PATH2")
    args = parser.parse_args()
    inputs: dict[str, str | list[str]] = {}
    for item in args.input:
        key, sep, value = item.partition("=")
        if not sep:
            sys.exit(f"render_report: --input {item!r} is not KEY=PATH")
        inputs[key] = value.split(",") if "," in value else value
    render(args.notebook, args.output, inputs)


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    render(Path(sm.input.notebook), Path(sm.output[0]), {k: v for k, v in sm.input.items() if k not in SKIPPED})
elif __name__ == "__main__":
    _cli()
