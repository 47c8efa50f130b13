"""Paper ``stiffness``: its title, source and place in the report order (found by ``linkwork.papers``)."""

TITLE = "Huang, Wu, Li 2022: equivalent stiffness of a coupled four-bar (energy method)"
CITATION = (
    'Huang Shuang, Wu Xin, Li Peixing, "Equivalent Stiffness Calculation of Coupled Four Bar Linkage", '
    "Journal of Light Industry Machinery 40(4):6-11, 2022, DOI 10.3969/j.issn.1005-2895.2022.04.002 (seed"
    " 000_3b8cde48dccf5fc1.txt)"
)
ORDER = 1
#: The model variants of the comparison, each in a few words (the index defines the labels it shows).
LABELS = {
    "equilibrium": "the paper's welded frame with internal forces from statics (our reading)",
    "tables": "the paper's welded frame with its Tables 1-2 as printed",
    "printed": "the paper's welded frame with its eqs. (8) and (14) as printed",
    "pinned": "the machine's pinned joints, crank held (our reading; a different quantity)",
}
#: The terms of the paper's answer, for a reader who has not read the paper (the index shows them).
GLOSSARY = {
    "K_h, K_c": "the linear and the rotational stiffness at the rocker's pivot O' (per unit force, per unit moment)",
    "welded frame": "the paper's model: the linkage frozen at each crank angle with rigid joints A and B",
}
