"""Elastic laws of the dry clearance contact: the sphere law of eq. (9) kept as it was, the conformal cylindrical
law of Pereira, Ramalho and Ambrosio (2011) against its formula written out here, potentials, a conformal run,
the config keys and the laws' ranges."""

import copy
import math
from dataclasses import replace

import numpy as np
import pytest
from scipy.integrate import quad

from conftest import load_yaml
from linkwork.engines.multibody.kernels import elastic_contact
from linkwork.engines.multibody.linkage import ELASTIC_LAWS, PEREIRA_Y_BREAK_MM, pereira_exponent
from linkwork.engines.multibody.model import compile_scene, pack
from linkwork.papers.clearance.fourbar import initial_state, integrate, scene
from linkwork.engines.multibody import validity
from linkwork.papers.clearance.adapter import model_keys, parameters, scene_effects

SECTION = load_yaml("config/config.yaml")["clearance"]
TIGHT = {"method": "dopri5", "rtol": 1e-8, "atol": 1e-11, "first_step_s": 1e-7, "max_step_s": 1e-3}
FRACTIONS = (0.1, 0.5, 1.0)  # penetrations as fractions of the radial clearance


def section_with(**joints):
    """The config's clearance section with some joint keys changed."""
    section = copy.deepcopy(SECTION)
    section["joints"].update(joints)
    return section


def contact_force_in_rhs(p, penetration):
    """(dry normal force N, penetration m) that the compiled right-hand side of scene dry_2 reports with joint 2's
    journal pushed ``penetration`` into its bushing, every body at rest (so the damping factor is 1)."""
    joints, effects = scene_effects(SECTION, "dry_2")
    lk, gravity = scene(p, joints, effects)
    module = compile_scene(lk, gravity)
    direction = np.array([0.6, -0.8])
    y0 = initial_state(p, joints, offset=tuple((p.clearance + penetration) * direction))
    y0[9:] = 0.0
    params, _ = pack(lk)
    diag = np.zeros(module.N_DIAG)
    module.rhs(0.0, y0, params, np.zeros(1), np.zeros(4, dtype=np.int64), diag)
    return diag[4 + 3], diag[4 + 1]


def test_default_law_is_the_sphere_law_of_eq_9():
    p = parameters(SECTION, "slender", "dry_2")
    assert SECTION["joints"]["elastic_law"] == "hertz-sphere" and p.elastic_law == "hertz-sphere"
    j = SECTION["joints"]
    r_i, r_j = j["journal_radius_m"], j["bearing_radius_m"]
    sigma = 2 * (1 - j["poisson"] ** 2) / j["youngs_modulus_Pa"]
    k = 4 / (3 * sigma) * math.sqrt(r_i * r_j / (r_j - r_i))
    for f in FRACTIONS:
        fn, delta = contact_force_in_rhs(p, f * p.clearance)
        assert delta == pytest.approx(f * p.clearance, rel=1e-9)
        assert fn == pytest.approx(k * delta**1.5, rel=1e-12)
        force, potential = elastic_contact(0, p.hertz_stiffness, 1.5, delta)
        assert (force, potential) == (p.hertz_stiffness * delta**1.5, p.hertz_stiffness * delta**2.5 / 2.5)


def pereira_written_out(clearance_m, length_m, youngs_pa, poisson, penetration_m):
    """Pereira et al.'s internal-contact law as published, in mm, N and N/mm^2: F = (a dR + b) L E* / dR delta^n,
    a = 0.965, b = 0.0965, n = Y dR^-0.005, Y = 1.51 ln(1000 dR)^-0.151 (dR <= 0.34954 mm) or 0.0151 dR + 1.151."""
    dr, length, delta = 1e3 * clearance_m, 1e3 * length_m, 1e3 * penetration_m
    e_star = 1e-6 * youngs_pa / (2 * (1 - poisson**2))
    y = 1.51 * math.log(1000 * dr) ** -0.151 if dr <= 0.34954 else 0.0151 * dr + 1.151
    n = y * dr**-0.005
    return (0.965 * dr + 0.0965) * length * e_star / dr * delta**n


@pytest.mark.parametrize("length", [0.02, 0.04, 0.06])
def test_pereira_force_is_the_published_formula(length):
    """No figure point of the paper could be read (only its first page is in the searchable corpora), so the check
    is the formula itself, written out above in the paper's units, against the engine's SI force."""
    section = section_with(elastic_law="pereira")
    section["assumed"]["joint_length_m"]["value"] = length
    p = parameters(section, "slender", "dry_2")
    assert p.joint_length == length
    j = section["joints"]
    for f in FRACTIONS:
        fn, delta = contact_force_in_rhs(p, f * p.clearance)
        published = pereira_written_out(p.clearance, length, j["youngs_modulus_Pa"], j["poisson"], delta)
        assert fn == pytest.approx(published, rel=1e-9)


def test_pereira_exponent_branches_meet_only_with_the_clearance_in_mm():
    """Y's two branches are continuous at the break clearance when dR is in mm in both (the reading used here)."""
    break_m = PEREIRA_Y_BREAK_MM * 1e-3
    below, above = pereira_exponent(break_m * (1 - 1e-12)), pereira_exponent(break_m * (1 + 1e-12))
    assert below == pytest.approx(above, rel=1e-6)
    assert 1.0 < pereira_exponent(5e-5) < 1.5  # between the line-contact and the sphere exponents
    with pytest.raises(ValueError):
        pereira_exponent(1e-6)
    with pytest.raises(ValueError):
        replace(parameters(SECTION, "slender", "dry_2"), elastic_law="hertz").elastic_stiffness


@pytest.mark.parametrize("law", sorted(ELASTIC_LAWS))
def test_potential_is_the_integral_of_the_force(law):
    section = section_with(elastic_law=law)
    p = parameters(section, "slender", "dry_2")
    code, k, n = ELASTIC_LAWS[law], p.elastic_stiffness, p.elastic_exponent
    for f in FRACTIONS:
        delta = f * p.clearance
        work, _ = quad(lambda d: elastic_contact(code, k, n, d)[0], 0.0, delta, epsabs=0.0, epsrel=1e-12)
        assert elastic_contact(code, k, n, delta)[1] == pytest.approx(work, rel=1e-10)


def test_conformal_dry_scene_runs_and_keeps_its_energy_balance():
    """Scene dry_2 over one crank cycle with the conformal law, restitution 1 and no friction: the contact is
    elastic, so mechanical energy (kinetic + gravity + contact potential) minus the driver's work stays constant up
    to integration and Baumgarte error; a wrong contact potential would break it by the order of the potential."""
    section = section_with(elastic_law="pereira", restitution=1.0, friction=0.0)
    p = parameters(section, "slender", "dry_2")
    joints, effects = scene_effects(section, "dry_2")
    t = np.linspace(0.0, 2 * np.pi / p.crank_speed, 721)
    ys, diags, steps, _, counts, _ = integrate(p, joints, effects, t, TIGHT)
    assert np.isfinite(ys).all() and np.isfinite(diags).all() and steps > 0 and counts[0] > 0
    penetration = np.clip(diags[:, 4 + 1], 0.0, None)
    assert penetration.max() > 0.0
    n = p.elastic_exponent
    contact_potential = p.elastic_stiffness * penetration ** (n + 1) / (n + 1)
    balance = diags[:, 2] - ys[:, 18]
    assert np.abs(balance - balance[0]).max() < 1e-2 * contact_potential.max()


def test_the_contact_reads_its_elastic_law_and_the_conformal_law_the_joint_length():
    sphere = model_keys(SECTION, "slender", "dry_2")
    assert "joints.elastic_law" in sphere and "assumed.joint_length_m" not in sphere
    conformal = model_keys(section_with(elastic_law="pereira"), "slender", "dry_2")
    assert "joints.elastic_law" in conformal and "assumed.joint_length_m" in conformal
    assert "joints.elastic_law" not in model_keys(SECTION, "slender", "ideal")
    assert math.isnan(parameters(SECTION, "slender", "dry_2").joint_length)
    conformal_p = parameters(section_with(elastic_law="pereira"), "slender", "dry_2")
    assert conformal_p.joint_length == SECTION["assumed"]["joint_length_m"]["value"]


def test_schema_lists_every_elastic_law():
    schema = load_yaml("config/schema.yaml")
    joints = schema["properties"]["clearance"]["properties"]["joints"]
    assert set(joints["properties"]["elastic_law"]["enum"]) == set(ELASTIC_LAWS)
    assert "elastic_law" in joints["required"]


def test_sphere_law_range_is_a_short_contact_arc():
    r_i, r_j = SECTION["joints"]["journal_radius_m"], SECTION["joints"]["bearing_radius_m"]
    c = r_j - r_i
    sphere = validity.elastic_law_validity("hertz-sphere", r_i, r_j)
    theta = sphere.limits["max_half_angle_rad"]
    assert theta**2 / 2 / (1 - math.cos(theta)) - 1 == pytest.approx(validity.PARABOLIC_PROFILE_TOLERANCE, rel=0.02)
    assert validity.contact_half_angle(sphere.limits["max_penetration_m"], r_i, r_j) == pytest.approx(theta, rel=1e-9)
    assert 0 < sphere.limits["max_penetration_over_clearance"] < 1  # penetration small against the clearance
    assert validity.contact_half_angle(0.0, r_i, r_j) == 0.0 and validity.contact_half_angle(-c, r_i, r_j) == 0.0
    assert validity.contact_half_angle(0.7 * c, r_i, r_j) > 2 * theta  # the paper's penetrations: far outside it
    assert "deg" in sphere.condition


def test_conformal_law_range_is_its_clearances():
    r_j = SECTION["joints"]["bearing_radius_m"]
    inside = validity.elastic_law_validity("pereira", r_j - 5e-5, r_j)
    outside = validity.elastic_law_validity("pereira", 2e-2, 4e-2)  # 20 mm radial clearance
    assert inside.limits["clearance_in_range"] == 1.0 and outside.limits["clearance_in_range"] == 0.0
    assert inside.limits["min_clearance_m"] < 5e-5 < inside.limits["max_clearance_m"]
    with pytest.raises(ValueError):
        validity.elastic_law_validity("sphere", r_j - 5e-5, r_j)


@pytest.mark.parametrize("fixed", [None, 0.05])
def test_a_fixed_impact_velocity_makes_the_damping_memory_free(fixed):
    """The compiled right-hand side's normal force with the journal moving into its bushing, at two very different
    latched impact velocities: with the paper's law (no fixed velocity) it follows the latched value (floored), with a
    fixed velocity it is the same at both and equals the Lankarani-Nikravesh force at that velocity, K delta^1.5
    (1 + 3 (1 - e^2) / 4 delta' / v), written out here."""
    p = parameters(section_with(fixed_impact_velocity_m_s=fixed), "slender", "dry_2")
    joints, effects = scene_effects(SECTION, "dry_2")
    lk, gravity = scene(p, joints, effects)
    module = compile_scene(lk, gravity)
    y0 = initial_state(p, joints, offset=tuple(1.3 * p.clearance * np.array([0.6, -0.8])))
    y0[9:18] = np.random.default_rng(3).normal(scale=0.5, size=9)  # bodies moving: delta' != 0
    params, _ = pack(lk)
    forces = []
    for latched in (1e-5, 2.0):
        diag = np.zeros(module.N_DIAG)
        module.rhs(0.0, y0, params, np.array([latched]), np.zeros(4, dtype=np.int64), diag)
        fn, delta, ddot = diag[4 + 3], diag[4 + 1], diag[4 + 2]
        v = fixed if fixed is not None else max(latched, p.impact_velocity_floor)
        chi = 3 * (1 - p.restitution**2) / 4
        assert abs(ddot) > 1e-3 and fn == pytest.approx(
            p.hertz_stiffness * delta**1.5 * max(0.0, 1 + chi * ddot / v), rel=1e-12
        )
        forces.append(fn)
    assert (forces[0] == forces[1]) == (fixed is not None)
