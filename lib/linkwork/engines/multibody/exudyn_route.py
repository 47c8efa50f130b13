"""Route 3, an established engine: any linkage of ``linkage.Linkage`` in Exudyn, ideal or with dry clearance joints.

Exudyn (C++ multibody engine, the optional extra ``crosscheck``) integrates the same bodies, joints, gravity and
driver forward in time, built from the same description: 2D rigid bodies at their centres of mass, a revolute joint
per ideal joint, and a coordinate constraint on the driven body's angle (theta0 + omega t, and the Fourier terms of a
given motion).  Nothing of linkwork's own multibody code is used but the consistent initial state (assembly) and the
description.  The driver torque is the driver constraint's force with linkwork's sign (Exudyn's multiplier acts the
other way).

A dry clearance joint is Exudyn's own compiled contact (``ObjectContactSphereSphere``: the journal a sphere in a
hollow sphere, the bearing), its parameters mapped from the joint's description by ``native_contact``: the elastic
law's K and exponent, Hunt-Crossley damping with the restitution that gives the joint's contact law's hysteresis
(the factor 3/2 (1 - e_res) equals the law's chi), no linear damping, the impact velocity latched at contact and
floored at the joint's floor, as ours.  Friction is Exudyn's regularised Coulomb (proportional up to v1, then mu F_N):
Ambrosio's law as we use it is zero below v0 and linear from v0 to v1, so the two differ at slips below v1 (and
Exudyn takes the slip at the contact point, r - delta/2 from each centre, where we take it at the radii).

Solver: Newmark (trapezoidal) with the constraints at velocity level (index 2; the driver then reads its time derivative
omega), modified Newton iterated to ``newton_tolerance``.  The default index-3 generalized-alpha returns accelerations
and multipliers that do not converge with the step for the decoded inertias (relative differences 0.25-0.65 at 1e-4 to
1e-5 s, positions exact to 1e-15): its algorithmic acceleration is not the mechanism's.
"""

from __future__ import annotations

import time

import numpy as np

from .assembly import kinematics, start_state
from .linkage import Clearance, Driver, Linkage


def _driver_offset(driver: Driver):
    """Exudyn's offset user functions of the driver (the driven angle without its reference value theta(0), rad, and
    its rate, rad/s) as functions of time.  theta(0) is theta0 plus the series' cosine terms."""
    reference = float(driver.angle(np.array([0.0]))[0][0])

    def offset(mbs, t, item, value):
        th, _, _ = driver.angle(np.array([t]))
        return float(th[0] - reference)

    def rate(mbs, t, item, value):
        return float(driver.angle(np.array([t]))[1][0])

    if not driver.cos:
        w = driver.speed
        return (lambda mbs, t, item, value: w * t), (lambda mbs, t, item, value: w)
    return offset, rate


def _build(linkage: Linkage, gravity: bool):
    """(system container, main system, sensor of the output body's coordinates_tt, sensor of the driver force): every
    clearance joint of the description a dry clearance joint (Exudyn's native contact, ``native_contact``)."""
    import exudyn as exu
    from exudyn import itemInterface as ii

    y0 = start_state(linkage)
    nq = linkage.n_coordinates
    q, qd = y0[:nq], y0[nq : 2 * nq]
    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    ground = mbs.AddObject(ii.ObjectGround(referencePosition=[0.0, 0.0, 0.0]))
    nodes, bodies = [], []
    for b, body in enumerate(linkage.bodies):
        node = mbs.AddNode(ii.NodeRigidBody2D(referenceCoordinates=[float(v) for v in q[3 * b : 3 * b + 3]],
                                              initialVelocities=[float(v) for v in qd[3 * b : 3 * b + 3]]))
        obj = mbs.AddObject(ii.ObjectRigidBody2D(mass=body.mass, inertia=body.inertia, nodeNumber=node))
        nodes.append(node)
        bodies.append(obj)
        if gravity:
            mass_marker = mbs.AddMarker(ii.MarkerBodyMass(bodyNumber=obj))
            mbs.AddLoad(ii.LoadMassProportional(markerNumber=mass_marker, loadVector=[0.0, -linkage.gravity, 0.0]))

    def marker(ref):
        b = linkage.body_index(ref[0])
        x, y = linkage.point(ref)
        return mbs.AddMarker(
            ii.MarkerBodyPosition(bodyNumber=ground if b < 0 else bodies[b], localPosition=[x, y, 0.0])
        )

    for joint in linkage.joints:
        if joint.clearance is None:
            mbs.AddObject(ii.ObjectJointRevolute2D(markerNumbers=[marker(joint.bearing), marker(joint.journal)]))
        else:
            bj, bb = linkage.body_index(joint.journal[0]), linkage.body_index(joint.bearing[0])
            _dry_joint(
                mbs, joint.clearance, bodies[bj], bodies[bb], linkage.point(joint.journal), linkage.point(joint.bearing)
            )

    for spring in linkage.springs:  # a spring pulls its body point towards its rest point, per axis
        rest = mbs.AddMarker(ii.MarkerBodyPosition(bodyNumber=ground, localPosition=[*spring.rest, 0.0]))
        mbs.AddObject(
            ii.ObjectConnectorCartesianSpringDamper(
                markerNumbers=[rest, marker(spring.point)], stiffness=[*spring.stiffness, 0.0],
                damping=[*spring.damping, 0.0],
            )
        )

    # the driver acts on the driven body's rotation coordinate, which excludes its reference value theta(0)
    fixed = mbs.AddMarker(
        ii.MarkerNodeCoordinate(
            nodeNumber=mbs.AddNode(ii.NodePointGround(referenceCoordinates=[0.0, 0.0, 0.0])), coordinate=0
        )
    )
    driven = mbs.AddMarker(
        ii.MarkerNodeCoordinate(nodeNumber=nodes[linkage.body_index(linkage.driver.body)], coordinate=2)
    )
    offset, rate = _driver_offset(linkage.driver)
    driver = mbs.AddObject(
        ii.ObjectConnectorCoordinate(
            markerNumbers=[fixed, driven], offsetUserFunction=offset, offsetUserFunction_t=rate
        )
    )
    out = nodes[linkage.body_index(linkage.output)]
    acc = mbs.AddSensor(
        ii.SensorNode(nodeNumber=out, outputVariableType=exu.OutputVariableType.Coordinates_tt, storeInternal=True)
    )
    torque = mbs.AddSensor(
        ii.SensorObject(objectNumber=driver, outputVariableType=exu.OutputVariableType.Force, storeInternal=True)
    )
    mbs.Assemble()
    return sc, mbs, acc, torque


#: The hysteresis damping coefficient chi(e) of each contact law of the registry (``linkage.CONTACT_LAWS``), written
#: again here from the laws' sources (the compiled kernels hold the other writing; tests/test_crosscheck.py compares
#: them): F_N = K delta^n (1 + chi delta' / delta'(-)).
HYSTERESIS = {
    "lankarani-nikravesh": lambda e: 3.0 * (1.0 - e * e) / 4.0,
    "hunt-crossley": lambda e: 3.0 * (1.0 - e) / 2.0,
    "flores": lambda e: 8.0 * (1.0 - e) / (5.0 * e),
}


def native_contact(c: Clearance) -> dict[str, object]:
    """The parameters of Exudyn's ``ObjectContactSphereSphere`` that give a dry clearance joint's force: journal
    (marker 0) inside the hollow bearing (marker 1), K delta^n with the joint's elastic law, Hunt-Crossley damping
    (impactModel 1: 1 + 3/2 (1 - e_res) delta'/delta'(-)) with e_res = 1 - 2 chi / 3 so that it is the joint's contact
    law, no linear damping, the latched impact velocity floored at ours; friction mu up to a proportional zone of v1
    (see the module's docstring).  ValueError where the law's chi gives no positive restitution for Exudyn."""
    if np.isfinite(c.impact_velocity_ceiling):
        raise ValueError("a capped (memory-free) impact velocity has no counterpart in Exudyn's contact: latched only")
    chi = HYSTERESIS[c.contact_law](c.restitution)
    restitution = 1.0 - 2.0 * chi / 3.0
    if not restitution > 0.0:
        raise ValueError(
            f"contact law {c.contact_law!r} at restitution {c.restitution:g} has chi = {chi:g}: Exudyn's Hunt-Crossley "
            "model needs chi < 1.5"
        )
    friction = "friction" in c.effects
    return {
        "spheresRadii": [c.journal_radius, c.bearing_radius],
        "isHollowSphere1": True,
        "contactStiffness": c.elastic_stiffness,
        "contactStiffnessExponent": c.elastic_exponent,
        "contactDamping": 0.0,
        "impactModel": 1,
        "restitutionCoefficient": restitution,
        "minimumImpactVelocity": c.impact_velocity_floor,
        "dynamicFriction": c.friction if friction else 0.0,
        "frictionProportionalZone": c.v1 if friction else 1e-3,
    }


def _dry_joint(mbs, c: Clearance, journal_body, bearing_body, journal_local, bearing_local) -> None:
    """A dry clearance joint: Exudyn's native sphere-in-hollow-sphere contact between the journal and bearing points."""
    from exudyn import itemInterface as ii

    markers = [mbs.AddMarker(ii.MarkerBodyRigid(bodyNumber=body, localPosition=[x, y, 0.0]))
               for body, (x, y) in ((journal_body, journal_local), (bearing_body, bearing_local))]
    data = mbs.AddNode(
        ii.NodeGenericData(initialCoordinates=[0.1 * c.clearance, 0.0, 0.0, 0.0], numberOfDataCoordinates=4)
    )
    mbs.AddObject(ii.ObjectContactSphereSphere(markerNumbers=markers, nodeNumber=data, **native_contact(c)))


def ideal_run(
    linkage: Linkage, end_time: float, step: float, newton_tolerance: float, gravity: bool = True
) -> dict[str, np.ndarray | float]:
    """Forward dynamics of the linkage with every joint ideal in Exudyn from its start for ``end_time`` (s) with the
    fixed step ``step`` (s).  Returns the output times t (s, every step), the output body's angular acceleration
    (rad/s^2), the driver torque (N m, linkwork's sign), the solver's wall time (s) and Exudyn's version."""
    ideal = linkage.with_clearance({j.name: None for j in linkage.clearance_joints})
    return run(ideal, end_time, step, newton_tolerance, step, gravity)


def _pre_step(end_time: float, progress_s: float):
    """Exudyn's pre-step function: a progress line every ``progress_s`` seconds of wall time (simulated time, share
    done)."""
    start = last = time.perf_counter()

    def pre_step(mbs, t) -> bool:
        nonlocal last
        now = time.perf_counter()
        if now - last >= progress_s:
            last = now
            print(
                f"  Exudyn: t = {t:.4f} s of {end_time:.4f} s ({100 * t / end_time:.0f} %), {now - start:.0f} s",
                flush=True,
            )
        return True

    return pre_step


def run(linkage: Linkage, end_time: float, step: float, newton_tolerance: float, output_period: float,
        gravity: bool = True, progress_s: float = 5.0) -> dict[str, np.ndarray | float]:
    """As ``ideal_run``, with the linkage's clearance joints dry (Exudyn's native contact, friction where named), output
    every ``output_period`` (s) and a progress line every ``progress_s`` seconds of wall time (none if infinite)."""
    import exudyn as exu

    _, mbs, acc_sensor, torque_sensor = _build(linkage, gravity)
    if np.isfinite(progress_s):
        mbs.SetPreStepUserFunction(_pre_step(end_time, progress_s))
    settings = exu.SimulationSettings()
    settings.timeIntegration.endTime = end_time
    settings.timeIntegration.numberOfSteps = int(round(end_time / step))
    settings.timeIntegration.generalizedAlpha.useNewmark = True
    settings.timeIntegration.generalizedAlpha.useIndex2Constraints = True
    settings.timeIntegration.newton.useModifiedNewton = True  # the Jacobian reused while it converges
    settings.timeIntegration.newton.relativeTolerance = newton_tolerance
    settings.timeIntegration.newton.absoluteTolerance = newton_tolerance
    # the default drives the step to its minimum at the first impact; the contact is resolved by the fixed step
    settings.timeIntegration.discontinuous.useRecommendedStepSize = False
    settings.timeIntegration.verboseMode = 0
    settings.solution.file.write = False
    settings.solution.sensors.writePeriod = output_period
    if linkage.driver.cos and not linkage.clearance_joints:
        # Exudyn's initial accelerations leave out what a constraint's user function imposes (its documentation), so a
        # driver with a Fourier series would start inconsistent and the trapezoidal rule would carry the error as an
        # undamped two-step oscillation: the ideal linkage's own initial accelerations are set instead
        qdd0 = kinematics(linkage, np.array([0.0]))[2][0]
        mbs.systemData.SetODE2Coordinates_tt([float(v) for v in qdd0], configuration=exu.ConfigurationType.Initial)
        settings.timeIntegration.generalizedAlpha.computeInitialAccelerations = False
    start, cpu = time.perf_counter(), time.process_time()
    mbs.SolveDynamic(settings)
    wall, cpu = time.perf_counter() - start, time.process_time() - cpu
    acc = mbs.GetSensorStoredData(acc_sensor)
    torque = mbs.GetSensorStoredData(torque_sensor)
    if not settings.timeIntegration.generalizedAlpha.computeInitialAccelerations:
        acc, torque = acc[1:], torque[1:]  # the start's multipliers are not computed then (stored as zero)
    return {
        "t": acc[:, 0],
        "output_acceleration": acc[:, 3],
        "driver_torque": -torque[:, 1],
        "wall_s": wall,
        "cpu_s": cpu,
        "version": exu.__version__,
    }
