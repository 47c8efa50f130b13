"""Time integration of a compiled scene: explicit RK4 / Dormand-Prince (compiled, in the scene
module) or one of scipy's integrators (implicit BDF / Radau / LSODA, explicit RK45 / DOP853) stepped from
Python around the compiled right-hand side.

An integrator setting is a mapping ``{method, step_s}`` (rk4) or ``{method, rtol, atol, first_step_s,
max_step_s}`` (the others); times in s.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from .model import FourBarParameters, compile_scene, initial_state, pack

SCIPY = ("bdf", "radau", "lsoda", "rk45", "dop853")  # scipy.integrate's OdeSolver classes, by lower-case name
METHODS = ("rk4", "dopri5", *SCIPY)


def integrate(p: FourBarParameters, joints, effects, t_out, integrator: Mapping[str, Any], y0=None):
    """Run a scene from its consistent initial state (or ``y0``) and sample it at ``t_out`` (s).

    Returns (states, diagnostics, accepted steps, rejected steps, effect evaluation counts, phi0).
    """
    module = compile_scene(tuple(joints), tuple(effects), p.contact_law)
    if y0 is None:
        y0, phi0 = initial_state(p)
    else:
        phi0 = initial_state(p)[1]
    params, _ = pack(p, phi0)
    latched = np.zeros(max(len(joints), 1))
    counts = np.zeros(4, dtype=np.int64)
    method = integrator["method"]
    if method == "rk4":
        ys, diags, steps, rejected = module.rk4(y0, 0.0, integrator["step_s"], t_out, params, latched, counts)
    elif method == "dopri5":
        ys, diags, steps, rejected = module.dopri5(
            y0, 0.0, t_out, params, latched, counts, integrator["rtol"], integrator["atol"], integrator["first_step_s"], integrator["max_step_s"]
        )
    elif method in SCIPY:
        ys, diags, steps, rejected = _scipy(module, y0, t_out, params, latched, counts, integrator)
    else:
        raise ValueError(f"unknown integrator {method!r}; known: {', '.join(METHODS)}")
    return ys, diags, int(steps), int(rejected), counts, phi0


def _scipy(module, y0, t_out, params, latched, counts, integrator):
    """A scipy integrator stepped from Python around the compiled right-hand side (the implicit ones with its
    compiled finite-difference Jacobian), with the impact velocity latched at accepted steps and dense output
    at t_out."""
    from scipy import integrate as si

    diag = np.zeros(module.N_DIAG)
    scratch = np.zeros(module.N_DIAG)
    was = np.zeros(max(len(module.JOINTS), 1), dtype=bool)
    solver_cls = {"bdf": si.BDF, "radau": si.Radau, "lsoda": si.LSODA, "rk45": si.RK45, "dop853": si.DOP853}[integrator["method"]]
    fun = lambda t, y: module.rhs(t, y, params, latched, counts, scratch)  # noqa: E731
    jac = lambda t, y: module.jacobian(t, y, params, latched, counts, scratch)  # noqa: E731
    ys = np.empty((t_out.size, y0.size))
    diags = np.empty((t_out.size, module.N_DIAG))
    module.rhs(t_out[0], y0, params, latched, counts, diag)
    module._latch(diag, latched, was)
    ys[0], diags[0] = y0, diag
    i = 1
    with np.errstate(over="ignore", invalid="ignore"):  # scipy's numerical Jacobian probes far steps
        implicit = {"jac": jac} if integrator["method"] in ("bdf", "radau", "lsoda") else {}
        solver = solver_cls(fun, t_out[0], y0, t_out[-1], rtol=integrator["rtol"], atol=integrator["atol"], max_step=integrator["max_step_s"], **implicit)
        steps = 0
        while solver.status == "running":
            solver.step()
            steps += 1
            if solver.status == "failed":
                raise RuntimeError(f"{integrator['method']}: step failed at t = {solver.t}")
            module.rhs(solver.t, solver.y, params, latched, counts, diag)
            module._latch(diag, latched, was)
            if i < t_out.size and t_out[i] <= solver.t:
                dense = solver.dense_output()
                while i < t_out.size and t_out[i] <= solver.t + 1e-15:
                    y_i = dense(t_out[i])
                    module.rhs(t_out[i], y_i, params, latched, counts, scratch)
                    ys[i], diags[i] = y_i, scratch.copy()
                    i += 1
    return ys, diags, steps, 0
