"""Another engine: Exudyn integrates the clearance paper's ideal four-bar forward in time; linkwork's inverse
dynamics must agree with it to Exudyn's own discretisation error, which falls at its integrator's order."""

import copy

import numpy as np
import pytest

from conftest import load_yaml
from linkwork.engines.multibody.linkage import CONTACT_LAWS, ELASTIC_LAWS
from linkwork.papers.clearance.adapter import parameters
from linkwork.papers.clearance.crosscheck import dry, ideal, observed_orders, relative_difference, time_to_reach
from linkwork.papers.clearance.fourbar import exudyn_ideal as ideal_run
from linkwork.papers.clearance.fourbar import inverse_dynamics

SECTION = load_yaml("config/config.yaml")["clearance"]


def test_exudyn_and_inverse_dynamics_agree_to_second_order_in_exudyns_step():
    for variant in SECTION["variants"]:
        p = parameters(SECTION, variant, "ideal")
        end = 0.5 * 2 * np.pi / p.crank_speed  # half a turn from the dead point
        steps = np.array([6e-4, 2e-4])
        diffs = []
        for step in steps:
            run = ideal_run(p, end, float(step), 1e-12)
            ours = inverse_dynamics(p, run["t"], True)
            assert abs(run["t"][-1] - end) < 1e-12
            diffs.append([relative_difference(run[q], ours[q]) for q in ("rocker_acceleration", "crank_torque")])
        diffs = np.array(diffs)
        assert diffs[-1].max() < 1e-3
        orders = observed_orders(steps, diffs)
        assert np.all((orders > 1.7) & (orders < 2.3))  # Newmark is second order: the models are the same


def test_a_wrong_coupler_mass_is_seen_by_the_cross_check():
    """The check can fail: Exudyn with a coupler mass (and so inertia) 10 % off disagrees far beyond its step error."""
    p = parameters(SECTION, "slender", "ideal")
    wrong = copy.deepcopy(SECTION)
    wrong["bodies"]["coupler"]["mass_kg"] *= 1.1
    q = parameters(wrong, "slender", "ideal")
    end = 0.5 * 2 * np.pi / p.crank_speed
    run = ideal_run(q, end, 2e-4, 1e-12)
    ours = inverse_dynamics(p, run["t"], True)
    assert relative_difference(run["crank_torque"], ours["crank_torque"]) > 1e-2


def test_the_study_records_agreement_and_the_observed_order():
    cfg = copy.deepcopy(SECTION)
    cfg["crosscheck"].update(cycles=0.25, steps_s=[2e-4, 6e-4])
    ds = ideal(cfg)
    assert list(ds.step.values) == [6e-4, 2e-4]  # coarse to fine, whatever the config's order
    assert bool(ds.agree.all())
    assert np.all(np.abs(ds.observed_order.values - 2.0) < 0.3)
    assert "Exudyn" in ds.attrs["engine"]


def _single_impact(c, speed: float, steps: int):
    """A free journal (1 kg) crossing a fixed bearing at ``speed`` (m/s) in Exudyn with the native contact of
    ``exudyn_route.native_contact``: times (s), Exudyn's contact force on the journal (N, x; its sign checked by the
    caller: the bearing pushes the journal back), its position and velocity."""
    import exudyn as exu
    from exudyn import itemInterface as ii

    from linkwork.engines.multibody.exudyn_route import native_contact

    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    ground = mbs.AddObject(ii.ObjectGround())
    node = mbs.AddNode(ii.NodeRigidBody2D(referenceCoordinates=[0.0, 0.0, 0.0], initialVelocities=[speed, 0.0, 0.0]))
    body = mbs.AddObject(ii.ObjectRigidBody2D(mass=1.0, inertia=0.01, nodeNumber=node))
    markers = [mbs.AddMarker(ii.MarkerBodyRigid(bodyNumber=b, localPosition=[0.0, 0.0, 0.0])) for b in (body, ground)]
    data = mbs.AddNode(ii.NodeGenericData(initialCoordinates=[0.1, 0.0, 0.0, 0.0], numberOfDataCoordinates=4))
    contact = mbs.AddObject(ii.ObjectContactSphereSphere(markerNumbers=markers, nodeNumber=data, **native_contact(c)))
    sensors = [
        mbs.AddSensor(
            ii.SensorObject(objectNumber=contact, outputVariableType=exu.OutputVariableType.Force, storeInternal=True)
        )
    ]
    sensors += [mbs.AddSensor(ii.SensorNode(nodeNumber=node, outputVariableType=kind, storeInternal=True))
                for kind in (exu.OutputVariableType.Position, exu.OutputVariableType.Velocity)]
    mbs.Assemble()
    end = 3 * c.clearance / speed
    settings = exu.SimulationSettings()
    settings.timeIntegration.endTime, settings.timeIntegration.numberOfSteps = end, steps
    settings.timeIntegration.generalizedAlpha.useNewmark = True
    settings.timeIntegration.generalizedAlpha.useIndex2Constraints = True
    settings.timeIntegration.discontinuous.useRecommendedStepSize = False
    settings.timeIntegration.newton.relativeTolerance = settings.timeIntegration.newton.absoluteTolerance = 1e-12
    settings.timeIntegration.verboseMode = 0
    settings.solution.file.write = False
    settings.solution.sensors.writePeriod = end / steps
    mbs.SolveDynamic(settings)
    force, position, velocity = (mbs.GetSensorStoredData(k) for k in sensors)
    return force[:, 0], force[:, 1], position[:, 1], velocity[:, 1]  # Exudyn's Force output: on marker 0, the journal


@pytest.mark.parametrize(
    "law, elastic", [(law, "hertz-sphere") for law in CONTACT_LAWS] + [("lankarani-nikravesh", "pereira")]
)
def test_exudyns_native_contact_is_linkworks_law(law, elastic):
    """Second route for every contact law of the registry (``linkage.CONTACT_LAWS``) and both elastic laws: Exudyn's
    compiled sphere-in-hollow-sphere contact with the parameters ``native_contact`` maps (no friction) on a single
    impact, against linkwork's compiled kernels evaluated on Exudyn's own trajectory (penetration, its rate and the
    approach speed latched at contact), to 1e-8 of the peak; the journal leaves with the law's restitution to 2 %."""
    from linkwork.engines.multibody.kernels import elastic_contact, hertz_damping_factor

    section = copy.deepcopy(SECTION)
    section["joints"].update(contact_law=law, elastic_law=elastic)
    c = parameters(section, "slender", "dry_both").joint(("contact",))
    speed = 0.5
    t, force, x, v = _single_impact(c, speed, 20000)
    delta = x - c.clearance
    first = int(np.argmax(delta > 0))
    assert 0 < first < t.size - 1 and delta[-1] < 0  # in and out again
    ours = np.zeros_like(x)
    for i in np.nonzero(delta > 0)[0]:
        damping = hertz_damping_factor(CONTACT_LAWS[law], c.restitution, v[i], max(speed, c.impact_velocity_floor))
        ours[i] = elastic_contact(ELASTIC_LAWS[elastic], c.elastic_stiffness, c.elastic_exponent, delta[i])[0] * damping
    assert np.all(force[delta > 0] < 0)  # the bearing pushes the journal back (-x)
    assert np.abs(force + ours).max() < 1e-8 * ours.max()
    assert -v[-1] / speed == pytest.approx(c.restitution, rel=0.02)


def test_the_dry_study_compares_per_cycle_means_against_its_margin():
    """A short dry run in both engines (one settle cycle, two recorded): shapes, the margin's definition, and
    Exudyn's clearance joint acting as a joint (its deviation from ideal within a factor 2 of ours)."""
    cfg = copy.deepcopy(SECTION)
    cfg["numerics"].update(settle_cycles=1, points_per_cycle=360)
    cfg["crosscheck"].update(record_cycles=2, dry_steps_s=[2e-5, 4e-5])
    ds = dry(cfg, "slender", "dry_2")
    assert ds.sizes == {"setting": 4, "quantity": 2, "cycle": 2}
    assert list(ds.setting.values[2:]) == ["Exudyn step 4e-05 s", "Exudyn step 2e-05 s"]  # coarse to fine
    assert np.all(ds.cycle_rms_deviation.values > 0)
    mean = ds["mean"].values
    np.testing.assert_allclose(ds.relative_difference.values, (mean[-1] - mean[0]) / mean[0])
    assert np.array_equal(ds.agree.values, np.abs(mean[-1] - mean[0]) <= ds.margin.values)
    assert np.all((mean[-1] / mean[0] > 0.5) & (mean[-1] / mean[0] < 2.0))


def test_time_to_reach_reads_the_work_precision_front():
    """The least time over the settings at least as accurate as the target; NaN if none is."""
    errors, times = np.array([0.3, 0.05, 0.06, 0.001]), np.array([1.0, 2.0, 3.0, 4.0])
    assert time_to_reach(errors, times, 0.055) == 2.0  # not 3.0: the front, not the setting order
    assert time_to_reach(errors, times, 0.3) == 1.0
    assert np.isnan(time_to_reach(errors, times, 1e-4))
