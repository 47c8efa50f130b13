"""The compiled integrators of every scene: explicit RK4, Dormand-Prince 5(4) and 8(5,3) (DOP853, scipy's algorithm
with its dense output), the implicit variable-order NDF (a port of scipy's BDF) and the finite-difference Jacobian.

They are compiled once, not once per scene: a scene's right-hand side comes in as a first-class function ``fun``
(numba's FunctionType of ``RHS_INTO``: ``fun(t, y, p, latched, counts, diag, w, out)`` writes dy/dt into ``out`` and
the diagnostics into ``diag``, with ``w`` a work array of ``n_work``), called through its compiled address, so that
one machine code of each integrator serves every topology and set of effects.  ``n_diag`` is the length of the
scene's diagnostics (``DIAG_FIXED + DIAG_PER_JOINT`` per clearance joint).  ``SIGNATURES`` holds the one signature
each is compiled for (``compile_once``); the caller passes arrays of exactly those types.

The DOP853 tableau is held here as data (E. Hairer, S. P. Norsett, G. Wanner, Solving Ordinary Differential
Equations I, 2nd ed., Springer 1993, Sec. II.10; the values as scipy.integrate tabulates them, checked to the bit
by tests/test_clearance.py), in this file so that numba's cache of these functions follows it.
"""

from __future__ import annotations

import numpy as np
from numba import njit, types

from ...compilecache import compile_once, use_for_numba

use_for_numba()  # compiled code cached in the compile cache folder, never below lib/

#: Accepted steps in a row that leave the time unchanged before a run is ended as stalled (a first step of zero, or a
#: step below the resolution of the time, would repeat forever): ``simulate.Run`` names the key to change.
STALL_STEPS = 1000

#: The diagnostics of a scene (``diag``): the output body's angular acceleration, the driver torque, the energy and
#: the constraint drift, then per clearance joint e, delta, delta', the dry normal force and the film's radial and
#: tangential forces.
DIAG_FIXED = 4
DIAG_PER_JOINT = 6

D853_A = [
    [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [0.05260015195876773, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [0.0197250569845379, 0.0591751709536137, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [0.02958758547680685, 0.0, 0.08876275643042054, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
     0.0],
    [0.2413651341592667, 0.0, -0.8845494793282861, 0.924834003261792, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
     0.0, 0.0, 0.0],
    [0.037037037037037035, 0.0, 0.0, 0.17082860872947386, 0.12546768756682242, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
     0.0, 0.0, 0.0, 0.0],
    [0.037109375, 0.0, 0.0, 0.17025221101954405, 0.06021653898045596, -0.017578125, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
     0.0, 0.0, 0.0, 0.0],
    [0.03709200011850479, 0.0, 0.0, 0.17038392571223998, 0.10726203044637328, -0.015319437748624402,
     0.008273789163814023, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [0.6241109587160757, 0.0, 0.0, -3.3608926294469414, -0.868219346841726, 27.59209969944671, 20.154067550477894,
     -43.48988418106996, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [0.47766253643826434, 0.0, 0.0, -2.4881146199716677, -0.590290826836843, 21.230051448181193,
     15.279233632882423, -33.28821096898486, -0.020331201708508627, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [-0.9371424300859873, 0.0, 0.0, 5.186372428844064, 1.0914373489967295, -8.149787010746927, -18.52006565999696,
     22.739487099350505, 2.4936055526796523, -3.0467644718982196, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [2.273310147516538, 0.0, 0.0, -10.53449546673725, -2.0008720582248625, -17.9589318631188, 27.94888452941996,
     -2.8589982771350235, -8.87285693353063, 12.360567175794303, 0.6433927460157636, 0.0, 0.0, 0.0, 0.0, 0.0],
    [0.054293734116568765, 0.0, 0.0, 0.0, 0.0, 4.450312892752409, 1.8915178993145003, -5.801203960010585,
     0.3111643669578199, -0.1521609496625161, 0.20136540080403034, 0.04471061572777259, 0.0, 0.0, 0.0, 0.0],
    [0.056167502283047954, 0.0, 0.0, 0.0, 0.0, 0.0, 0.25350021021662483, -0.2462390374708025, -0.12419142326381637,
     0.15329179827876568, 0.00820105229563469, 0.007567897660545699, -0.008298, 0.0, 0.0, 0.0],
    [0.03183464816350214, 0.0, 0.0, 0.0, 0.0, 0.028300909672366776, 0.053541988307438566, -0.05492374857139099,
     0.0, 0.0, -0.00010834732869724932, 0.0003825710908356584, -0.00034046500868740456, 0.1413124436746325, 0.0,
     0.0],
    [-0.42889630158379194, 0.0, 0.0, 0.0, 0.0, -4.697621415361164, 7.683421196062599, 4.06898981839711,
     0.3567271874552811, 0.0, 0.0, 0.0, -0.0013990241651590145, 2.9475147891527724, -9.15095847217987, 0.0],
]
D853_B = [0.054293734116568765, 0.0, 0.0, 0.0, 0.0, 4.450312892752409, 1.8915178993145003, -5.801203960010585,
     0.3111643669578199, -0.1521609496625161, 0.20136540080403034, 0.04471061572777259]
D853_C = [0.0, 0.05260015195876773, 0.0789002279381516, 0.1183503419072274, 0.2816496580927726, 0.3333333333333333,
     0.25, 0.3076923076923077, 0.6512820512820513, 0.6, 0.8571428571428571, 1.0, 1.0, 0.1, 0.2, 0.7777777777777778]
D853_E3 = [-0.18980075407240762, 0.0, 0.0, 0.0, 0.0, 4.450312892752409, 1.8915178993145003, -5.801203960010585,
      -0.4226823213237919, -0.1521609496625161, 0.20136540080403034, 0.02265179219836082, 0.0]
D853_E5 = [0.01312004499419488, 0.0, 0.0, 0.0, 0.0, -1.2251564463762044, -0.4957589496572502, 1.6643771824549864,
      -0.35032884874997366, 0.3341791187130175, 0.08192320648511571, -0.022355307863886294, 0.0]
D853_D = [
    [-8.428938276109013, 0.0, 0.0, 0.0, 0.0, 0.5667149535193777, -3.0689499459498917, 2.38466765651207,
     2.117034582445028, -0.871391583777973, 2.2404374302607883, 0.6315787787694688, -0.08899033645133331,
     18.148505520854727, -9.194632392478356, -4.436036387594894],
    [10.427508642579134, 0.0, 0.0, 0.0, 0.0, 242.28349177525817, 165.20045171727028, -374.5467547226902,
     -22.113666853125306, 7.733432668472264, -30.674084731089398, -9.332130526430229, 15.697238121770845,
     -31.139403219565178, -9.35292435884448, 35.81684148639408],
    [19.985053242002433, 0.0, 0.0, 0.0, 0.0, -387.0373087493518, -189.17813819516758, 527.8081592054236,
     -11.57390253995963, 6.8812326946963, -1.0006050966910838, 0.7777137798053443, -2.778205752353508,
     -60.19669523126412, 84.32040550667716, 11.99229113618279],
    [-25.69393346270375, 0.0, 0.0, 0.0, 0.0, -154.18974869023643, -231.5293791760455, 357.6391179106141,
     93.40532418362432, -37.45832313645163, 104.0996495089623, 29.8402934266605, -43.53345659001114,
     96.32455395918828, -39.17726167561544, -149.72683625798564],
]
D853_A, D853_B, D853_C = np.array(D853_A), np.array(D853_B), np.array(D853_C)
D853_E3, D853_E5, D853_D = np.array(D853_E3), np.array(D853_E5), np.array(D853_D)

_F = types.float64
_V = types.float64[::1]
_I = types.int64
#: A scene's right-hand side: (t, y, p, latched, counts, diag, w, out) -> None.
RHS_INTO = (_F, _V, _V, _V, types.int64[::1], _V, _V, _V)
_FUN = types.FunctionType(types.none(*RHS_INTO))
_WAS = types.boolean[::1]
_ADAPTIVE = (_FUN, _I, _I, _V, _F, _V, _V, _V, types.int64[::1], _F, _F, _F, _F, _WAS)
#: The one argument signature each function here is compiled for.
SIGNATURES = {
    "rhs": (_FUN, _I, _F, _V, _V, _V, types.int64[::1], _V),
    "jacobian": (_FUN, _I, _F, _V, _V, _V, types.int64[::1], _V),
    "latch": (_V, _V, _WAS),
    "rk4": (_FUN, _I, _I, _V, _F, _F, _V, _V, _V, types.int64[::1], _WAS),
    "dopri5": _ADAPTIVE,
    "dop853": _ADAPTIVE,
    "ndf": _ADAPTIVE,
}


def ready(name: str):
    """The compiled ``name`` (compiled for ``SIGNATURES[name]`` or loaded from the cache, one process at a time), which
    then takes a scene's ``rhs_into`` dispatcher as ``fun``."""
    dispatcher = globals()[name]
    if SIGNATURES[name] not in dispatcher.overloads:
        compile_once(dispatcher, SIGNATURES[name], f"{__name__}.{name}")
        dispatcher.disable_compile()  # a call then converts the dispatcher it is given to ``fun``'s type
    return dispatcher


@njit(cache=True)
def rhs(fun, n_work, t, y, p, latched, counts, diag):
    """dy/dt at (t, y) as a new array, the diagnostics into ``diag``."""
    out = np.empty(y.size)
    fun(t, y, p, latched, counts, diag, np.empty(n_work), out)
    return out

@njit(cache=True)
def latch(diag, latched, was_in_contact):
    """The impact velocity |delta'| (m/s) latched at each clearance joint whose contact starts at this state (its
    diagnostics ``diag``); ``was_in_contact`` updated.  Called at accepted steps only."""
    for k in range((diag.size - DIAG_FIXED) // DIAG_PER_JOINT):
        delta = diag[DIAG_FIXED + DIAG_PER_JOINT * k + 1]
        ddot = diag[DIAG_FIXED + DIAG_PER_JOINT * k + 2]
        now = delta > 0.0
        if now and not was_in_contact[k]:
            latched[k] = abs(ddot)
        was_in_contact[k] = now


@njit(cache=True)
def _start(fun, n_work, n_diag, y0, t0, n_out, p, latched, counts, was):
    """Output buffers, work arrays and the first right-hand side (latching its contact state; ``was`` holds
    which joints were in contact before t0, so that a continued run latches no impact that is not one)."""
    ys = np.empty((n_out, y0.size))
    diags = np.empty((n_out, n_diag))
    diag = np.zeros(n_diag)
    scratch = np.zeros(n_diag)
    y = y0.copy()
    k1 = rhs(fun, n_work, t0, y, p, latched, counts, diag)
    latch(diag, latched, was)
    return ys, diags, diag, scratch, was, y, k1


@njit(cache=True)
def jacobian(fun, n_work, t, y, p, latched, counts, scratch):
    """d rhs / d y by forward differences (step sqrt(eps) max(|y_j|, 1)), compiled: for the implicit integrators."""
    n = y.size
    work = np.empty(n_work)
    f0 = np.empty(n)
    f1 = np.empty(n)
    fun(t, y, p, latched, counts, scratch, work, f0)
    jac = np.empty((n, n))
    yy = y.copy()
    for j in range(n):
        h = 1.4901161193847656e-08 * max(abs(y[j]), 1.0)
        yy[j] = y[j] + h
        fun(t, yy, p, latched, counts, scratch, work, f1)
        for i in range(n):
            jac[i, j] = (f1[i] - f0[i]) / h
        yy[j] = y[j]
    return jac


@njit(cache=True)
def rk4(fun, n_work, n_diag, y0, t0, h, t_out, p, latched, counts, was):
    """Fixed-step RK4; steps are shortened only to land on the output times."""
    n_out = t_out.size
    ys, diags, diag, scratch, was, y, k1 = _start(fun, n_work, n_diag, y0, t0, n_out, p, latched, counts, was)
    t = t0
    steps = 0
    stalled = 0
    for i in range(n_out):
        while t < t_out[i] - 1e-15:
            hh = min(h, t_out[i] - t)
            k2 = rhs(fun, n_work, t + 0.5 * hh, y + 0.5 * hh * k1, p, latched, counts, scratch)
            k3 = rhs(fun, n_work, t + 0.5 * hh, y + 0.5 * hh * k2, p, latched, counts, scratch)
            k4 = rhs(fun, n_work, t + hh, y + hh * k3, p, latched, counts, scratch)
            y = y + hh / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
            stalled = 0 if t + hh > t else stalled + 1
            if stalled >= STALL_STEPS:
                raise RuntimeError("rk4: the time did not advance")
            t = t + hh
            k1 = rhs(fun, n_work, t, y, p, latched, counts, diag)
            latch(diag, latched, was)
            steps += 1
        ys[i] = y
        diags[i] = diag
    return ys, diags, steps, 0, h


@njit(cache=True)
def dopri5(fun, n_work, n_diag, y0, t0, t_out, p, latched, counts, rtol, atol, h0, h_max, was):
    """Adaptive Dormand-Prince 5(4) with FSAL; steps land on the output times; latching at accepted steps."""
    c2, c3, c4, c5 = 1.0 / 5, 3.0 / 10, 4.0 / 5, 8.0 / 9
    a21 = 1.0 / 5
    a31, a32 = 3.0 / 40, 9.0 / 40
    a41, a42, a43 = 44.0 / 45, -56.0 / 15, 32.0 / 9
    a51, a52, a53, a54 = 19372.0 / 6561, -25360.0 / 2187, 64448.0 / 6561, -212.0 / 729
    a61, a62, a63, a64, a65 = 9017.0 / 3168, -355.0 / 33, 46732.0 / 5247, 49.0 / 176, -5103.0 / 18656
    b1, b3, b4, b5, b6 = 35.0 / 384, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784, 11.0 / 84
    e1, e3, e4, e5, e6, e7 = 71.0 / 57600, -71.0 / 16695, 71.0 / 1920, -17253.0 / 339200, 22.0 / 525, -1.0 / 40
    n_out = t_out.size
    ys, diags, diag, scratch, was, y, k1 = _start(fun, n_work, n_diag, y0, t0, n_out, p, latched, counts, was)
    t = t0
    h = h0
    accepted = 0
    rejected = 0
    stalled = 0
    for i in range(n_out):
        while t < t_out[i] - 1e-15:
            hh = min(h, h_max, t_out[i] - t)
            k2 = rhs(fun, n_work, t + c2 * hh, y + hh * a21 * k1, p, latched, counts, scratch)
            k3 = rhs(fun, n_work, t + c3 * hh, y + hh * (a31 * k1 + a32 * k2), p, latched, counts, scratch)
            k4 = rhs(fun, n_work, t + c4 * hh, y + hh * (a41 * k1 + a42 * k2 + a43 * k3), p, latched, counts, scratch)
            y5 = y + hh * (a51 * k1 + a52 * k2 + a53 * k3 + a54 * k4)
            k5 = rhs(fun, n_work, t + c5 * hh, y5, p, latched, counts, scratch)
            y6 = y + hh * (a61 * k1 + a62 * k2 + a63 * k3 + a64 * k4 + a65 * k5)
            k6 = rhs(fun, n_work, t + hh, y6, p, latched, counts, scratch)
            y_new = y + hh * (b1 * k1 + b3 * k3 + b4 * k4 + b5 * k5 + b6 * k6)
            k7 = rhs(fun, n_work, t + hh, y_new, p, latched, counts, scratch)
            err_vec = hh * (e1 * k1 + e3 * k3 + e4 * k4 + e5 * k5 + e6 * k6 + e7 * k7)
            sc = atol + rtol * np.maximum(np.abs(y), np.abs(y_new))
            err = np.sqrt(np.mean((err_vec / sc) ** 2))
            if err <= 1.0:
                stalled = 0 if t + hh > t else stalled + 1
                if stalled >= STALL_STEPS:
                    raise RuntimeError("dopri5: the time did not advance")
                t = t + hh
                y = y_new
                k1 = k7  # first same as last: its diagnostics are in scratch
                diag[:] = scratch
                latch(diag, latched, was)
                accepted += 1
                fac = 5.0 if err == 0.0 else min(5.0, max(0.2, 0.9 * err ** -0.2))
                if hh == t_out[i] - (t - hh) and hh < h:
                    fac = max(fac, 1.0)
                h = hh * fac
            else:
                rejected += 1
                h = hh * max(0.2, 0.9 * err ** -0.25)
                if h < 1e-14:
                    raise RuntimeError("dopri5: step size underflow")
        ys[i] = y
        diags[i] = diag
    return ys, diags, accepted, rejected, h


@njit(cache=True)
def _rms(x):
    return np.sqrt(np.mean(x * x))


@njit(cache=True)
def _ndf_R(order, factor):
    """The matrix that re-expresses the differences array for a step size changed by ``factor``."""
    m = np.zeros((order + 1, order + 1))
    m[0, :] = 1.0
    for i in range(1, order + 1):
        for j in range(1, order + 1):
            m[i, j] = (i - 1 - factor * j) / i
    for i in range(1, order + 1):
        for j in range(order + 1):
            m[i, j] *= m[i - 1, j]
    return m


@njit(cache=True)
def _ndf_change(D, order, factor):
    ru = _ndf_R(order, factor) @ _ndf_R(order, 1.0)
    D[: order + 1] = ru.T @ D[: order + 1].copy()


@njit(cache=True)
def ndf(fun, n_work, n_diag, y0, t0, t_out, p, latched, counts, rtol, atol, h0, h_max, was):
    """Variable-order (1-5) implicit NDF/BDF, compiled: the algorithm of scipy.integrate.BDF (quasi-constant step,
    numerical differentiation formulas, Newton with a reused Jacobian), with the compiled finite-difference
    Jacobian; outputs at t_out by the method's own interpolating polynomial; latching at accepted steps."""
    n_out = t_out.size
    ys, diags, diag, scratch, was, y, f = _start(fun, n_work, n_diag, y0, t0, n_out, p, latched, counts, was)
    n = y.size
    kappa = np.array([0.0, -0.1850, -1.0 / 9.0, -0.0823, -0.0415, 0.0])
    gamma = np.zeros(6)
    for k in range(1, 6):
        gamma[k] = gamma[k - 1] + 1.0 / k
    alpha = (1.0 - kappa) * gamma
    error_const = kappa * gamma + 1.0 / np.arange(1, 7)
    newton_tol = max(10.0 * 2.220446049250313e-16 / rtol, min(0.03, rtol ** 0.5))
    D = np.zeros((8, n))
    D[0] = y
    D[1] = f * h0
    order = 1
    n_equal = 0
    h_abs = h0
    J = jacobian(fun, n_work, t0, y, p, latched, counts, scratch)
    current_jac = True
    work = np.empty(n_work)
    fk = np.empty(n)
    eye = np.eye(n)
    minv = np.empty((n, n))
    inv_ok = False
    t = t0
    i = 0
    while i < n_out and t_out[i] <= t + 1e-15:
        ys[i] = y
        diags[i] = diag
        i += 1
    accepted = 0
    rejected = 0
    t_bound = t_out[-1]
    while i < n_out:
        if h_abs > h_max:
            _ndf_change(D, order, h_max / h_abs)
            h_abs = h_max
            n_equal = 0
            inv_ok = False
        min_step = 10.0 * (np.nextafter(t, np.inf) - t)  # as scipy: ten units in the last place of t
        if h_abs < min_step:  # as scipy: a step below it (a cut's rounding-size remainder) is raised to it
            _ndf_change(D, order, min_step / h_abs)
            h_abs = min_step
            n_equal = 0
            inv_ok = False
        while True:
            if h_abs < min_step:
                raise RuntimeError("ndf: step size underflow")
            t_new = t + h_abs
            if t_new > t_bound:
                t_new = t_bound
                _ndf_change(D, order, (t_new - t) / h_abs)
                n_equal = 0
                inv_ok = False
            h = t_new - t
            h_abs = h
            y_predict = np.zeros(n)
            for k in range(order + 1):
                y_predict += D[k]
            scale = atol + rtol * np.abs(y_predict)
            psi = np.zeros(n)
            for k in range(1, order + 1):
                psi += D[k] * gamma[k]
            psi /= alpha[order]
            c = h / alpha[order]
            converged = False
            n_iter = 0
            y_new = y_predict.copy()
            d = np.zeros(n)
            while True:
                if not inv_ok:
                    minv = np.ascontiguousarray(np.linalg.inv(eye - c * J))
                    inv_ok = True
                # Newton iterations on the BDF system
                y_new = y_predict.copy()
                d = np.zeros(n)
                converged = False
                dy_norm_old = -1.0
                for k in range(4):
                    n_iter = k + 1
                    fun(t_new, y_new, p, latched, counts, scratch, work, fk)
                    if not np.all(np.isfinite(fk)):
                        break
                    dy = minv @ (c * fk - psi - d)
                    dy_norm = _rms(dy / scale)
                    rate = -1.0 if dy_norm_old < 0 else dy_norm / dy_norm_old
                    if rate >= 0 and (rate >= 1 or rate ** (4 - k) / (1 - rate) * dy_norm > newton_tol):
                        break
                    y_new += dy
                    d += dy
                    if dy_norm == 0 or (rate >= 0 and rate / (1 - rate) * dy_norm < newton_tol):
                        converged = True
                        break
                    dy_norm_old = dy_norm
                if converged or current_jac:
                    break
                J = jacobian(fun, n_work, t_new, y_predict, p, latched, counts, scratch)
                current_jac = True
                inv_ok = False
            if not converged:
                h_abs *= 0.5
                _ndf_change(D, order, 0.5)
                n_equal = 0
                inv_ok = False
                rejected += 1
                continue
            safety = 0.9 * 9.0 / (8.0 + n_iter)
            scale = atol + rtol * np.abs(y_new)
            error_norm = _rms(error_const[order] * d / scale)
            if error_norm > 1.0:
                factor = max(0.2, safety * error_norm ** (-1.0 / (order + 1)))
                h_abs *= factor
                _ndf_change(D, order, factor)
                n_equal = 0
                inv_ok = False
                rejected += 1
                continue
            break
        accepted += 1
        n_equal += 1
        t = t_new
        y = y_new
        current_jac = False
        D[order + 2] = d - D[order + 1]
        D[order + 1] = d
        for k in range(order, -1, -1):
            D[k] += D[k + 1]
        fun(t, y, p, latched, counts, diag, work, fk)
        latch(diag, latched, was)
        while i < n_out and t_out[i] <= t + 1e-15:  # the step's interpolating polynomial, into ys[i] in place
            yi = ys[i]
            for m in range(n):
                yi[m] = D[0, m]
            prod = 1.0
            for k in range(1, order + 1):
                prod *= (t_out[i] - (t - h * (k - 1))) / (h * k)
                for m in range(n):
                    yi[m] += D[k, m] * prod
            fun(t_out[i], yi, p, latched, counts, diags[i], work, fk)
            i += 1
        if n_equal < order + 1:
            continue
        em = _rms(error_const[order - 1] * D[order] / scale) if order > 1 else np.inf
        ep = _rms(error_const[order + 1] * D[order + 2] / scale) if order < 5 else np.inf
        norms = np.array([em, error_norm, ep])
        best, delta = -1.0, 0
        for k in range(3):
            fac = np.inf if norms[k] == 0 else norms[k] ** (-1.0 / (order + k))
            if fac > best:
                best, delta = fac, k - 1
        order += delta
        factor = min(10.0, safety * best)
        h_abs *= factor
        _ndf_change(D, order, factor)
        n_equal = 0
        inv_ok = False
    return ys, diags, accepted, rejected, h_abs

@njit(cache=True)
def _d853_stage(y, K, row, s, h, out):
    """out = y + h * sum_j<s A[row, j] K[j]."""
    for m in range(y.size):
        acc = 0.0
        for j in range(s):
            acc += D853_A[row, j] * K[j, m]
        out[m] = y[m] + h * acc


@njit(cache=True)
def dop853(fun, n_work, n_diag, y0, t0, t_out, p, latched, counts, rtol, atol, h0, h_max, was):
    """Adaptive Dormand-Prince 8(5,3) (DOP853: scipy's step-size control and error norm), compiled; outputs at t_out
    by its 7th-order dense output (three extra stages in a step that holds an output), the diagnostics evaluated
    there; steps land only on t_out[-1]; latching at accepted steps."""
    n_out = t_out.size
    ys, diags, diag, scratch, was, y, f = _start(fun, n_work, n_diag, y0, t0, n_out, p, latched, counts, was)
    n = y.size
    K = np.empty((16, n))
    F = np.empty((7, n))
    yy = np.empty(n)
    y_new = np.empty(n)
    diag_new = np.zeros(n_diag)
    work = np.empty(n_work)
    f_out = np.empty(n)
    t = t0
    h = h0
    t_end = t_out[-1]
    accepted = 0
    rejected = 0
    stalled = 0
    i = 0
    while i < n_out and t_out[i] <= t + 1e-15:
        ys[i] = y
        diags[i] = diag
        i += 1
    while t < t_end - 1e-15:
        step_rejected = False
        while True:
            hh = min(h, h_max)
            t_new = t + hh
            if t_new >= t_end - 1e-15:
                t_new = t_end
                hh = t_end - t
            K[0] = f
            for s in range(1, 12):
                _d853_stage(y, K, s, s, hh, yy)
                fun(t + D853_C[s] * hh, yy, p, latched, counts, scratch, work, K[s])
            for m in range(n):
                acc = 0.0
                for j in range(12):
                    acc += D853_B[j] * K[j, m]
                y_new[m] = y[m] + hh * acc
            fun(t_new, y_new, p, latched, counts, diag_new, work, K[12])
            e5 = 0.0
            e3 = 0.0
            for m in range(n):
                sc = atol + rtol * max(abs(y[m]), abs(y_new[m]))
                a5 = 0.0
                a3 = 0.0
                for j in range(13):
                    a5 += D853_E5[j] * K[j, m]
                    a3 += D853_E3[j] * K[j, m]
                e5 += (a5 / sc) ** 2
                e3 += (a3 / sc) ** 2
            err = 0.0 if e5 == 0.0 and e3 == 0.0 else hh * e5 / np.sqrt((e5 + 0.01 * e3) * n)
            if err < 1.0:
                break
            rejected += 1
            step_rejected = True
            h = hh * max(0.2, 0.9 * err ** (-1.0 / 8.0))
            if h < 1e-14:
                raise RuntimeError("dop853: step size underflow")
        factor = 10.0 if err == 0.0 else min(10.0, 0.9 * err ** (-1.0 / 8.0))
        if step_rejected:
            factor = min(1.0, factor)
        stalled = 0 if t_new > t else stalled + 1
        if stalled >= STALL_STEPS:
            raise RuntimeError("dop853: the time did not advance")
        if i < n_out and t_out[i] < t_new - 1e-15:
            for s in range(13, 16):
                _d853_stage(y, K, s, s, hh, yy)
                fun(t + D853_C[s] * hh, yy, p, latched, counts, scratch, work, K[s])
            for m in range(n):
                dy = y_new[m] - y[m]
                F[0, m] = dy
                F[1, m] = hh * f[m] - dy
                F[2, m] = 2.0 * dy - hh * (f[m] + K[12, m])
                for r in range(4):
                    acc = 0.0
                    for j in range(16):
                        acc += D853_D[r, j] * K[j, m]
                    F[3 + r, m] = hh * acc
            while i < n_out and t_out[i] < t_new - 1e-15:
                x = (t_out[i] - t) / hh
                for m in range(n):
                    v = 0.0
                    for r in range(7):
                        v += F[6 - r, m]
                        v *= x if r % 2 == 0 else 1.0 - x
                    yy[m] = y[m] + v
                ys[i] = yy
                fun(t_out[i], yy, p, latched, counts, diags[i], work, f_out)
                i += 1
        t = t_new
        y[:] = y_new
        f[:] = K[12]
        diag[:] = diag_new
        latch(diag, latched, was)
        accepted += 1
        while i < n_out and t_out[i] <= t + 1e-15:
            ys[i] = y
            diags[i] = diag
            i += 1
        if t_new != t_end or hh >= h:
            h = hh * factor
    return ys, diags, accepted, rejected, h
