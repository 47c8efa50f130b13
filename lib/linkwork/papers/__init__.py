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

#: The source of each paper (authors, title, journal; DOI where it has one) and the seed file of its text.
CITATIONS: dict[str, str] = {
    "stiffness": 'Huang Shuang, Wu Xin, Li Peixing, "Equivalent Stiffness Calculation of Coupled Four Bar Linkage", '
                 "Journal of Light Industry Machinery 40(4):6-11, 2022, DOI 10.3969/j.issn.1005-2895.2022.04.002 (seed 000_3b8cde48dccf5fc1.txt)",
    "beatup": 'Gao Weidong, "The kinematic analysis of the six-link beating-up mechanism" (GN721 rapier loom), received 3 August 1983 '
              "(seed 001_c546737132d2571c.txt)",
    "clearance": 'Li Yuanyuan, Chen Guoping, Gao Yong, Sun Dongyang, "Dynamics analysis of no-load four-link mechanism with multiple '
                 'clearance and lubrication joints", J. Nanjing Univ. Aeronaut. Astronaut. 49(6):798-804, 2017 (seed 002_4370c9631b87b84c.txt; '
                 "the extracted text is garbled, values decoded with the project digest's key)",
    "transplanter": 'Li Dewei, Xu Fengying, "Flexible dynamic synthesis on the linkage of high speed crank-rocker style rice seedling '
                    'transplanter", Journal of South China Agricultural University 22(4):81-83, 2001 (seed 003_0cfa70853744423c.txt)',
    "heald": 'V.A. Grigoriev, S.V. Kheylo, "The mechanical chains for dynamic estimation of joint-rod heald motion mechanisms of weaving '
             "machines\", Izvestiya VUZov, Tekhnologiya Tekstil'noi Promyshlennosti 2021(3), DOI 10.47367/0021-3497_2021_3_117 "
             "(seed 004_911fbc8eddce308f.txt)",
}
