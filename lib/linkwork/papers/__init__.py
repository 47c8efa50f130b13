"""The papers this project re-derives: one package per paper, found by looking, in report order.

Each package holds its model, its config adapter (``adapter``), its studies (config -> result Datasets, ``studies``),
its physical config checks (``checks``) and, where published numbers are needed to state a finding, its findings
(``findings``).  Papers import engines, never each other.  A package is a paper when its ``__init__`` declares
``TITLE`` (one line), ``CITATION`` (authors, title, journal; DOI where it has one; the seed file of its text) and
``ORDER`` (its place among the reports), where its comparison has model variants ``LABELS`` (variant -> what it
is, in a few words: the index defines the labels it shows), and ``GLOSSARY`` (term of its answer -> its meaning, for
a reader who has not read the paper): adding a paper edits no shared file.  ``PAPERS`` and
``CITATIONS`` are the one list of papers (rules, index and README read them).  Standard library only.

The packages are found when ``PAPERS`` or ``CITATIONS`` is first read, not when a paper's module is imported (a paper
imports no other paper).  linkwork-deps: PAPERS CITATIONS import every subpackage (linkwork.pipeline.deps: a module that
imports these names has every paper package's __init__ in its closure)
"""

import importlib
import pkgutil


def _declared() -> list[tuple[int, str, str, str]]:
    """(order, name, title, citation) of every paper package below this one, in report order."""
    found = []
    for info in pkgutil.iter_modules(__path__):
        if info.ispkg:
            package = importlib.import_module(f"{__name__}.{info.name}")
            if hasattr(package, "TITLE"):
                found.append((package.ORDER, info.name, package.TITLE, package.CITATION))
    return sorted(found)


def __getattr__(name: str):
    """``PAPERS`` (name -> title, in report order), ``CITATIONS`` (name -> the paper's source and the seed file of
    its text), ``LABELS`` (name -> its model variants' labels in words) and ``GLOSSARY`` (name -> the terms of its
    answer in words), found on first reading."""
    if name not in ("PAPERS", "CITATIONS", "LABELS", "GLOSSARY"):
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    found = _declared()
    globals()["PAPERS"] = {paper: title for _, paper, title, _ in found}
    globals()["CITATIONS"] = {paper: citation for _, paper, _, citation in found}
    for attribute in ("LABELS", "GLOSSARY"):
        globals()[attribute] = {
            paper: dict(getattr(importlib.import_module(f"{__name__}.{paper}"), attribute, {}))
            for _, paper, _, _ in found
        }
    return globals()[name]
