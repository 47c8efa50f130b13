"""Route 3, an established engine: the four-bar of ``FourBarParameters`` in Exudyn, ideal or with dry clearance joints.

Exudyn (C++ multibody engine, the optional extra ``crosscheck``) integrates the same bodies, joints,
gravity and constant-speed crank driver forward in time: three 2D rigid bodies at their centres of mass,
four revolute joints, and a coordinate constraint phi_crank = phi0 + omega t.  Nothing of linkwork's own
multibody code is used but the consistent initial state (kinematics) and the parameters.  The crank torque
is the driver constraint's force with linkwork's sign (Exudyn's multiplier acts the other way).

A dry clearance joint is a Cartesian spring-damper between the journal and bearing points whose Python user
function applies the same law as linkwork: Hertz stiffness K with Lankarani-Nikravesh damping on the impact
velocity latched when contact starts (floored, latched before each step from the accepted state), and
Ambrosio's friction with its moment about both centres (a torque load from the same contact state).

Solver: Newmark (trapezoidal) with the constraints at velocity level (index 2; the driver then reads its
time derivative omega), modified Newton iterated to ``newton_tolerance``.  The default index-3 generalized-alpha returns accelerations and multipliers that
do not converge with the step for the decoded inertias (relative differences 0.25-0.65 at 1e-4 to 1e-5 s,
positions exact to 1e-15): its algorithmic acceleration is not the mechanism's.
"""

from __future__ import annotations

import time

import numpy as np

from .model import FourBarParameters, joint_points, kinematic_state, start_angle


def _build(p: FourBarParameters, gravity: bool, clearance_joints: tuple[int, ...] = ()):
    """(system container, main system, sensor of the rocker's coordinates_tt, sensor of the driver force); the
    joints in ``clearance_joints`` (1: crank-coupler, 2: coupler-rocker) are dry clearance joints."""
    import exudyn as exu
    from exudyn import itemInterface as ii

    phi0 = start_angle(p)
    q, qd, _ = kinematic_state(p, np.array([phi0]))
    q, qd = q[0], qd[0]
    l2, l3, l4 = p.lengths
    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    ground = mbs.AddObject(ii.ObjectGround(referencePosition=[0.0, 0.0, 0.0]))
    nodes, bodies = [], []
    for b in range(3):
        node = mbs.AddNode(ii.NodeRigidBody2D(referenceCoordinates=[float(v) for v in q[3 * b : 3 * b + 3]],
                                              initialVelocities=[float(v) for v in qd[3 * b : 3 * b + 3]]))
        body = mbs.AddObject(ii.ObjectRigidBody2D(mass=p.masses[b], inertia=p.inertias[b], nodeNumber=node))
        nodes.append(node)
        bodies.append(body)
        if gravity:
            mass_marker = mbs.AddMarker(ii.MarkerBodyMass(bodyNumber=body))
            mbs.AddLoad(ii.LoadMassProportional(markerNumber=mass_marker, loadVector=[0.0, -p.gravity, 0.0]))

    def point(body: int, s: float):
        return mbs.AddMarker(ii.MarkerBodyPosition(bodyNumber=bodies[body], localPosition=[s, 0.0, 0.0]))

    crank_pivot = mbs.AddMarker(ii.MarkerBodyPosition(bodyNumber=ground, localPosition=[0.0, 0.0, 0.0]))
    rocker_pivot = mbs.AddMarker(ii.MarkerBodyPosition(bodyNumber=ground, localPosition=[p.ground, 0.0, 0.0]))
    mbs.AddObject(ii.ObjectJointRevolute2D(markerNumbers=[crank_pivot, point(0, -l2 / 2)]))
    mbs.AddObject(ii.ObjectJointRevolute2D(markerNumbers=[rocker_pivot, point(2, -l4 / 2)]))
    contacts = []
    for j, (bj, (jx, _), bb, (bx, _)) in joint_points(p.lengths).items():
        journal, bearing = point(bj, jx), point(bb, bx)
        if j in clearance_joints:
            contacts.append(_dry_joint(mbs, p, nodes[bj], nodes[bb], bodies[bj], bodies[bb], journal, bearing))
        else:
            mbs.AddObject(ii.ObjectJointRevolute2D(markerNumbers=[journal, bearing]))

    # the driver acts on the crank's rotation coordinate, which excludes its reference value phi0
    fixed = mbs.AddMarker(ii.MarkerNodeCoordinate(nodeNumber=mbs.AddNode(ii.NodePointGround(referenceCoordinates=[0.0, 0.0, 0.0])), coordinate=0))
    crank_angle = mbs.AddMarker(ii.MarkerNodeCoordinate(nodeNumber=nodes[0], coordinate=2))
    omega = p.crank_speed
    driver = mbs.AddObject(ii.ObjectConnectorCoordinate(markerNumbers=[fixed, crank_angle], offsetUserFunction=lambda mbs, t, item, offset: omega * t,
                                                        offsetUserFunction_t=lambda mbs, t, item, offset: omega))
    acc = mbs.AddSensor(ii.SensorNode(nodeNumber=nodes[2], outputVariableType=exu.OutputVariableType.Coordinates_tt, storeInternal=True))
    torque = mbs.AddSensor(ii.SensorObject(objectNumber=driver, outputVariableType=exu.OutputVariableType.Force, storeInternal=True))
    mbs.Assemble()
    return sc, mbs, acc, torque, contacts


def contact_force(p: FourBarParameters, latched: float, u, v, w_journal: float, w_bearing: float) -> tuple[list[float], float]:
    """The dry joint's force in Exudyn's convention and the friction force ft (N): u = journal centre - bearing
    centre (m), v its rate (m/s), w the bodies' angular velocities (rad/s), ``latched`` the impact velocity of
    this contact (m/s, floored here).  The journal receives minus the returned vector: (-F_N) n + ft t."""
    e = (u[0] * u[0] + u[1] * u[1]) ** 0.5
    if e <= p.clearance:
        return [0.0, 0.0, 0.0], 0.0
    nx, ny = u[0] / e, u[1] / e
    chi = 3.0 * (1.0 - p.restitution**2) / 4.0  # Lankarani-Nikravesh
    factor = 1.0 + chi * (v[0] * nx + v[1] * ny) / max(latched, p.impact_velocity_floor)
    fn = p.hertz_stiffness * (e - p.clearance) ** 1.5 * max(factor, 0.0)
    v_t = -v[0] * ny + v[1] * nx + w_journal * p.journal_radius - w_bearing * p.bearing_radius
    slip = abs(v_t)
    if slip <= p.v0:
        mu = 0.0
    else:
        mu = p.friction * (1.0 if slip >= p.v1 else (slip - p.v0) / (p.v1 - p.v0)) * (-1.0 if v_t > 0 else 1.0)
    ft = mu * fn
    return [fn * nx + ft * ny, fn * ny - ft * nx, 0.0], ft


def _dry_joint(mbs, p: FourBarParameters, journal_node, bearing_node, journal_body, bearing_body, journal, bearing):
    """A dry clearance joint between the markers ``journal`` and ``bearing``; returns its latch (a pre-step function)."""
    import exudyn as exu
    from exudyn import itemInterface as ii

    c = p.clearance
    state = {"latched": 0.0, "in_contact": False, "ft": 0.0}
    angular = exu.OutputVariableType.AngularVelocity

    def force(mbs, t, item, u, v, stiffness, damping, offset):
        w_j, w_b = mbs.GetNodeOutput(journal_node, angular)[2], mbs.GetNodeOutput(bearing_node, angular)[2]
        f, state["ft"] = contact_force(p, state["latched"], u, v, w_j, w_b)
        return f

    mbs.AddObject(ii.ObjectConnectorCartesianSpringDamper(markerNumbers=[bearing, journal], stiffness=[0.0, 0.0, 0.0],
                                                          damping=[0.0, 0.0, 0.0], springForceUserFunction=force))
    for body, radius in ((journal_body, p.journal_radius), (bearing_body, -p.bearing_radius)):
        marker = mbs.AddMarker(ii.MarkerBodyRigid(bodyNumber=body, localPosition=[0.0, 0.0, 0.0]))
        mbs.AddLoad(ii.LoadTorqueVector(markerNumber=marker, loadVectorUserFunction=lambda mbs, t, load, r=radius: [0.0, 0.0, r * state["ft"]]))
    position, velocity = exu.OutputVariableType.Position, exu.OutputVariableType.Velocity

    def latch(mbs) -> bool:
        pj, pb = mbs.GetMarkerOutput(journal, position), mbs.GetMarkerOutput(bearing, position)
        vj, vb = mbs.GetMarkerOutput(journal, velocity), mbs.GetMarkerOutput(bearing, velocity)
        ex, ey = pj[0] - pb[0], pj[1] - pb[1]
        e = (ex * ex + ey * ey) ** 0.5
        now = e > c
        if now and not state["in_contact"]:
            state["latched"] = abs(((vj[0] - vb[0]) * ex + (vj[1] - vb[1]) * ey) / e)
        state["in_contact"] = now
        return True

    return latch


def ideal_run(p: FourBarParameters, end_time: float, step: float, newton_tolerance: float, gravity: bool = True) -> dict[str, np.ndarray | float]:
    """Forward dynamics of the ideal four-bar in Exudyn from the dead point for ``end_time`` (s) with the
    fixed step ``step`` (s).  Returns the output times t (s, every step), the rocker's angular acceleration
    (rad/s^2), the crank torque (N m, linkwork's sign), the solver's wall time (s) and Exudyn's version."""
    return run(p, end_time, step, newton_tolerance, step, (), gravity)


def _pre_step(latches, end_time: float, progress_s: float):
    """Exudyn's pre-step function: latch every dry joint's impact velocity; print a progress line every
    ``progress_s`` seconds of wall time (simulated time, share done)."""
    start = last = time.perf_counter()

    def pre_step(mbs, t) -> bool:
        nonlocal last
        for latch in latches:
            latch(mbs)
        now = time.perf_counter()
        if now - last >= progress_s:
            last = now
            print(f"  Exudyn: t = {t:.4f} s of {end_time:.4f} s ({100 * t / end_time:.0f} %), {now - start:.0f} s", flush=True)
        return True

    return pre_step


def run(p: FourBarParameters, end_time: float, step: float, newton_tolerance: float, output_period: float,
        clearance_joints: tuple[int, ...] = (), gravity: bool = True, progress_s: float = 5.0) -> dict[str, np.ndarray | float]:
    """As ``ideal_run``, with dry clearance joints, output every ``output_period`` (s) and a progress line
    every ``progress_s`` seconds of wall time."""
    import exudyn as exu

    _, mbs, acc_sensor, torque_sensor, latches = _build(p, gravity, tuple(clearance_joints))
    mbs.SetPreStepUserFunction(_pre_step(latches, end_time, progress_s))
    settings = exu.SimulationSettings()
    settings.timeIntegration.endTime = end_time
    settings.timeIntegration.numberOfSteps = int(round(end_time / step))
    settings.timeIntegration.generalizedAlpha.useNewmark = True
    settings.timeIntegration.generalizedAlpha.useIndex2Constraints = True
    settings.timeIntegration.newton.useModifiedNewton = True  # the Jacobian of the Python force is numerical: reused, 4x faster
    settings.timeIntegration.newton.relativeTolerance = newton_tolerance
    settings.timeIntegration.newton.absoluteTolerance = newton_tolerance
    settings.timeIntegration.verboseMode = 0
    settings.solution.file.write = False
    settings.solution.sensors.writePeriod = output_period
    start = time.perf_counter()
    mbs.SolveDynamic(settings)
    wall = time.perf_counter() - start
    acc = mbs.GetSensorStoredData(acc_sensor)
    torque = mbs.GetSensorStoredData(torque_sensor)
    return {"t": acc[:, 0], "rocker_acceleration": acc[:, 3], "crank_torque": -torque[:, 1], "wall_s": wall, "version": exu.__version__}
