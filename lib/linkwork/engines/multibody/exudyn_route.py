"""Route 3, an established engine: the ideal four-bar of ``FourBarParameters`` in Exudyn.

Exudyn (C++ multibody engine, the optional extra ``crosscheck``) integrates the same bodies, joints,
gravity and constant-speed crank driver forward in time: three 2D rigid bodies at their centres of mass,
four revolute joints, and a coordinate constraint phi_crank = phi0 + omega t.  Nothing of linkwork's own
multibody code is used but the consistent initial state (kinematics) and the parameters.  The crank torque
is the driver constraint's force with linkwork's sign (Exudyn's multiplier acts the other way).

Solver: Newmark (trapezoidal) with the constraints at velocity level (index 2; the driver then reads its
time derivative omega).  The default index-3 generalized-alpha returns accelerations and multipliers that
do not converge with the step for the decoded inertias (relative differences 0.25-0.65 at 1e-4 to 1e-5 s,
positions exact to 1e-15): its algorithmic acceleration is not the mechanism's.
"""

from __future__ import annotations

import time

import numpy as np

from .model import FourBarParameters, kinematic_state, start_angle


def available() -> bool:
    """True if the optional extra (Exudyn) is installed."""
    import importlib.util

    return importlib.util.find_spec("exudyn") is not None


def _build(p: FourBarParameters, gravity: bool):
    """(system container, main system, sensor of the rocker's coordinates_tt, sensor of the driver force)."""
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
    mbs.AddObject(ii.ObjectJointRevolute2D(markerNumbers=[point(0, l2 / 2), point(1, -l3 / 2)]))
    mbs.AddObject(ii.ObjectJointRevolute2D(markerNumbers=[point(1, l3 / 2), point(2, l4 / 2)]))
    mbs.AddObject(ii.ObjectJointRevolute2D(markerNumbers=[rocker_pivot, point(2, -l4 / 2)]))
    # the driver acts on the crank's rotation coordinate, which excludes its reference value phi0
    fixed = mbs.AddMarker(ii.MarkerNodeCoordinate(nodeNumber=mbs.AddNode(ii.NodePointGround(referenceCoordinates=[0.0, 0.0, 0.0])), coordinate=0))
    crank_angle = mbs.AddMarker(ii.MarkerNodeCoordinate(nodeNumber=nodes[0], coordinate=2))
    omega = p.crank_speed
    driver = mbs.AddObject(ii.ObjectConnectorCoordinate(markerNumbers=[fixed, crank_angle], offsetUserFunction=lambda mbs, t, item, offset: omega * t,
                                                        offsetUserFunction_t=lambda mbs, t, item, offset: omega))
    acc = mbs.AddSensor(ii.SensorNode(nodeNumber=nodes[2], outputVariableType=exu.OutputVariableType.Coordinates_tt, storeInternal=True))
    torque = mbs.AddSensor(ii.SensorObject(objectNumber=driver, outputVariableType=exu.OutputVariableType.Force, storeInternal=True))
    mbs.Assemble()
    return sc, mbs, acc, torque


def ideal_run(p: FourBarParameters, end_time: float, step: float, newton_tolerance: float, gravity: bool = True) -> dict[str, np.ndarray | float]:
    """Forward dynamics of the ideal four-bar in Exudyn from the dead point for ``end_time`` (s) with the
    fixed step ``step`` (s).  Returns the output times t (s, every step), the rocker's angular acceleration
    (rad/s^2), the crank torque (N m, linkwork's sign), the solver's wall time (s) and Exudyn's version."""
    import exudyn as exu

    _, mbs, acc_sensor, torque_sensor = _build(p, gravity)
    settings = exu.SimulationSettings()
    settings.timeIntegration.endTime = end_time
    settings.timeIntegration.numberOfSteps = int(round(end_time / step))
    settings.timeIntegration.generalizedAlpha.useNewmark = True
    settings.timeIntegration.generalizedAlpha.useIndex2Constraints = True
    settings.timeIntegration.newton.useModifiedNewton = False
    settings.timeIntegration.newton.relativeTolerance = newton_tolerance
    settings.timeIntegration.newton.absoluteTolerance = newton_tolerance
    settings.timeIntegration.verboseMode = 0
    settings.solution.file.write = False
    settings.solution.sensors.writePeriod = step
    start = time.perf_counter()
    mbs.SolveDynamic(settings)
    wall = time.perf_counter() - start
    acc = mbs.GetSensorStoredData(acc_sensor)
    torque = mbs.GetSensorStoredData(torque_sensor)
    return {"t": acc[:, 0], "rocker_acceleration": acc[:, 3], "crank_torque": -torque[:, 1], "wall_s": wall, "version": exu.__version__}
