"""Section optimisation by the paper's mixed penalty function (SUMT, eqs. 9-16) and by SLSQP.

Design variables: member diameters x (m).  Given a function returning each member's largest
stress |sigma_i,max|(x) (Pa), the paper's objective is

    SS(x, r) = SY + SZ + SG + SH
    SY = sum_i (1 - |sigma_i,max| / [sigma])^2                       (10)
    SZ = sum_i (x_i l_i / ([x_S1] l_1))^2                            (11)
    SG = r sum_u 1 / g_u(x)                                          (12)
    SH = r^(-1/2) sum_v h_v(x)^2   (the paper has no equality constraint) (13)
    g_i = 100 (x_i - d_min) >= 0,  g_(4+i) = 1 - |sigma_i,max| / [sigma] >= 0   (15), (16)

minimised for a decreasing sequence r(k).  SG is an interior barrier, so a start outside the
feasible set needs help: constraints violated at x are penalised by the exterior term
r^(-1/2) g^2 instead (the mixed form of Fiacco and McCormick), which walks the iterate into the
feasible set, where the barrier then keeps it.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class PenaltyProblem:
    """The section-design problem: stresses(x) -> (n,) Pa for diameters x (m)."""

    stresses: Callable[[FloatArray], FloatArray]
    lengths: FloatArray  # m
    allowable: float  # Pa
    reference_diameter: float  # [x_S1], m
    minimum_diameter: float  # m

    def constraints(self, x: FloatArray) -> FloatArray:
        sigma = np.abs(self.stresses(x))
        return np.concatenate([100.0 * (np.asarray(x) - self.minimum_diameter), 1.0 - sigma / self.allowable])

    def parts(self, x: FloatArray, r: float) -> dict[str, float]:
        """SY, SZ, SG, SH (the mixed barrier/exterior form), SS and the constraints at x."""
        x = np.asarray(x, dtype=float)
        sigma = np.abs(self.stresses(x))
        g = np.concatenate([100.0 * (x - self.minimum_diameter), 1.0 - sigma / self.allowable])
        sy = float(np.sum((1.0 - sigma / self.allowable) ** 2))
        sz = float(np.sum((x * self.lengths / (self.reference_diameter * self.lengths[0])) ** 2))
        ok = g > 0
        sg = float(
            r * np.sum(1.0 / g[ok]) + r**-0.5 * np.sum(g[~ok] ** 2) + (1e6 * np.sum(~ok) if (~ok).any() else 0.0)
        )
        sh = 0.0
        return {"SY": sy, "SZ": sz, "SG": sg, "SH": sh, "SS": sy + sz + sg + sh, "g": g, "sigma": sigma}

    def ss(self, x: FloatArray, r: float) -> float:
        return self.parts(x, r)["SS"]


@dataclass
class SumtResult:
    x: FloatArray
    history: list[dict] = field(default_factory=list)
    evaluations: int = 0


def sumt(
    problem: PenaltyProblem,
    x0: FloatArray,
    r0: float,
    factor: float,
    iterations: int,
    xtol: float,
    inner_maxiter: int = 2000,
) -> SumtResult:
    """Minimise SS(x, r(k)) for r(k) = r0 factor^k, k = 0..iterations-1, each from the previous optimum.

    Inner minimiser: Nelder-Mead in millimetres (xtol in m).  The history holds, per k, r, x and
    the objective parts.
    """
    from scipy.optimize import minimize

    x = np.asarray(x0, dtype=float)
    result = SumtResult(x)
    for k in range(iterations):
        r = r0 * factor**k
        res = minimize(
            lambda y, r=r: problem.ss(y * 1e-3, r),
            x * 1e3,
            method="Nelder-Mead",
            options={"xatol": xtol * 1e3, "fatol": 1e-10, "maxiter": inner_maxiter, "maxfev": inner_maxiter},
        )
        x_new = res.x * 1e-3
        result.evaluations += int(res.nfev)
        parts = problem.parts(x_new, r)
        result.history.append(
            {
                "k": k,
                "r": r,
                "x": x_new.copy(),
                **{p: parts[p] for p in ("SY", "SZ", "SG", "SH", "SS")},
                "g": parts["g"].copy(),
            }
        )
        converged = np.max(np.abs(x_new - x)) < xtol and k > 0
        x = x_new
        if converged:
            break
    result.x = x
    return result


def slsqp(problem: PenaltyProblem, x0: FloatArray, ftol: float = 1e-10, maxiter: int = 200) -> tuple[FloatArray, dict]:
    """Cross-check: minimise SY + SZ subject to g(x) >= 0 as explicit constraints (scipy SLSQP, in mm)."""
    from scipy.optimize import minimize

    fun = lambda y: (lambda p: p["SY"] + p["SZ"])(problem.parts(y * 1e-3, 1.0))  # noqa: E731
    cons = {"type": "ineq", "fun": lambda y: problem.constraints(y * 1e-3)}
    res = minimize(
        fun, np.asarray(x0) * 1e3, method="SLSQP", constraints=[cons], options={"ftol": ftol, "maxiter": maxiter}
    )
    return res.x * 1e-3, {
        "success": bool(res.success),
        "message": str(res.message),
        "evaluations": int(res.nfev),
        "objective": float(res.fun),
    }


def gradient(f: Callable[[FloatArray], float], x: FloatArray, step: float) -> FloatArray:
    """Central-difference gradient (step in the units of x)."""
    x = np.asarray(x, dtype=float)
    g = np.empty_like(x)
    for i in range(x.size):
        e = np.zeros_like(x)
        e[i] = step
        g[i] = (f(x + e) - f(x - e)) / (2 * step)
    return g
