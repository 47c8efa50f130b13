"""What the heald chains say beyond the claims' measures: damping ratios of the modes, the joint reactions
from the mechanism's own kinetostatics, the flip points of the verdicts, and a dwell cam's harmonics.

All SI units (rad/s, m, N, kg); ``p`` is the parameter dict of :mod:`.model`.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping

import numpy as np

from ...engines.chains import Network, assemble_matrices, solve_network
from .model import build, drive_frequency

# --- the joint forces of a chain ---


def joint_forces(model: str, p: Mapping[str, float], variant: str, omega: np.ndarray, amplitude: float):
    """(input force, Q_E, Q_F, singular) at main-shaft frequencies ``omega`` (rad/s) for a drive displacement
    amplitude (m): the chain is driven at w_d = drive_ratio x omega, V = j w_d X."""
    wd = drive_frequency(p, omega)
    r = solve_network(build(model, p, variant), wd, 1j * wd * amplitude)
    q_e = r.element_force["joint_E"] + r.element_force["joint_E_damping"]
    q_f = r.element_force["joint_F"] + r.element_force["joint_F_damping"]
    return r.input_force, q_e, q_f, r.singular


# --- damping ratios ------------------------------------------------------------------------------


def damped_modes(net: Network, held: bool = True) -> tuple[np.ndarray, np.ndarray]:
    """(undamped natural frequency |lambda| in rad/s, damping ratio -Re(lambda)/|lambda|) of every mode,
    ascending, from the complex eigenvalues of the damped chain.

    ``held``: the driven node held (the resonances a kinematic drive excites, K = 0); else free (the
    antiresonances, K -> infinity).  Needs a non-singular reduced mass matrix; returns empty arrays otherwise
    (a free massless driven node).
    """
    from scipy.linalg import null_space

    m, k, c, g = assemble_matrices(net)
    n = m.shape[0]
    rows = [g] + ([np.eye(n)[net.index[net.drive_node]]] if held else [])
    con = np.vstack([r for r in rows if r.size]) if any(r.size for r in rows) else np.zeros((0, n))
    t = null_space(con) if con.shape[0] else np.eye(n)
    mr, kr, cr = t.T @ m @ t, t.T @ k @ t, t.T @ c @ t
    if mr.shape[0] == 0 or np.linalg.cond(mr) > 1e12:
        return np.array([]), np.array([])
    minv = np.linalg.inv(mr)
    d = mr.shape[0]
    a = np.block([[np.zeros((d, d)), np.eye(d)], [-minv @ kr, -minv @ cr]])
    lam = np.linalg.eigvals(a)
    lam = lam[lam.imag >= 0]  # one of each conjugate pair (an overdamped pair gives two real ones)
    wn = np.abs(lam)
    keep = wn > 1e-9 * max(wn.max(initial=0.0), 1.0)
    wn, zeta = wn[keep], -lam.real[keep] / wn[keep]
    zeta = np.where(
        zeta > 0.0, zeta, 0.0
    )  # an undamped mode gives -0.0 or a round-off negative: no negative damping here
    order = np.argsort(wn)
    return wn[order], zeta[order]


# --- reactions from the mechanism's kinetostatics ------------------------------------------------


def kinetostatic_reactions(model: str, p: Mapping[str, float]) -> tuple[float, float]:
    """(|R_E|, |R_F|) of the ideal-joint chain (pins of stiffness k_n, no clearance) driven with the heald
    stroke ``stroke_D`` at the operating speed ``omega_op``: the kinetostatic reactions (first harmonic)."""

    w = np.array([p["omega_op"]])
    _, q_e, q_f, _ = joint_forces(model, p, "ideal", w, p["stroke_D"])
    return float(np.abs(q_e[0])), float(np.abs(q_f[0]))


def self_consistent_reactions(p: Mapping[str, float], model: str = "A") -> dict[str, float]:
    """Reactions that reproduce themselves: R = |Q(omega_op; k_tau(R))| of the elastic chain under the heald
    stroke at the operating speed (Vulfson's stiffness fed by the forces it produces).

    Returns R_E, R_F, their ratio, and the slope of the fixed-point map along the split at that point
    (1 would make every split self-consistent).
    """
    from scipy.optimize import root


    w = np.array([p["omega_op"]])

    def forces(r: np.ndarray) -> np.ndarray:
        q = {**p, "reaction_E": abs(r[0]), "reaction_F": abs(r[1])}
        _, q_e, q_f, _ = joint_forces(model, q, "elastic", w, p["stroke_D"])
        return np.array([abs(q_e[0]), abs(q_f[0])])

    start = np.array(kinetostatic_reactions(model, p))
    sol = root(lambda r: forces(r) - r, start, method="hybr", options={"xtol": 1e-12})
    r = np.abs(sol.x)
    # slope of the map along the split (R_E up, R_F down by the same amount), by a central difference
    h = 1e-4 * r.sum()
    d = np.array([1.0, -1.0])
    slope = float(d @ (forces(r + h * d) - forces(r - h * d)) / (2 * h) / 2.0)
    return {"R_E": float(r[0]), "R_F": float(r[1]), "ratio": float(r[0] / r[1]), "split_slope": slope,
            "converged": bool(sol.success and np.allclose(forces(r), r, rtol=1e-8))}


def clearance_difference_for_ratio(p: Mapping[str, float], target: float, model: str = "A") -> float:
    """Delta_F - Delta_E (m, Delta_E nominal) at which the self-consistent reactions split as R_E/R_F = target."""
    from scipy.optimize import brentq

    def gap(delta: float) -> float:
        return self_consistent_reactions({**p, "clearance_F": p["clearance_E"] + delta}, model)["ratio"] - target

    hi = p["clearance_E"]
    while gap(hi) < 0 and hi < 1.0:
        hi *= 2.0
    return float(brentq(gap, 0.0, hi, xtol=1e-12, rtol=1e-6))


# --- flip points of a verdict --------------------------------------------------------------------


def flip_point(holds: Callable[[float], bool], nominal: float, end: float, rtol: float) -> float:
    """The value between ``nominal`` and ``end`` where ``holds`` changes (bisection, geometric for positive
    values), to a relative width ``rtol``; NaN if it does not change between the two."""
    a, b = float(nominal), float(end)
    ha, hb = holds(a), holds(b)
    if ha == hb:
        return float("nan")
    geometric = a > 0 and b > 0
    while abs(b - a) > rtol * max(abs(a), abs(b)):
        mid = np.sqrt(a * b) if geometric else 0.5 * (a + b)
        if holds(mid) == ha:
            a = mid
        else:
            b = mid
    return float(0.5 * (a + b))


# --- a dwell cam as a Fourier series of the drive ------------------------------------------------


def cam_profile(theta: np.ndarray, rise_fraction: float) -> np.ndarray:
    """Dwell-rise-dwell-return over one turn, cycloidal rise and return, displacement 0..1.

    Rise over [0, beta) of the turn, dwell up to 1/2, return over [1/2, 1/2 + beta), dwell to the end;
    beta = ``rise_fraction`` (< 1/2).
    """
    u = np.mod(np.asarray(theta, dtype=float), 2 * np.pi) / (2 * np.pi)
    b = rise_fraction

    def cyc(s):  # cycloidal 0 -> 1 over s in [0, 1]
        return s - np.sin(2 * np.pi * s) / (2 * np.pi)

    x = np.zeros_like(u)
    x = np.where(u < b, cyc(u / b), x)
    x = np.where((u >= b) & (u < 0.5), 1.0, x)
    x = np.where((u >= 0.5) & (u < 0.5 + b), 1.0 - cyc((u - 0.5) / b), x)
    return x


def cam_harmonics(rise_fraction: float, harmonics: int, samples: int) -> np.ndarray:
    """Complex amplitudes c_h, h = 1..harmonics, of x(theta) = Re sum_h c_h exp(j h theta), by the FFT of
    ``samples`` points over one turn (the mean is left out: it moves no mass)."""
    theta = 2 * np.pi * np.arange(samples) / samples
    spec = np.fft.rfft(cam_profile(theta, rise_fraction)) / samples
    return 2.0 * spec[1 : harmonics + 1]


def harmonic_transfer(
    model: str, p: Mapping[str, float], omega: np.ndarray, harmonics: int
) -> tuple[np.ndarray, np.ndarray]:
    """Q_E and Q_F per metre of drive displacement at h omega, h = 1..harmonics: arrays (speeds, harmonics)."""

    freqs = np.outer(omega, np.arange(1, harmonics + 1))
    _, q_e, q_f, _ = joint_forces(model, p, "elastic", freqs.ravel(), 1.0)
    return q_e.reshape(freqs.shape), q_f.reshape(freqs.shape)


def periodic_peaks(
    transfer: tuple[np.ndarray, np.ndarray], coefficients: np.ndarray, samples: int
) -> tuple[np.ndarray, np.ndarray]:
    """Peak |Q_E(t)|, |Q_F(t)| over one turn at each shaft speed, the drive being Re sum_h c_h exp(j h omega t)
    (coefficients in m, ``transfer`` from :func:`harmonic_transfer`): the chain is linear, so the harmonics
    superpose."""
    h = np.arange(1, coefficients.size + 1)
    phase = np.exp(1j * np.outer(h, 2 * np.pi * np.arange(samples) / samples))  # (harmonics, samples)
    return tuple(np.abs(np.real((q * coefficients) @ phase)).max(axis=1) for q in transfer)
