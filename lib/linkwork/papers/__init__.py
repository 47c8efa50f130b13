"""The papers this project re-derives: one package per paper, in report order.

Each package holds its model, its config adapter (``adapter``), its studies (config -> result
Datasets, ``studies``), its physical config checks (``checks``) and, where published numbers are
needed to state a finding, its findings (``findings``).  Papers import engines, never each other.
This registry is the one list of papers (rules, index and README read it).  Standard library only.
"""

PAPERS: dict[str, str] = {
    "stiffness": "Huang, Wu, Li 2022: equivalent stiffness of a coupled four-bar (energy method)",
    "beatup": "Gao 1983: six-bar beating-up mechanism vs four-bar",
    "clearance": "Li et al. 2017: four-bar with clearance joints and lubrication",
    "transplanter": "Li, Xu 2001: elastodynamic design of a crank-rocker transplanter",
    "heald": "Grigoriev, Kheylo 2021: mechanical chains for a heald motion",
}
