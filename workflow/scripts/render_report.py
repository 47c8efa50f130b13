"""Execute a jupytext percent script and render it to self-contained HTML.

As a rule script: the notebook is ``input.notebook``; every other named input except ``code`` is passed
to the report by name.  By hand: ``render_report.py NOTEBOOK.py OUTPUT.html [--input KEY=PATH[,PATH...] ...]``.

The cells run in this process, in an IPython shell with the inline matplotlib backend (no kernel to start: a report is
one job and one process).  Inputs reach the report as absolute paths in the environment variable LINKWORK_REPORT (JSON:
{"inputs": {...}}); a list input is a list of paths.  A cell that raises stops the render with the cell and the error.
Code cells are hidden in the HTML; figures are embedded as data URIs at the figure's own size (the layout is
constrained, so IPython's default 'tight' bounding box, an extra pass over every artist's extent, adds nothing); with
LINKWORK_CHECK_FIGURES=1 (the tests) a figure that draws outside its canvas, or two of whose texts overlap, stops the
render (``=list``: every such problem is printed and the render goes on).  Cell ids are derived from
the notebook's path and the cell's position, so rendering the same report twice writes the same bytes.  The HTML is
written atomically.
"""

import argparse
import hashlib
import json
import os
import sys
import time
from pathlib import Path

SKIPPED = ("notebook", "code", "template")
TEMPLATE = "reports/templates/linkwork/index.html.j2"  # the project's nbconvert template (no scripts from the network)


class CellError(RuntimeError):
    """A report cell raised; the message holds the cell's first lines and the error."""


def _outputs(captured, nbformat) -> list:
    """nbformat outputs from IPython's captured stdout, stderr and rich displays, in that order."""
    out = []
    if captured.stdout:
        out.append(nbformat.v4.new_output("stream", name="stdout", text=captured.stdout))
    if captured.stderr:
        out.append(nbformat.v4.new_output("stream", name="stderr", text=captured.stderr))
    for rich in captured.outputs:
        out.append(nbformat.v4.new_output("display_data", data=rich.data, metadata=rich.metadata or {}))
    return out


#: Figures of the running cell that draw outside their canvas (filled only with LINKWORK_CHECK_FIGURES=1).
_OUTSIDE: list[str] = []
#: How far (inches) a figure's drawn extent may pass its canvas edge before the check calls it clipped.
CANVAS_SLACK_IN = 0.02


def thin_crowded_ticks(fig) -> None:
    """The house rule for tick labels: on an axis whose drawn tick labels run into each other (a log axis spanning
    less than a decade labels its minor ticks too), the minor labels go; the major ones stay."""
    from matplotlib.ticker import NullFormatter

    renderer = fig.canvas.get_renderer()
    for ax in fig.axes:
        for axis in (ax.xaxis, ax.yaxis):
            boxes = [
                label.get_window_extent(renderer)
                for tick in axis._update_ticks()
                for label in (tick.label1, tick.label2)
                if label.get_visible() and label.get_text().strip()
            ]
            if any(a.overlaps(b) for i, a in enumerate(boxes) for b in boxes[i + 1:]):
                axis.set_minor_formatter(NullFormatter())


def _figure_png(fig) -> str:
    """The figure as base64 PNG at its own size, no 'tight' extent pass (crowded tick labels thinned first); the
    canvas and text checks where asked for."""
    from IPython.core.pylabtools import print_figure

    fig.canvas.draw()
    thin_crowded_ticks(fig)
    png = print_figure(fig, fmt="png", bbox_inches=None, base64=True)
    if os.environ.get("LINKWORK_CHECK_FIGURES") in ("1", "list"):
        title = fig.get_suptitle() or (fig.axes[0].get_title() if fig.axes else "")
        drawn = fig.get_tightbbox(fig.canvas.get_renderer())
        width, height = fig.get_size_inches()
        if (
            drawn.x0 < -CANVAS_SLACK_IN
            or drawn.y0 < -CANVAS_SLACK_IN
            or drawn.x1 > width + CANVAS_SLACK_IN
            or drawn.y1 > height + CANVAS_SLACK_IN
        ):
            _OUTSIDE.append(
                f"figure {title!r} draws over ({drawn.x0:.2f}, {drawn.y0:.2f})-({drawn.x1:.2f}, {drawn.y1:.2f}) in, its"
                f" canvas is {width:.2f} x {height:.2f} in"
            )
        _OUTSIDE.extend(f"figure {title!r}: {clash}" for clash in overlapping_texts(fig))
    return png


#: How far (pixels at the figure's dpi) two texts' boxes may overlap before they count as overlapping: glyph boxes
#: include their line's ascent and descent, so neighbouring lines of one label touch without clashing.
OVERLAP_SLACK_PX = 1.0


def drawn_texts(fig) -> list:
    """The texts ``fig`` draws, non-empty and visible: its suptitle, texts and legends; per visible axes its titles,
    axis labels, offset texts, the labels of the ticks inside its view (an axis keeps labels of ticks beyond its limits
    that it does not draw), its legend and its annotations (those clipped to the axes only where inside it)."""
    renderer = fig.canvas.get_renderer()
    found = [fig._suptitle, *fig.texts, *(t for legend in fig.legends for t in legend.get_texts())]
    for ax in fig.axes:
        if not ax.get_visible():
            continue
        found += [ax.title, ax._left_title, ax._right_title]
        for axis in (ax.xaxis, ax.yaxis):
            found += [axis.label, axis.get_offset_text()]
            for tick in axis._update_ticks():
                found += [tick.label1, tick.label2]
        if ax.get_legend() is not None:
            found += list(ax.get_legend().get_texts())
        box = ax.get_window_extent(renderer)
        for text in ax.texts:
            if not text.get_clip_on() or box.overlaps(text.get_window_extent(renderer)):
                found.append(text)
    unique = list({id(t): t for t in found if t is not None}.values())  # the suptitle is also among fig.texts
    return [t for t in unique if t.get_visible() and t.get_text().strip() and t.get_alpha() != 0]


def overlapping_texts(fig) -> list[str]:
    """Every pair of texts ``fig`` draws (``drawn_texts``) whose boxes overlap by more than ``OVERLAP_SLACK_PX`` on both
    axes: text a reader cannot read at the figure's size."""
    from matplotlib.transforms import Bbox

    renderer = fig.canvas.get_renderer()
    boxes = []
    for text in drawn_texts(fig):
        box = text.get_window_extent(renderer)
        if text.axes is not None and text.get_clip_on() and text in text.axes.texts:  # drawn clipped to its axes
            box = Bbox.intersection(box, text.axes.get_window_extent(renderer))
        if box is not None and box.width > 0 and box.height > 0:
            boxes.append((text.get_text().strip(), box))
    clashes = []
    for i, (a, box_a) in enumerate(boxes):
        for b, box_b in boxes[i + 1:]:
            dx = min(box_a.x1, box_b.x1) - max(box_a.x0, box_b.x0)
            dy = min(box_a.y1, box_b.y1) - max(box_a.y0, box_b.y0)
            if dx > OVERLAP_SLACK_PX and dy > OVERLAP_SLACK_PX:
                clashes.append(f"texts {a[:40]!r} and {b[:40]!r} overlap")
    return clashes


def execute(nb, folder: Path) -> None:
    """Run every code cell of ``nb`` in a fresh IPython shell whose working folder is ``folder``."""
    import nbformat
    from IPython.core.interactiveshell import InteractiveShell
    from IPython.utils.capture import capture_output

    os.environ["MPLBACKEND"] = "module://matplotlib_inline.backend_inline"
    os.chdir(folder)
    sys.path.insert(0, str(folder))
    shell = InteractiveShell.instance()
    from matplotlib_inline.backend_inline import configure_inline_support

    configure_inline_support(shell, "module://matplotlib_inline.backend_inline")
    from matplotlib.figure import Figure

    shell.display_formatter.formatters["image/png"].for_type(Figure, _figure_png)
    for index, cell in enumerate(nb.cells):
        if cell.cell_type != "code":
            continue
        with capture_output() as captured:
            result = shell.run_cell(cell.source, store_history=False, silent=False)
        cell.outputs = _outputs(captured, nbformat)
        if _OUTSIDE and os.environ.get("LINKWORK_CHECK_FIGURES") == "list":  # every problem of every figure, printed
            print("\n".join(f"render_report: cell {index}: {problem}" for problem in _OUTSIDE), file=sys.stderr)
            _OUTSIDE.clear()
        if _OUTSIDE:
            raise CellError(f"cell {index}: " + "; ".join(_OUTSIDE))
        if not result.success:
            error = result.error_in_exec or result.error_before_exec
            if type(error).__name__ == "UnreadableResult":  # a corrupted input: its one line says how to rebuild it
                raise CellError(str(error))
            head = "\n".join(cell.source.splitlines()[:5])
            raise CellError(f"cell {index} failed:\n{head}\n...\n{type(error).__name__}: {error}")


def stable_ids(nb, name: str) -> None:
    """Cell ids from the report's name and the cell's position (nbformat's are random)."""
    for index, cell in enumerate(nb.cells):
        cell.id = hashlib.sha256(f"{name}:{index}".encode()).hexdigest()[:16]


def page_title(nb) -> str:
    """The page's title: the report's first heading (its markdown '# ...' line), without markdown emphasis."""
    for cell in nb.cells:
        if cell.cell_type == "markdown":
            for line in cell.source.splitlines():
                if line.startswith("# "):
                    return line[2:].replace("*", "").replace("`", "").strip()
    return "linkwork report"


#: Where a report asks for its table of contents (after its answer); elsewhere it goes before the first section.
CONTENTS_MARK = '<div class="contents-here"></div>'
#: The pages every page links to, after the papers' own (in the papers' order).
OTHER_PAGES = {"accuracy": "what accuracy costs", "sweeps": "parameter sweeps"}


def pages() -> dict[str, str]:
    """Every report page by name, with its link text: the index, each paper, then the pages across papers."""
    from linkwork.papers import PAPERS

    authors = {p: title.split(":")[0] for p, title in PAPERS.items()}  # 'Huang, Wu, Li 2022'
    return {"index": "index: does each paper hold up?", **{p: f"{p} ({authors[p]})" for p in PAPERS}, **OTHER_PAGES}


def finish_page(html: str, name: str) -> str:
    """The exported page made navigable: a bar linking the index and every other report, a table of contents of its
    sections (where the report marks it, else before its first section), and each figure's alt text from its caption
    (the 'Figure: ...' line after it; nbconvert's placeholder otherwise)."""
    from bs4 import BeautifulSoup

    soup = BeautifulSoup(html, "html.parser")
    main = soup.find("main") or soup.body
    bar = soup.new_tag("nav", attrs={"class": "site", "aria-label": "reports"})
    for page, text in pages().items():
        if page == name:
            link = soup.new_tag("strong")
        else:
            link = soup.new_tag("a", href=f"{page}.html")
        link.string = text
        bar.append(link)
    main.insert(0, bar)
    sections = [h for h in soup.find_all("h2") if h.get("id")]
    if sections:
        toc = soup.new_tag("nav", attrs={"class": "toc", "aria-label": "contents"})
        head = soup.new_tag("strong")
        head.string = "Contents"
        toc.append(head)
        items = soup.new_tag("ul")  # the sections number themselves
        for h in sections:
            item = soup.new_tag("li")
            link = soup.new_tag("a", href=f"#{h['id']}")
            link.string = h.get_text(" ", strip=True).rstrip("¶").strip()
            item.append(link)
            items.append(item)
        toc.append(items)
        mark = soup.find("div", class_="contents-here")
        (mark.replace_with(toc) if mark else sections[0].insert_before(toc))
    for img in soup.find_all("img"):
        caption = img.find_next(string=lambda s: s and s.strip().startswith("Figure:"))
        if caption is not None and caption.find_previous("img") is img:  # the caption under this figure
            text = caption.parent.get_text(" ", strip=True) if caption.parent else caption.strip()
            img["alt"] = text.removeprefix("Figure:").strip()
    return str(soup)


def render(notebook: Path, output: Path, inputs: dict, template: Path) -> None:
    import jupytext
    from nbconvert import HTMLExporter

    absolute = {
        k: [str(Path(p).resolve()) for p in v] if isinstance(v, list) else str(Path(v).resolve())
        for k, v in inputs.items()
    }
    os.environ["LINKWORK_REPORT"] = json.dumps({"inputs": absolute})
    output, template = output.resolve(), template.resolve()
    start = time.perf_counter()
    nb = jupytext.read(notebook)
    nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3", "language": "python"}
    print(f"render_report: executing {notebook} ...", flush=True)
    try:
        execute(nb, notebook.resolve().parent)
    except CellError as exc:
        sys.exit(f"render_report: {notebook}: {exc}")
    stable_ids(nb, notebook.name)
    nb.metadata["title"] = page_title(nb)  # nbconvert's page title (else "Notebook")
    exporter = HTMLExporter(
        template_name=template.parent.name, extra_template_basedirs=[str(template.resolve().parent.parent)],
        exclude_input=True, exclude_input_prompt=True, exclude_output_prompt=True,
    )
    html, _ = exporter.from_notebook_node(nb)
    html = finish_page(html, output.stem)
    from linkwork.pipeline.results import ResultWriteError, write_text

    try:
        write_text(html, output)  # atomic, with its checksum beside it; no temporary file left on failure
    except ResultWriteError as exc:
        sys.exit(f"render_report: {exc}")
    print(f"render_report: wrote {output.name} in {time.perf_counter() - start:.1f} s", flush=True)


def _cli() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("notebook", type=Path)
    parser.add_argument("output", type=Path)
    parser.add_argument("--input", action="append", default=[], help="KEY=PATH or KEY=PATH1,PATH2")
    args = parser.parse_args()
    inputs: dict = {}
    for item in args.input:
        key, sep, value = item.partition("=")
        if not sep:
            sys.exit(f"render_report: --input {item!r} is not KEY=PATH")
        inputs[key] = value.split(",") if "," in value else value
    render(args.notebook, args.output, inputs, Path(__file__).resolve().parents[2] / TEMPLATE)


if "snakemake" in globals():
    sm = snakemake  # noqa: F821
    render(
        Path(sm.input.notebook), Path(sm.output[0]), {k: v for k, v in sm.input.items() if k not in SKIPPED},
        Path(sm.input.template),
    )
    from linkwork.pipeline.results import finish_job

    finish_job()  # no interpreter teardown: the page is written and closed
elif __name__ == "__main__":
    _cli()
