"""Time integration of a compiled scene: explicit RK4, Dormand-Prince 5(4) and 8(5,3) (DOP853, scipy's algorithm
with its dense output) and the implicit variable-order NDF (a compiled port of scipy's BDF; all in ``integrators``,
compiled once for every scene), or one of scipy's integrators (implicit BDF / Radau / LSODA, explicit RK45 /
DOP853 as ``scipy-dop853``) stepped from Python around the compiled right-hand side.

An integrator setting is a mapping ``{method, step_s}`` (rk4) or ``{method, rtol, atol, first_step_s,
max_step_s}`` (the others; scipy's without ``first_step_s`` guess their own); times in s.  ``READS`` holds the keys
each method reads, which config/schema.yaml requires for it; a run checks them (``check_integrator``), refuses a
stretch that would take more than ``STEP_LIMIT`` steps, and ends one that stops advancing (the compiled integrators'
``STALL_STEPS``), each in one line naming the key to change (``LinkageError``).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from ...compilecache import compile_once
from . import integrators
from .assembly import start_state
from .linkage import Linkage, LinkageError
from .model import compile_scene, n_state, pack

SCIPY = ("bdf", "radau", "lsoda", "rk45", "scipy-dop853")  # scipy.integrate's OdeSolver classes, by lower-case name
METHODS = ("rk4", "dopri5", "dop853", "ndf", *SCIPY)
#: The keys of an integrator setting each method reads (config/schema.yaml requires the same for each method).
READS = {
    "rk4": ("step_s",),
    **dict.fromkeys(("dopri5", "dop853", "ndf"), ("rtol", "atol", "first_step_s", "max_step_s")),
    **dict.fromkeys(SCIPY, ("rtol", "atol", "max_step_s")),
}
#: At most this many steps in one stretch of a run (``Run.advance``), counted before it starts (at least the stretch
#: over ``step_s`` for rk4, over ``max_step_s`` for the others): a size guard against a slip of a setting (a step of
#: 1e-9 s over a second is 1e9 steps: rk4 takes 5.6 us a step on the shipped six-bar here, so 1.6 h that look like a
#: hang; 1e8 steps are 9 minutes).
STEP_LIMIT = 100_000_000


def check_integrator(integrator: Mapping[str, Any], key: str = "integrator") -> None:
    """An integrator setting a run can start from: a known method, and every key it reads (``READS``), and any optional
    one given, a positive finite number (LinkageError naming the key, ``key`` that of the setting)."""
    method = integrator.get("method")
    if method not in READS:
        raise LinkageError(f"{key}.method", f"unknown integrator {method!r}; known: {', '.join(METHODS)}")
    for name in (*READS[method], *(n for n in ("first_step_s",) if n in integrator and n not in READS[method])):
        value = integrator.get(name)
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) or value <= 0:
            raise LinkageError(f"{key}.{name}", f"the method {method} reads it: a positive number, got {value!r}")


def least_steps(integrator: Mapping[str, Any], span: float) -> tuple[str, float]:
    """The key that bounds a run's step from above (``step_s`` for rk4, ``max_step_s`` otherwise) and the fewest
    steps a stretch of ``span`` seconds can then take."""
    name = "step_s" if integrator["method"] == "rk4" else "max_step_s"
    return name, span / integrator[name]


def stall_key(integrator: Mapping[str, Any], h: float) -> tuple[str, float]:
    """The key to change when a run stops advancing, having started the stretch from the step ``h`` (s), and the step
    it gave: rk4's ``step_s``; else ``max_step_s`` where it is no positive step; else ``first_step_s`` (h)."""
    if integrator["method"] == "rk4":
        return "step_s", integrator["step_s"]
    if not integrator["max_step_s"] > 0:
        return "max_step_s", integrator["max_step_s"]
    return "first_step_s", h


class Run:
    """A scene's run that can be continued: the state y, the time t (s), the contact memory (the impact velocity
    latched at each clearance joint's last impact, m/s, and whether it is in contact) and the integrator's next
    step (s).  ``advance(t_out)`` integrates from t to t_out[-1] and samples at t_out (t_out[0] == t), so that a
    run cut into pieces is the run in one piece, up to the step size chosen at each cut.

    ``memory()`` is the run's whole state as one vector (t, y, latched, in contact): a run restarted from it
    (``Run(..., memory=...)``) continues the same motion; a Poincaré section point that holds it can be restarted."""

    def __init__(
        self, linkage: Linkage, gravity: bool, integrator: Mapping[str, Any], y0=None, t0: float = 0.0, memory=None,
        key: str = "integrator",
    ):
        check_integrator(integrator, key)
        self.key = key  # the config key of the integrator setting, for messages
        self.module = compile_scene(linkage, gravity)
        self.integrator = dict(integrator)
        self.params, _ = pack(linkage)
        n, ns = max(len(linkage.clearance_joints), 1), n_state(linkage)
        if memory is not None:
            memory = np.asarray(memory, dtype=float)
            t0, y = float(memory[0]), memory[1:]
            self.y, self.latched, self.was = y[:ns].copy(), y[ns : ns + n].copy(), y[ns + n :] > 0.5
        else:
            self.y = start_state(linkage) if y0 is None else np.asarray(y0, dtype=float).copy()
            self.latched, self.was = np.zeros(n), np.zeros(n, dtype=bool)
        self.t = float(t0)
        self.h = integrator.get("first_step_s", integrator.get("step_s"))  # the next step of the compiled integrators
        self.counts = np.zeros(4, dtype=np.int64)
        self.steps = self.rejected = 0
        self.fallbacks = 0  # stretches the compiled NDF gave up on and scipy's BDF integrated instead

    def memory(self) -> np.ndarray:
        """(t (s), y, latched impact velocity per joint (m/s), 1 where in contact per joint): the run's whole state."""
        return np.concatenate([[self.t], self.y, self.latched, self.was.astype(float)])

    def advance(self, t_out: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Integrate to t_out[-1] (s), sampling states and diagnostics at t_out; returns (states, diagnostics)."""
        t_out = np.asarray(t_out, dtype=float)
        if abs(t_out[0] - self.t) > 1e-12 * max(1.0, abs(self.t)):
            raise ValueError(f"a run at t = {self.t} s cannot sample from t = {t_out[0]} s")
        integ, span = self.integrator, float(t_out[-1] - t_out[0])
        name, least = least_steps(integ, span)
        if least > STEP_LIMIT:
            raise LinkageError(
                f"{self.key}.{name}",
                f"{integ[name]!r} s takes at least {least:.3g} steps for the {span:g} s from t = {self.t:g} s (a size"
                f" guard: STEP_LIMIT = {STEP_LIMIT:.0e} steps in lib/linkwork/engines/multibody/simulate.py)",
            )
        t_out = np.ascontiguousarray(t_out)
        try:
            ys, diags, steps, rejected = self._integrate(t_out)
        except RuntimeError as exc:
            if "did not advance" not in str(exc):
                raise
            name, step = stall_key(integ, self.h)
            raise LinkageError(
                f"{self.key}.{name}",
                f"the run stopped advancing after t = {self.t:g} s ({exc}: a step of {step!r} s leaves it unchanged)",
            ) from None
        self.y, self.t = ys[-1].copy(), float(t_out[-1])
        self.steps += int(steps)
        self.rejected += int(rejected)
        return ys, diags

    def _integrate(self, t_out: np.ndarray):
        """The stretch to t_out[-1] by the setting's method: (states, diagnostics, accepted, rejected steps)."""
        integ, method = self.integrator, self.integrator["method"]
        if method in ("rk4", "dopri5", "dop853", "ndf"):
            scene = rhs_into(self.module), self.module.N_WORK, self.module.N_DIAG
            compiled = integrators.ready(method)
        if method == "rk4":
            ys, diags, steps, rejected, _ = compiled(
                *scene, self.y, self.t, integ["step_s"], t_out, self.params, self.latched, self.counts, self.was
            )
        elif method in ("dopri5", "dop853"):
            ys, diags, steps, rejected, self.h = compiled(
                *scene, self.y, self.t, t_out, self.params, self.latched, self.counts, integ["rtol"], integ["atol"],
                self.h, integ["max_step_s"], self.was,
            )
        elif method == "ndf":
            saved = self.latched.copy(), self.was.copy(), self.counts.copy()
            try:
                ys, diags, steps, rejected, self.h = compiled(
                    *scene, self.y, self.t, t_out, self.params, self.latched, self.counts, integ["rtol"],
                    integ["atol"], self.h, integ["max_step_s"], self.was,
                )
            except (
                RuntimeError
            ):  # a step size underflow: this stretch again with scipy's BDF, the same algorithm in Python
                self.latched[:], self.was[:], self.counts[:] = saved
                ys, diags, steps, rejected = _scipy(
                    self.module, self.y, t_out, self.params, self.latched, self.counts, {**integ, "method": "bdf"},
                    self.was,
                )
                self.fallbacks += 1
        elif method in SCIPY:
            ys, diags, steps, rejected = _scipy(
                self.module, self.y, t_out, self.params, self.latched, self.counts, integ, self.was
            )
        else:
            raise ValueError(f"unknown integrator {method!r}; known: {', '.join(METHODS)}")
        return ys, diags, steps, rejected


def integrate(linkage: Linkage, gravity: bool, t_out, integrator: Mapping[str, Any], y0=None):
    """Run a scene from its consistent start (or ``y0``) and sample it at ``t_out`` (s, from 0).

    Returns (states, diagnostics, accepted steps, rejected steps, effect evaluation counts).
    """
    run = Run(linkage, gravity, integrator, y0=y0)
    ys, diags = run.advance(t_out)
    return ys, diags, run.steps, run.rejected, run.counts


def rhs_into(module):
    """The scene's compiled ``rhs_into`` (compiled for ``integrators.RHS_INTO`` or loaded from the cache, one process
    at a time), as the integrators take it."""
    compile_once(module.rhs_into, integrators.RHS_INTO, f"{module.__name__}.rhs_into")
    return module.rhs_into


def _scipy(module, y0, t_out, params, latched, counts, integrator, was):
    """A scipy integrator stepped from Python around the compiled right-hand side (the implicit ones with its
    compiled finite-difference Jacobian), with the impact velocity latched at accepted steps and dense output
    at t_out."""
    from scipy import integrate as si

    diag = np.zeros(module.N_DIAG)
    scratch = np.zeros(module.N_DIAG)
    solver_cls = {"bdf": si.BDF, "radau": si.Radau, "lsoda": si.LSODA, "rk45": si.RK45, "scipy-dop853": si.DOP853}[
        integrator["method"]
    ]
    fun = lambda t, y: module.rhs(t, y, params, latched, counts, scratch)  # noqa: E731
    jacobian, latch, scene = integrators.ready("jacobian"), integrators.ready("latch"), rhs_into(module)
    jac = lambda t, y: jacobian(  # noqa: E731
        scene, module.N_WORK, t, np.ascontiguousarray(y), params, latched, counts, scratch
    )
    ys = np.empty((t_out.size, y0.size))
    diags = np.empty((t_out.size, module.N_DIAG))
    module.rhs(t_out[0], y0, params, latched, counts, diag)
    latch(diag, latched, was)
    ys[0], diags[0] = y0, diag
    i = 1
    with np.errstate(over="ignore", invalid="ignore"):  # scipy's numerical Jacobian probes far steps
        implicit = {"jac": jac} if integrator["method"] in ("bdf", "radau", "lsoda") else {}
        solver = solver_cls(
            fun, t_out[0], y0, t_out[-1], rtol=integrator["rtol"], atol=integrator["atol"],
            max_step=integrator["max_step_s"], first_step=integrator.get("first_step_s"), **implicit,
        )
        steps = 0
        while solver.status == "running":
            solver.step()
            steps += 1
            if solver.status == "failed":
                raise RuntimeError(f"{integrator['method']}: step failed at t = {solver.t}")
            module.rhs(solver.t, solver.y, params, latched, counts, diag)
            latch(diag, latched, was)
            if i < t_out.size and t_out[i] <= solver.t:
                stop = int(np.searchsorted(t_out, solver.t + 1e-15, side="right"))
                ys[i:stop] = solver.dense_output()(t_out[i:stop]).T
                for k in range(i, stop):
                    module.rhs(t_out[k], ys[k], params, latched, counts, diags[k])
                i = stop
    return ys, diags, steps, 0
