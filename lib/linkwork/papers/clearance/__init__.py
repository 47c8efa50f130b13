"""Paper ``clearance``: its title, source and place in the report order (found by ``linkwork.papers``)."""

TITLE = "Li et al. 2017: four-bar with clearance joints and lubrication"
CITATION = (
    'Li Yuanyuan, Chen Guoping, Gao Yong, Sun Dongyang, "Dynamics analysis of no-load four-link mechanism'
    ' with multiple clearance and lubrication joints", J. Nanjing Univ. Aeronaut. Astronaut. '
    "49(6):798-804, 2017 (seed 002_4370c9631b87b84c.txt; the extracted text is garbled, values decoded "
    "with the project digest's key)"
)
ORDER = 3
#: The model variants of the comparison, each in a few words (the index defines the labels it shows).
LABELS = {
    "decoded": "the link inertias as decoded from the text",
    "slender": "slender-rod link inertias, J = mL^2/12 (our reading)",
}
#: The terms of the paper's answer, for a reader who has not read the paper (the index shows them).
GLOSSARY = {
    "journal": "the pin of a clearance joint, moving inside its bushing",
    "decoded inertias": "the link inertias as read from the paper's garbled text (implausibly large)",
    "contact damping's memory": "the contact law's damping scales with the impact velocity stored at the last impact",
    "film cap": "our limit on the oil film's force close to contact, where the paper's own transition is ill-posed",
}
