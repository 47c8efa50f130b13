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
