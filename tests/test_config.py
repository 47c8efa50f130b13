"""Config validation: schema and physical checks name the key and the value."""

import copy

import pytest

import yaml

from linkwork.project.validate import validate_config


def test_project_config_is_valid(config, schema):
    validate_config(config, schema)


from conftest import expect_config_error as _expect


def test_zero_or_negative_length(config, schema):
    for bad in (0.0, -0.015):
        c = copy.deepcopy(config)
        c["stiffness"]["linkage"]["crank_m"] = bad
        _expect(c, schema, "stiffness.linkage.crank_m", repr(bad))


def test_linkage_that_cannot_be_assembled(config, schema):
    c = copy.deepcopy(config)
    c["stiffness"]["linkage"]["crank_m"] = 0.2
    _expect(c, schema, "stiffness.linkage", "crank_m=0.2", "cannot be assembled", "crank angle")


def test_number_read_as_a_string(config, schema):
    c = copy.deepcopy(config)
    c["stiffness"]["numerics"]["assembly_tol"] = yaml.safe_load("x: 1e-6")["x"]
    assert c["stiffness"]["numerics"]["assembly_tol"] == "1e-6"  # PyYAML really does this
    _expect(c, schema, "stiffness.numerics.assembly_tol", "'1e-6'", "string")


def test_unknown_key(config, schema):
    c = copy.deepcopy(config)
    c["stiffness"]["linkage"]["crank_mm"] = 15.0
    _expect(c, schema, "stiffness.linkage.crank_mm", "unknown key")
    c = copy.deepcopy(config)
    c["stifness"] = {}
    _expect(c, schema, "stifness", "unknown key")


def test_compared_forms_must_be_computed(config, schema):
    c = copy.deepcopy(config)
    c["stiffness"]["forms"] = ["equilibrium"]
    _expect(c, schema, "stiffness.forms", "'tables'")


def test_grid_step_must_divide_a_turn(config, schema):
    c = copy.deepcopy(config)
    c["stiffness"]["grids"]["fine_step_deg"] = 7.0
    _expect(c, schema, "stiffness.grids.fine_step_deg", "7.0")


def test_heald_parameters_are_checked(config, schema):
    c = copy.deepcopy(config)
    c["heald"]["parameters"]["k_O"]["value"] = -2.0e4
    _expect(c, schema, "heald.parameters.k_O.value", "-20000.0")
    c = copy.deepcopy(config)
    c["heald"]["parameters"]["eta8"]["value"] = 0.0
    _expect(c, schema, "heald.parameters.eta8.value", "lever ratio")
    c = copy.deepcopy(config)
    c["heald"]["parameters"]["M_P"]["status"] = "guessed"
    _expect(c, schema, "heald.parameters.M_P.status", "guessed")


def test_transplanter_bad_input(config, schema):
    c = copy.deepcopy(config)
    c["transplanter"]["initial_diameters_m"][1] = -0.008
    _expect(c, schema, "transplanter.initial_diameters_m.1", "-0.008")
    c = copy.deepcopy(config)
    c["transplanter"]["material"]["name"] = "unobtainium"
    _expect(c, schema, "transplanter.material.name", "'unobtainium'", "LF6")
    c = copy.deepcopy(config)
    c["transplanter"]["geometry"]["arm_angle_deg"] = 0.0  # the arm along the coupler, through the pin C
    _expect(c, schema, "transplanter.geometry.arm_angle_deg", "0.0", "pivot C")


@pytest.mark.parametrize(
    ("path", "value", "fragment"),
    [
        (("transplanter", "fe", "gravity_m_s2", "value"), 5.0, "not one of its choices"),
        (
            ("transplanter", "fe", "gravity_m_s2", "choice_labels"), ["gravity off", "gravity on", "gravity doubled"],
            "3 names for 2 choices",
        ),
        (("heald", "parameters", "M_P", "value"), 20.0, "outside its own range"),
        (("heald", "parameters", "M_P", "range"), [12.0, 5.0], "is not a range"),
        (("heald", "parameters", "M_P", "range"), [8.0, 8.0], "is not a range"),
    ],
)
def test_a_labelled_entry_must_be_a_value_of_its_own_range_or_choices(config, schema, path, value, fragment):
    node = config
    for key in path[:-1]:
        node = node[key]
    node[path[-1]] = value
    _expect(config, schema, ".".join(path[:-1]), fragment)


def test_a_physical_check_runs_again_only_when_its_own_section_or_code_changed(config, tmp_path, monkeypatch):
    """The remembered validation (validate_once): a changed config or validating code validates again, and then each
    paper's physical check (here the heald one, which follows the heald linkage through its turn) runs only if its own
    section or the code it reads changed."""
    import shutil

    import linkwork.papers.heald.checks as heald_checks
    from linkwork.project import validate

    from conftest import PROJECT

    runs = {"whole": 0, "heald": 0}
    schema_check, heald_check = validate.validate_schema, heald_checks.check

    def whole(*args):
        runs["whole"] += 1
        return schema_check(*args)

    def heald(*args):
        runs["heald"] += 1
        return heald_check(*args)

    monkeypatch.setattr(validate, "validate_schema", whole)
    monkeypatch.setattr(heald_checks, "check", heald)
    lib = tmp_path / "lib"
    shutil.copytree(PROJECT / "lib", lib, ignore=shutil.ignore_patterns("__pycache__", "*.egg-info"))
    stamp, schema = tmp_path / "validated", PROJECT / "config/schema.yaml"

    def after(edit) -> tuple[int, int]:
        edit()
        validate.validate_once(config, schema, lib, stamp)
        return runs["whole"], runs["heald"]

    def append(rel: str):
        return lambda: (lib / rel).write_text((lib / rel).read_text() + "\n# edited\n")

    def reason(paper: str, entry: str):
        return lambda: config[paper]["parameters" if paper == "heald" else "assumed"][entry].update(reason="edited")

    assert after(lambda: None) == (1, 1)
    assert after(lambda: None) == (1, 1)  # nothing changed: nothing runs
    assert after(reason("clearance", "joint_length_m")) == (2, 1)  # another paper's key
    assert after(append("linkwork/papers/clearance/checks.py")) == (3, 1)  # another paper's checks
    assert after(reason("heald", "m_D")) == (4, 2)  # a key of its own section
    assert after(append("linkwork/engines/multibody/assembly.py")) == (5, 3)  # code it reads
