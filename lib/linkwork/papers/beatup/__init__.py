"""Paper ``beatup``: its title, source and place in the report order (found by ``linkwork.papers``)."""

TITLE = "Gao 1983: six-bar beating-up mechanism vs four-bar"
CITATION = (
    'Gao Weidong, "The kinematic analysis of the six-link beating-up mechanism" (GN721 rapier loom), '
    "received 3 August 1983 (seed 001_c546737132d2571c.txt)"
)
ORDER = 2
