"""Any planar linkage from config: a six-bar written as a config entry alone, its ideal dynamics by the engine against
an independent route, the generated right-hand side against the assembly's constraints, and bad descriptions refused
with their key.

The independent route: the six-bar's closed-form dyad kinematics (``engines.kinematics.solve_chain``: the crank and
three RRR dyads, from the link lengths written out here, no constraint Jacobian), the bodies' centres of mass from
their points, and the driver torque from the power balance T theta' = sum(m a.v + J alpha omega) + sum(m g v_y).
"""

from __future__ import annotations

import copy
import json

import numpy as np
import pytest
import yaml
from conftest import assert_rhs_solves_the_numpy_equations, load_yaml

from linkwork.engines.kinematics import Chain, Dyad, solve_chain
from linkwork.engines.multibody import assembly, describe
from linkwork.engines.multibody.linkage import LinkageError
from linkwork.engines.multibody.simulate import integrate

#: A Watt six-bar with a bell crank: crank O2-A, coupler A-B, bell crank O4-B-C, link C-D, rocker O6-D (SI, degrees).
SIX_BAR = yaml.safe_load("""
bodies:
  crank: {mass_kg: 0.4, inertia_kg_m2: 1.0e-3, points: {O: [-0.05, 0.0], A: [0.05, 0.0]}, angle_guess_deg: 30}
  coupler: {mass_kg: 1.2, inertia_kg_m2: 9.0e-3, points: {A: [-0.15, 0.0], B: [0.15, 0.0]}, angle_guess_deg: -50}
  bellcrank: {mass_kg: 1.0, inertia_kg_m2: 6.0e-3, angle_guess_deg: -100,
              points: {O: [-0.05, -0.03], B: [0.15, -0.03], C: [-0.05, 0.12]}}
  link: {mass_kg: 0.9, inertia_kg_m2: 7.0e-3, points: {C: [-0.15, 0.0], D: [0.15, 0.0]}, angle_guess_deg: 150}
  rocker: {mass_kg: 0.7, inertia_kg_m2: 2.5e-3, points: {O: [-0.1, 0.0], D: [0.1, 0.0]}, angle_guess_deg: -120}
ground: {O2: [0.0, 0.0], O4: [0.3, 0.0], O6: [0.3, 0.3]}
joints:
  O2: {journal: crank.O, bearing: ground.O2}
  A: {journal: crank.A, bearing: coupler.A}
  B: {journal: coupler.B, bearing: bellcrank.B}
  O4: {journal: bellcrank.O, bearing: ground.O4}
  C: {journal: bellcrank.C, bearing: link.C}
  D: {journal: link.D, bearing: rocker.D}
  O6: {journal: rocker.O, bearing: ground.O6}
driver: {body: crank, speed_rad_s: 20.0, start_angle_deg: 30}
output: rocker
""")
from linkwork.units import STANDARD_GRAVITY as G  # noqa: E402


def _chain() -> Chain:
    """The same six-bar as a crank and three dyads, by its link lengths (m): the independent route's geometry."""
    return Chain(
        ground={"O2": (0.0, 0.0), "O4": (0.3, 0.0), "O6": (0.3, 0.3)},
        crank_pivot="O2",
        crank_tip="A",
        crank_length=0.1,
        dyads=(
            Dyad("B", "A", "O4", 0.3, 0.2, -1), Dyad("C", "O4", "B", 0.15, 0.25, 1), Dyad("D", "C", "O6", 0.3, 0.2, 1),
        ),
    )


#: Each body of the route: (mass, inertia, a point the chain knows, that point in the body frame, the link giving the
#: body's angle, that link's angle in the body frame).
ROUTE_BODIES = (
    (0.4, 1.0e-3, "A", (0.05, 0.0), "O2-A", 0.0),
    (1.2, 9.0e-3, "B", (0.15, 0.0), "A-B", 0.0),
    (1.0, 6.0e-3, "B", (0.15, -0.03), "O4-B", 0.0),
    (0.9, 7.0e-3, "D", (0.15, 0.0), "C-D", 0.0),
    (0.7, 2.5e-3, "D", (0.1, 0.0), "O6-D", 0.0),
)


def independent_route(theta, theta_d, theta_dd, gravity=True):
    """Output (rocker) angular acceleration (rad/s^2) and driver torque (N m) at crank angles theta (rad), rates and
    accelerations, by the closed-form chain and the power balance."""
    m = solve_chain(_chain(), theta)
    power = np.zeros_like(theta)
    for mass, inertia, name, (sx, sy), link, offset in ROUTE_BODIES:
        pt, ln = m.points[name], m.links[link]
        phi = ln.angle - offset
        w, a = theta_d * ln.rate, theta_dd * ln.rate + theta_d**2 * ln.accel
        vp = theta_d[:, None] * pt.vel
        ap = theta_dd[:, None] * pt.vel + (theta_d**2)[:, None] * pt.acc
        r = np.stack(
            [np.cos(phi) * sx - np.sin(phi) * sy, np.sin(phi) * sx + np.cos(phi) * sy], axis=-1
        )  # centre -> point
        perp = np.stack([-r[:, 1], r[:, 0]], axis=-1)
        v = vp - w[:, None] * perp
        acc = ap - a[:, None] * perp + (w**2)[:, None] * r
        power += mass * np.sum(acc * v, axis=-1) + inertia * a * w + (mass * G * v[:, 1] if gravity else 0.0)
    out = m.links["O6-D"]
    return theta_dd * out.rate + theta_d**2 * out.accel, power / theta_d


def _times(linkage, turns=1.0, n=361):
    return np.linspace(0.0, turns * 2 * np.pi / linkage.driver.speed, n)


def test_a_six_bar_written_in_config_assembles_on_its_branch_through_the_turn():
    linkage = describe.check(SIX_BAR, "linkages.six_bar")
    turn = assembly.follow_turn(linkage)
    m = solve_chain(_chain(), linkage.driver.angle(turn.t)[0])
    for b, (_, _, _, _, link, offset) in enumerate(ROUTE_BODIES):
        gap = np.angle(np.exp(1j * (turn.q[:, 3 * b + 2] - (m.links[link].angle - offset))))
        assert np.abs(gap).max() < 1e-10
    assert turn.gain[2] == pytest.approx(2 * np.pi) and np.all(turn.gain[5::3] == 0.0)  # the crank turns, the rest rock


@pytest.mark.parametrize("gravity", [True, False])
def test_six_bar_inverse_dynamics_equals_the_closed_form_chain_and_power_balance(gravity):
    linkage = describe.from_config(SIX_BAR, "linkages.six_bar")
    t = _times(linkage, turns=1.5)
    ours = assembly.inverse_dynamics(linkage, t, gravity)
    th, thd, thdd = linkage.driver.angle(t)
    acc, torque = independent_route(th, thd, thdd, gravity)
    assert np.abs(ours["output_acceleration"] - acc).max() < 1e-9 * np.abs(acc).max()
    assert np.abs(ours["driver_torque"] - torque).max() < 1e-9 * np.abs(torque).max()


def test_the_joint_reactions_balance_every_body_by_newton_and_euler():
    """The reaction components of inverse dynamics (the bearing's body on the journal's) summed per body with gravity
    (and the driver torque on the driven body): m a_G and I alpha of every body, from the engine's own accelerations
    but with the forces assembled body by body, not from the multipliers' solve."""
    linkage = describe.from_config(SIX_BAR, "linkages.six_bar")
    t = _times(linkage)[::40]
    ours = assembly.inverse_dynamics(linkage, t, True)
    q, qdd = ours["q"], ours["qdd"]
    force = {b.name: np.zeros((t.size, 2)) for b in linkage.bodies}
    moment = {b.name: np.zeros(t.size) for b in linkage.bodies}
    for joint in linkage.joints:
        r = ours[f"reaction_{joint.name}"]
        for ref, sign in ((joint.journal, 1.0), (joint.bearing, -1.0)):
            if ref[0] == "ground":
                continue
            b = linkage.body_index(ref[0])
            pos, _ = assembly._world_stack(linkage, q, np.zeros_like(q), ref)
            arm = pos - q[:, 3 * b : 3 * b + 2]
            force[ref[0]] += sign * r
            moment[ref[0]] += sign * (arm[:, 0] * r[:, 1] - arm[:, 1] * r[:, 0])
    moment[linkage.driver.body] += ours["driver_torque"]
    for k, body in enumerate(linkage.bodies):
        weight = np.array([0.0, -body.mass * linkage.gravity])
        scale = body.mass * np.abs(qdd[:, 3 * k : 3 * k + 2]).max() + body.mass * linkage.gravity
        assert np.abs(force[body.name] + weight - body.mass * qdd[:, 3 * k : 3 * k + 2]).max() < 1e-9 * scale
        assert np.abs(moment[body.name] - body.inertia * qdd[:, 3 * k + 2]).max() < 1e-9 * np.abs(
            ours["driver_torque"]
        ).max()
    for joint in linkage.joints:  # the magnitudes are the components'
        assert np.allclose(np.hypot(*ours[f"reaction_{joint.name}"].T), ours[f"force_{joint.name}"], rtol=1e-12)


def test_six_bar_forward_dynamics_reproduces_the_independent_route():
    """The compiled right-hand side generated from the description, integrated (DOP853) from the assembled start over
    one turn: its output acceleration and driver torque against the independent route."""
    linkage = describe.from_config(SIX_BAR, "linkages.six_bar")
    t = _times(linkage)
    integ = {"method": "dop853", "rtol": 1e-11, "atol": 1e-13, "first_step_s": 1e-6, "max_step_s": 1e-3}
    ys, diags, *_ = integrate(linkage, True, t, integ)
    acc, torque = independent_route(*linkage.driver.angle(t))
    assert diags[:, 3].max() < 1e-9  # constraint drift, m
    assert np.abs(diags[:, 0] - acc).max() < 1e-6 * np.abs(acc).max()
    assert np.abs(diags[:, 1] - torque).max() < 1e-6 * np.abs(torque).max()


def test_a_driver_given_as_a_fourier_series_moves_the_crank_so():
    """The driver theta0 + omega t + a1 cos(omega t) + b2 sin(2 omega t): engine (inverse and forward) against the
    route."""
    spec = copy.deepcopy(SIX_BAR)
    spec["driver"].update(cos_deg=[6.0, 0.0], sin_deg=[0.0, -4.0])
    linkage = describe.check(spec, "linkages.six_bar")
    t = _times(linkage)
    th, thd, thdd = linkage.driver.angle(t)
    acc, torque = independent_route(th, thd, thdd)
    ours = assembly.inverse_dynamics(linkage, t, True)
    assert np.abs(ours["driver_torque"] - torque).max() < 1e-9 * np.abs(torque).max()
    integ = {"method": "dop853", "rtol": 1e-11, "atol": 1e-13, "first_step_s": 1e-6, "max_step_s": 1e-3}
    ys, diags, *_ = integrate(linkage, True, t, integ)
    assert np.abs(ys[:, 2] - th).max() < 1e-9  # the crank follows the series
    assert np.abs(diags[:, 1] - torque).max() < 1e-6 * np.abs(torque).max()


@pytest.mark.parametrize("name", ["six_bar", "sprung"])
def test_the_generated_right_hand_side_solves_the_assemblys_equations(name):
    """At random states of the six-bar: the compiled right-hand side's accelerations satisfy M q'' = g - Phi_q^T lam and
    Phi_q q'' = gamma - 2 a Phi' - b^2 Phi with Phi_q, Phi, gamma (and g's spring-damper) written independently in numpy
    (``assembly``); the driver's power follows its row (the third: after the crank's pin).  ``sprung``: a spring-damper
    to the ground and a rocking driver, the elements of the heald linkage, on a linkage that compiles in a fraction of
    the heald one's time."""
    linkage = describe.from_config(SIX_BAR if name == "six_bar" else SPRUNG, f"linkages.{name}")
    assert_rhs_solves_the_numpy_equations(linkage, True, (0.0, 0.3), 1e-4, 0.5, seed=5, states=20, driver_row=2)


def _edit(path: str, value):
    spec = copy.deepcopy(SIX_BAR)
    *parents, last = path.split(".")
    node = spec
    for p in parents:
        node = node[p]
    if value is None:
        del node[last]
    else:
        node[last] = value
    return spec


BAD = [
    # (what, edit, the key named, words of the message)
    (
        "a joint naming an unknown point", ("joints.C.bearing", "link.X"), "linkages.six_bar.joints.C.bearing",
        "unknown point 'X'",
    ),
    (
        "a joint naming an unknown body", ("joints.C.bearing", "lever.C"), "linkages.six_bar.joints.C.bearing",
        "unknown body 'lever'",
    ),
    (
        "a joint missing: a free motion left", ("joints.O6", None), "linkages.six_bar.joints",
        "2 free motions besides the driver",
    ),
    (
        "a body not connected to the ground",
        ("bodies.weight", {"mass_kg": 1.0, "inertia_kg_m2": 0.1, "points": {"P": [0.0, 0.0]}}),
        "linkages.six_bar.bodies.weight", "not connected to the ground",
    ),
    (
        "a driver on a body that is not grounded", ("driver.body", "coupler"), "linkages.six_bar.driver.body",
        "not pinned to the ground",
    ),
    ("a linkage that cannot assemble", ("ground.O6", [0.3, 0.9]), "linkages.six_bar.driver", "does not assemble"),
    ("a joint of a body to itself", ("joints.C.bearing", "bellcrank.O"), "linkages.six_bar.joints.C", "to itself"),
    (
        "a clearance reading a key of an effect it does not name",
        (
            "joints.D.clearance",
            {
                "journal_radius_m": 0.0099,
                "bearing_radius_m": 0.01,
                "effects": ["lubrication"],
                "viscosity_Pa_s": 0.1,
                "length_m": 0.02,
                "e0_m": 1e-6,
                "friction": 0.1,
            },
        ),
        "linkages.six_bar.joints.D.clearance.friction",
        "unknown key",
    ),
    (
        "friction without contact",
        ("joints.D.clearance", {"journal_radius_m": 0.0099, "bearing_radius_m": 0.01, "effects": ["friction"]}),
        "linkages.six_bar.joints.D.clearance.effects", "friction needs contact",
    ),
    (
        "a film cap beyond the clearance",
        (
            "joints.D.clearance",
            {
                "journal_radius_m": 0.0099,
                "bearing_radius_m": 0.01,
                "effects": ["lubrication"],
                "viscosity_Pa_s": 0.1,
                "length_m": 0.02,
                "e0_m": 2e-4,
            },
        ),
        "linkages.six_bar.joints.D.clearance.e0_m",
        "below the radial clearance",
    ),
    ("a negative mass", ("bodies.link.mass_kg", -1.0), "linkages.six_bar.bodies.link.mass_kg", "positive"),
    (
        "a spring with a negative stiffness",
        ("springs", {"w": {"point": "link.C", "rest_m": [0.0, 0.0], "stiffness_N_m": [-1.0, 0.0]}}),
        "linkages.six_bar.springs.w.stiffness_N_m", "must not be negative",
    ),
    (
        "a spring on a ground point",
        ("springs", {"w": {"point": "ground.O2", "rest_m": [0.0, 0.0], "stiffness_N_m": [1.0, 0.0]}}),
        "linkages.six_bar.springs.w.point", "point of a body",
    ),
    (
        "a rocking driver without its motion", ("driver.rocking", True), "linkages.six_bar.driver.cos_deg",
        "needs its motion",
    ),
    ("an unknown output body", ("output", "sley"), "linkages.six_bar.output", "unknown body"),
]


@pytest.mark.parametrize("what, edit, key, words", BAD, ids=[b[0] for b in BAD])
def test_a_bad_description_is_refused_with_its_key(what, edit, key, words):
    with pytest.raises(LinkageError) as err:
        describe.check(_edit(*edit), "linkages.six_bar")
    assert err.value.key == key and words in str(err.value), str(err.value)


def test_lock_up_inside_the_turn_is_refused_with_the_angle():
    """A first loop that is not a crank-rocker (a coupler of 0.15 m: coupler and bell crank reach 0.35 m, the crank pin
    goes 0.4 m from O4 at 180 deg, so B cannot close beyond about 112 deg): the turn is
    followed until the dyad at B cannot close, and the message names the linkage and the driver angle."""
    spec = _edit("bodies.coupler.points", {"A": [-0.075, 0.0], "B": [0.075, 0.0]})
    spec["bodies"]["coupler"]["angle_guess_deg"] = -60
    with pytest.raises(LinkageError) as err:
        describe.check(spec, "linkages.six_bar")
    assert err.value.key == "linkages.six_bar" and "driver angle" in str(err.value), str(err.value)


def test_exudyn_built_from_the_same_description_drives_the_six_bar_alike():
    """Route 3 for any linkage: Exudyn's model is built from the description (bodies, revolute joints, the driver's
    coordinate constraint); its output acceleration and driver torque against our inverse dynamics, converging with the
    step (second order)."""
    from linkwork.engines.multibody.exudyn_route import ideal_run

    linkage = describe.from_config(SIX_BAR, "linkages.six_bar")
    end = 2 * np.pi / linkage.driver.speed
    diffs = []
    for step in (4e-4, 2e-4):
        run = ideal_run(linkage, end, step, 1e-12)
        ours = assembly.inverse_dynamics(linkage, run["t"], True)
        diffs.append(np.abs(run["driver_torque"] - ours["driver_torque"]).max() / np.abs(ours["driver_torque"]).max())
    assert diffs[1] < 1e-3 and 3.0 < diffs[0] / diffs[1] < 5.0, diffs


#: The six-bar's rocker held by a spring-damper at its pin D and its crank rocked by a given motion (config form).
SPRUNG = {
    **copy.deepcopy(SIX_BAR),
    "springs": {
        "w": {"point": "rocker.D", "rest_m": [0.35, 0.45], "stiffness_N_m": [400.0, 900.0], "damping_N_s_m": [3.0, 5.0]}
    },
    "driver": {
        "body": "crank",
        "speed_rad_s": 20.0,
        "start_angle_deg": 30,
        "cos_deg": [20.0, 5.0],
        "sin_deg": [10.0, 0.0],
        "rocking": True,
    },
}


def test_a_spring_and_a_rocking_driver_from_config_balance_the_drivers_power():
    """A spring-damper and a rocking driver read from config: the driver's power from the engine's multipliers equals
    the rate of the energy (kinetic, gravity's, the spring's; fourth-order differences) plus the damper's loss, 1e-6."""
    linkage = describe.check(SPRUNG, "linkages.sprung")
    n = 4001
    t = np.linspace(0.0, linkage.driver.period, n)
    out = assembly.inverse_dynamics(linkage, t, True)
    assert np.ptp(out["q"][:, 2]) < np.radians(60.0)  # it rocks (no mean turning)
    power = out["driver_torque"] * linkage.driver.angle(t)[1]
    e, dt = out["energy"], t[1] - t[0]
    rate = (e[:-4] - 8 * e[1:-3] + 8 * e[3:-1] - e[4:]) / (12 * dt)
    _, vel = assembly._world_stack(linkage, out["q"], out["qd"], ("rocker", "D"))
    loss = 3.0 * vel[:, 0] ** 2 + 5.0 * vel[:, 1] ** 2
    assert np.abs(power[2:-2] - rate - loss[2:-2]).max() < 1e-6 * np.abs(power).max()


def test_exudyn_drives_a_sprung_rocking_six_bar_alike():
    """Route 3 with a spring-damper (Exudyn's Cartesian spring-damper) and a rocking driver: Exudyn's driver torque
    against our inverse dynamics, converging with the step."""
    from linkwork.engines.multibody.exudyn_route import ideal_run

    linkage = describe.from_config(SPRUNG, "linkages.sprung")
    diffs = []
    for step in (4e-4, 2e-4):
        run = ideal_run(linkage, linkage.driver.period, step, 1e-12)
        ours = assembly.inverse_dynamics(linkage, run["t"], True)
        diffs.append(np.abs(run["driver_torque"] - ours["driver_torque"]).max() / np.abs(ours["driver_torque"]).max())
    assert diffs[1] < 1e-3 and 3.0 < diffs[0] / diffs[1] < 5.0, diffs


def test_the_registries_are_one_table_each():
    """Contact laws and integrators: the schema's choices, the compiled kernels' codes and the Exudyn route's laws are
    the keys of ``linkage.CONTACT_LAWS`` and ``simulate.METHODS``."""
    from linkwork.engines.multibody.exudyn_route import HYSTERESIS
    from linkwork.engines.multibody.linkage import CONTACT_LAWS
    from linkwork.engines.multibody.simulate import METHODS

    schema = load_yaml("config/schema.yaml")
    clearance = schema["properties"]["clearance"]
    assert clearance["$defs"]["integrator"]["properties"]["method"]["enum"] == list(METHODS)
    joints = clearance["properties"]["joints"]["properties"]
    assert set(joints["contact_law"]["enum"]) == set(CONTACT_LAWS) == set(HYSTERESIS)
    assert sorted(CONTACT_LAWS.values()) == list(range(len(CONTACT_LAWS)))  # the kernels' codes 0, 1, 2


def test_a_driver_turning_the_other_way():
    """A negative driver speed turns the crank towards decreasing angles: the turn is followed that way (the crank's
    gain is -2 pi) and the inverse dynamics matches the independent route at the negative rates."""
    spec = copy.deepcopy(SIX_BAR)
    spec["driver"]["speed_rad_s"] = -20.0
    linkage = describe.check(spec, "linkages.six_bar")
    assert assembly.follow_turn(linkage).gain[2] == pytest.approx(-2 * np.pi)
    t = np.linspace(0.0, linkage.driver.period, 181)
    ours = assembly.inverse_dynamics(linkage, t, True)
    acc, torque = independent_route(*linkage.driver.angle(t))
    assert np.abs(ours["output_acceleration"] - acc).max() < 1e-9 * np.abs(acc).max()
    assert np.abs(ours["driver_torque"] - torque).max() < 1e-9 * np.abs(torque).max()


def test_an_over_constrained_linkage_is_refused():
    """A second pin between the bell crank and the ground (redundant constraints): Grübler's count names them."""
    spec = copy.deepcopy(SIX_BAR)
    spec["ground"]["C0"] = [0.2, 0.1]
    spec["joints"]["extra"] = {"journal": "bellcrank.C", "bearing": "ground.C0"}
    with pytest.raises(LinkageError) as err:
        describe.check(spec, "linkages.six_bar")
    assert err.value.key == "linkages.six_bar.joints" and "redundant constraints" in str(err.value), str(err.value)


def test_a_change_point_linkage_is_refused_where_it_passes_it():
    """A four-bar with s + l = p + q (crank 0.1, coupler 0.3, rocker 0.2, ground 0.2 m: a change point where all four
    links line up): following the turn meets a singular constraint Jacobian there, and the description is refused with
    its key and the driver angle."""
    spec = yaml.safe_load("""
bodies:
  crank: {mass_kg: 0.4, inertia_kg_m2: 1.0e-3, points: {O: [-0.05, 0.0], A: [0.05, 0.0]}, angle_guess_deg: 90}
  coupler: {mass_kg: 1.0, inertia_kg_m2: 8.0e-3, points: {A: [-0.15, 0.0], B: [0.15, 0.0]}, angle_guess_deg: 20}
  rocker: {mass_kg: 0.8, inertia_kg_m2: 3.0e-3, points: {O: [-0.1, 0.0], B: [0.1, 0.0]}, angle_guess_deg: 100}
ground: {O2: [0.0, 0.0], O4: [0.2, 0.0]}
joints:
  O2: {journal: crank.O, bearing: ground.O2}
  A: {journal: crank.A, bearing: coupler.A}
  B: {journal: coupler.B, bearing: rocker.B}
  O4: {journal: rocker.O, bearing: ground.O4}
driver: {body: crank, speed_rad_s: 10.0, start_angle_deg: 90}
output: rocker
""")
    with pytest.raises(LinkageError) as err:
        describe.check(spec, "linkages.change_point")
    message = str(err.value)
    assert err.value.key == "linkages.change_point" and ("change point" in message or "locks up" in message), message
    assert "driver angle" in message


def _renamed(spec: dict, new) -> dict:
    """``spec`` with every name it chooses (bodies, their points, ground points, joints, springs) replaced by
    ``new(name)``, and every reference to them with it."""

    def ref(text: str) -> str:
        body, point = text.split(".")
        return f"{body if body == 'ground' else new(body)}.{new(point)}"

    out = copy.deepcopy(spec)
    out["bodies"] = {
        new(b): {**v, "points": {new(p): xy for p, xy in v["points"].items()}} for b, v in spec["bodies"].items()
    }
    out["ground"] = {new(g): xy for g, xy in spec["ground"].items()}
    out["joints"] = {
        new(j): {**v, "journal": ref(v["journal"]), "bearing": ref(v["bearing"])} for j, v in spec["joints"].items()
    }
    out["springs"] = {new(s): {**v, "point": ref(v["point"])} for s, v in spec.get("springs", {}).items()}
    out["driver"] = {**spec["driver"], "body": new(spec["driver"]["body"])}
    out["output"] = new(spec["output"])
    return out


def _names(spec: dict) -> set[str]:
    """Every name a description chooses."""
    points = {p for b in spec["bodies"].values() for p in b["points"]}
    return {*spec["bodies"], *points, *spec["ground"], *spec["joints"], *spec.get("springs", {})}


#: The shipped linkage (a clearance joint with contact and friction) with a spring: every kind of part the generated
#: source has a line for.
SHIPPED = {
    **load_yaml("config/config.yaml")["linkages"]["watt_six_bar_worn_pin"]["linkage"],
    "springs": {"guide": {"point": "rocker.D", "rest_m": [0.4, 0.3], "stiffness_N_m": [400.0, 900.0]}},
}


def test_the_generated_source_holds_no_name_of_the_description():
    """The scene's source names bodies, joints and springs by their index: with names no code could contain by chance
    (a prefix and suffix around each), none of them is in the source; and the same topology under other names is the
    same source (one compiled scene)."""
    from linkwork.engines.multibody.model import generate_source

    spec = _renamed(SHIPPED, lambda n: f"Qz{n}zQ")
    source = generate_source(describe.from_config(spec, "linkages.named"), True)
    assert "clearance joint 0" in source and "spring 0" in source
    assert not [n for n in _names(spec) if n in source] and "QzD" not in source
    assert generate_source(describe.from_config(SHIPPED, "linkages.shipped"), True) == source


def test_a_name_with_code_never_reaches_the_generated_source():
    """Behind the validation that refuses it: a joint and a spring named with code after a newline (the description
    read without the config's name rule) give the source of the same scene with plain names, so nothing of them runs."""
    from linkwork.engines.multibody.model import generate_source

    hostile = "D\nopen('pwned.txt','w').write('pwned')\nif True:"
    spec = copy.deepcopy(SHIPPED)
    spec["joints"] = {hostile if j == "D" else j: v for j, v in spec["joints"].items()}
    spec["springs"] = {"</script>pwned": spec["springs"]["guide"]}
    source = generate_source(describe.from_config(spec, "linkages.hostile"), True)
    assert "pwned" not in source and "script" not in source
    assert source == generate_source(describe.from_config(SHIPPED, "linkages.shipped"), True)


#: A driven crank alone (one body, one pin): the smallest scene, quick to compile.
CRANK = {
    "bodies": {"crank": {"mass_kg": 0.4, "inertia_kg_m2": 1.0e-3, "points": {"O": [-0.05, 0.0], "A": [0.05, 0.0]}}},
    "ground": {"O2": [0.0, 0.0]},
    "joints": {"O2": {"journal": "crank.O", "bearing": "ground.O2"}},
    "driver": {"body": "crank", "speed_rad_s": 20.0, "start_angle_deg": 30},
    "output": "crank",
}
DOP853 = {"method": "dop853", "rtol": 1e-8, "atol": 1e-11, "first_step_s": 1e-6, "max_step_s": 1e-3}


def test_the_schema_requires_of_each_method_the_keys_a_run_reads():
    """One table: each integrator method's keys in config/schema.yaml (required for it) are ``simulate.READS``."""
    from linkwork.engines.multibody.simulate import METHODS, READS

    integrator = load_yaml("config/schema.yaml")["properties"]["clearance"]["$defs"]["integrator"]
    required = {}
    for rule in integrator["allOf"]:
        chosen = rule["if"]["properties"]["method"]
        for method in chosen.get("enum", [chosen.get("const")]):
            required[method] = tuple(rule["then"]["required"])
    assert required == READS and set(READS) == set(METHODS)


@pytest.mark.parametrize(
    "setting, key",
    [
        ({k: v for k, v in DOP853.items() if k != "first_step_s"}, "first_step_s"),
        ({**DOP853, "first_step_s": 0.0}, "first_step_s"),
        ({**DOP853, "method": "ndf", "max_step_s": -1.0}, "max_step_s"),
        ({"method": "rk4"}, "step_s"),
        ({"method": "radau", "rtol": 1e-8, "atol": 1e-11}, "max_step_s"),
        ({"method": "radau", "rtol": 1e-8, "atol": 1e-11, "max_step_s": 1e-3, "first_step_s": 0.0}, "first_step_s"),
        ({"method": "euler", "step_s": 1e-4}, "method"),
    ],
)
def test_a_run_refuses_an_integrator_setting_without_a_key_it_reads(setting, key):
    """A run checks its setting before it starts (the schema refuses the same before any job): a missing or
    non-positive key its method reads is named, instead of a first step of 0.0 that never advances or a KeyError."""
    from linkwork.engines.multibody.simulate import Run

    with pytest.raises(LinkageError) as err:
        Run(describe.from_config(CRANK, "linkages.crank"), True, setting, key="linkages.crank.integrator")
    assert err.value.key == f"linkages.crank.integrator.{key}", str(err.value)


def test_a_stretch_of_too_many_steps_is_refused_with_its_key():
    """rk4 at 1e-9 s over a second would take 1e9 steps: refused before it starts, naming step_s and the guard; the
    same bound by max_step_s for an adaptive method."""
    from linkwork.engines.multibody.simulate import STEP_LIMIT, Run

    linkage = describe.from_config(CRANK, "linkages.crank")
    for setting, key in (({"method": "rk4", "step_s": 1e-9}, "step_s"), ({**DOP853, "max_step_s": 1e-9}, "max_step_s")):
        with pytest.raises(LinkageError) as err:
            Run(linkage, True, setting).advance(np.array([0.0, 1.0]))
        message = str(err.value)
        assert err.value.key == f"integrator.{key}" and f"{STEP_LIMIT:.0e}" in message and "1e+09 steps" in message


#: A run that stops advancing, in a process of its own (a guard that failed would hang it): rk4 at a step below the
#: time's resolution (1e-12 s at t = 1e6 s), and dop853 from a first step of 0.0 (the issue's hang); each message.
STALLS = """
import json
import numpy as np
from linkwork.engines.multibody import describe
from linkwork.engines.multibody.linkage import LinkageError
from linkwork.engines.multibody.simulate import Run
linkage = describe.from_config(json.loads(CRANK), "linkages.crank")
out = []
for setting, t0, h in (({"method": "rk4", "step_s": 1e-12}, 1e6, None), (json.loads(DOP853), 0.0, 0.0)):
    run = Run(linkage, True, setting, t0=t0, key="linkages.crank.integrator")
    if h is not None:
        run.h = h  # as a setting that bypassed the checks would give
    try:
        run.advance(np.linspace(t0, t0 + 1e-6, 3))
        out.append("advanced")
    except LinkageError as exc:
        out.append(str(exc))
print(json.dumps(out))
"""


def test_a_run_that_stops_advancing_ends_in_one_line_naming_the_key(tmp_path):
    """The compiled integrators end a run whose accepted steps stop advancing the time (STALL_STEPS in a row), and the
    run names the key to change: rk4's step_s, dop853's first_step_s (a first step of 0.0 used to run forever)."""
    import json
    import os
    import subprocess
    import sys

    from conftest import PROJECT

    script = f"CRANK = {json.dumps(json.dumps(CRANK))}\nDOP853 = {json.dumps(json.dumps(DOP853))}\n" + STALLS
    env = {**os.environ, "PYTHONPATH": str(PROJECT / "lib")}
    done = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True, text=True, timeout=900)
    assert done.returncode == 0, done.stderr[-3000:]
    rk4, dop853 = json.loads(done.stdout.splitlines()[-1])
    assert rk4.startswith("linkages.crank.integrator.step_s: the run stopped advancing after t = 1e+06 s"), rk4
    assert dop853.startswith("linkages.crank.integrator.first_step_s: the run stopped advancing"), dop853
    assert "a step of 0.0 s" in dop853 and "\n" not in rk4 + dop853


def test_a_linkage_job_names_the_key_in_one_line(tmp_path):
    """The study script of every rule, given a linkage whose integrator the run refuses (rk4 at 1e-9 s over a turn of
    6.3 s): the job stops with one line naming the config key, no traceback and no output."""
    import runpy
    from types import SimpleNamespace

    from conftest import PROJECT

    cfg = {
        "linkage": {**CRANK, "driver": {**CRANK["driver"], "speed_rad_s": 1.0}}, "gravity": True, "turns": 1,
        "points_per_turn": 36, "integrator": {"method": "rk4", "step_s": 1e-9},
    }
    output = tmp_path / "results" / "linkages" / "crank.nc"
    snakemake = SimpleNamespace(
        params=SimpleNamespace(study="linkwork.pipeline.linkages:study", cfg=cfg, args={"name": "crank"},
                               paper="linkages"),
        rule="linkage", wildcards={"name": "crank"}, input={}, output=[str(output)], threads=1,
    )
    with pytest.raises(SystemExit) as stop:
        runpy.run_path(str(PROJECT / "workflow" / "scripts" / "study.py"), init_globals={"snakemake": snakemake})
    message = str(stop.value.code)
    assert message.startswith("linkage (name=crank): config key linkages.crank.integrator.step_s: 1e-09 s"), message
    assert "\n" not in message and not output.exists()


def test_a_description_too_stiff_for_its_integrator_ends_in_one_line_naming_its_keys():
    """The shipped example with a modulus of 1e30 Pa at its clearance joint: dop853's step falls below its floor; the
    study stops with a ConfigError naming the linkage and the keys that decide the stiffness, not a RuntimeError."""
    from linkwork.pipeline import linkages
    from linkwork.pipeline.errors import ConfigError

    cfg = copy.deepcopy(load_yaml("config/config.yaml")["linkages"]["watt_six_bar_worn_pin"])
    cfg["linkage"]["joints"]["D"]["clearance"]["youngs_modulus_Pa"] = 1e30
    cfg["turns"], cfg["points_per_turn"] = 1, 360
    with pytest.raises(ConfigError) as err:
        linkages.study(cfg, "watt_six_bar_worn_pin")
    text = str(err.value)
    assert "linkages.watt_six_bar_worn_pin" in text and "youngs_modulus_Pa" in text and "\n" not in text


def test_a_linkage_result_says_where_a_clearance_joint_leaves_its_contact_law():
    """The shipped example at its own clearance stays inside the sphere law's range (no warning); with a 1000 times
    softer contact (modulus 2e8 Pa) the journal sinks deep into its bushing and the result says so, in its attributes
    and on the run's output, with the penetration against the law's limit."""
    from linkwork.pipeline import linkages

    cfg = copy.deepcopy(load_yaml("config/config.yaml")["linkages"]["watt_six_bar_worn_pin"])
    cfg["points_per_turn"] = 360
    ds = linkages.study(cfg, "watt_six_bar_worn_pin")
    measures = json.loads(ds.attrs["validity_D"])
    assert ds.attrs["validity_warnings"] == "" and measures["validity_penetration_limit"] > 0
    cfg["linkage"]["joints"]["D"]["clearance"]["youngs_modulus_Pa"] = 2.0e8
    soft = linkages.study(cfg, "watt_six_bar_worn_pin")
    measures = json.loads(soft.attrs["validity_D"])
    assert measures["validity_penetration_over_clearance"] > measures["validity_penetration_limit"]
    assert soft.attrs["validity_warnings"].startswith("joint D: dry penetration reaches")
