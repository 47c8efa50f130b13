# Helpers shared by the rule files.

LIB = "lib/linkwork"

# Papers whose rules exist; the index says "not yet built" for the others.
BUILT_PAPERS = ["stiffness", "beatup", "clearance", "transplanter", "heald"]


def lib(*modules):
    """Paths of the lib modules a rule uses: declared as input so an edit reruns it."""
    return [f"{LIB}/__init__.py"] + [f"{LIB}/{m}.py" for m in modules]
