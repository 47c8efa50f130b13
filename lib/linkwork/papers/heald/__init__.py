"""Paper ``heald``: its title, source and place in the report order (found by ``linkwork.papers``)."""

TITLE = "Grigoriev, Kheylo 2021: mechanical chains for a heald motion"
CITATION = (
    'V.A. Grigoriev, S.V. Kheylo, "The mechanical chains for dynamic estimation of joint-rod heald motion'
    ' mechanisms of weaving machines", Izvestiya VUZov, Tekhnologiya Tekstil\'noi Promyshlennosti 2021(3),'
    " DOI 10.47367/0021-3497_2021_3_117 (seed 004_911fbc8eddce308f.txt)"
)
ORDER = 5
#: The model variants of the comparison, each in a few words (the index defines the labels it shows).
LABELS = {
    "A": "the physical heald linkage (rigid links, clearance springs at E and F)",
    "B": "the chain with the form of the paper's eq. (2)",
}
#: The terms of the paper's answer, for a reader who has not read the paper (the index shows them).
GLOSSARY = {
    "E, F": "the joints where the longitudinal rod DEF drives the two bell cranks (with clearance in the paper)",
    "physical linkage": "our chain model of the real rods and levers (the paper's own chain, eq. (2), is the other)",
    "loom speeds it names": "500-1200 min^-1, the air-jet loom speeds in the paper's introduction",
}
