"""Paper ``transplanter``: its title, source and place in the report order (found by ``linkwork.papers``)."""

TITLE = "Li, Xu 2001: elastodynamic design of a crank-rocker transplanter"
CITATION = (
    'Li Dewei, Xu Fengying, "Flexible dynamic synthesis on the linkage of high speed crank-rocker style '
    'rice seedling transplanter", Journal of South China Agricultural University 22(4):81-83, 2001 (seed '
    "003_0cfa70853744423c.txt)"
)
ORDER = 4
#: The terms of the paper's answer, for a reader who has not read the paper (the index shows them).
GLOSSARY = {
    "x- and y-deflection": "the planting-arm tip's elastic displacement (the paper's Ux, Uy)",
    "optimiser": "the paper's SUMT method: a sequence of penalised minimisations with a falling penalty factor",
}
