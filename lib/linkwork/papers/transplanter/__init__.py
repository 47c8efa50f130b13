"""Paper ``transplanter``: its title, source and place in the report order (found by ``linkwork.papers``)."""

TITLE = "Li, Xu 2001: elastodynamic design of a crank-rocker transplanter"
CITATION = (
    'Li Dewei, Xu Fengying, "Flexible dynamic synthesis on the linkage of high speed crank-rocker style '
    'rice seedling transplanter", Journal of South China Agricultural University 22(4):81-83, 2001 (seed '
    "003_0cfa70853744423c.txt)"
)
ORDER = 4
