"""Paper ``beatup``: its title, source and place in the report order (found by ``linkwork.papers``)."""

TITLE = "Gao 1983: six-bar beating-up mechanism vs four-bar"
CITATION = (
    'Gao Weidong, "The kinematic analysis of the six-link beating-up mechanism" (GN721 rapier loom), '
    "received 3 August 1983 (seed 001_c546737132d2571c.txt)"
)
ORDER = 2
#: The terms of the paper's answer, for a reader who has not read the paper (the index shows them).
GLOSSARY = {
    "kinematic headline numbers": "the sley's dead centres, swing and velocity and acceleration peaks the paper prints",
    "S_w": "the reed clearance the shuttle needs, which sets the weft-insertion window",
    "1511M": "the four-bar loom the paper compares its six-bar with",
}
