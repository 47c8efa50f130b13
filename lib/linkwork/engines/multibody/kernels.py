"""Compiled building blocks of the planar multibody engine (numba; SI units, radians).

Bodies are (x, y, phi) at the centre of mass; a point of a body is given by its local
coordinates s.  A revolute constraint between points of two bodies (or a body and the ground)
contributes two rows to Phi, Phi_q and gamma; a force applied at a point contributes to the
generalized force vector g.  These functions are shared by every generated scene.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ...compilecache import use_for_numba

use_for_numba()  # compiled code cached in the compile cache folder, never below lib/


@njit(cache=True)
def body_trig(q, cs):
    """cos and sin of every body's angle into cs (c0, s0, c1, s1, ...): computed once per right-hand side and read
    by every kernel below."""
    for b in range(cs.size // 2):
        cs[2 * b] = np.cos(q[3 * b + 2])
        cs[2 * b + 1] = np.sin(q[3 * b + 2])


@njit(cache=True)
def point(q, cs, body, sx, sy):
    """Global position of a body point (cs: ``body_trig``)."""
    c, s = cs[2 * body], cs[2 * body + 1]
    return q[3 * body] + c * sx - s * sy, q[3 * body + 1] + s * sx + c * sy


@njit(cache=True)
def point_velocity(q, qd, cs, body, sx, sy):
    c, s = cs[2 * body], cs[2 * body + 1]
    w = qd[3 * body + 2]
    return qd[3 * body] - w * (s * sx + c * sy), qd[3 * body + 1] + w * (c * sx - s * sy)


@njit(cache=True)
def revolute(q, qd, cs, bi, six, siy, bj, sjx, sjy, gx, gy, row, phi, phiq, gamma, phidot):
    """Rows row, row+1: point s_i of body bi coincides with point s_j of body bj (bj < 0: ground point g)."""
    ci, si = cs[2 * bi], cs[2 * bi + 1]
    wi = qd[3 * bi + 2]
    pix, piy = point(q, cs, bi, six, siy)
    vix, viy = point_velocity(q, qd, cs, bi, six, siy)
    # d(A s)/dphi = B s
    bsx, bsy = -si * six - ci * siy, ci * six - si * siy
    phiq[row, 3 * bi] = 1.0
    phiq[row + 1, 3 * bi + 1] = 1.0
    phiq[row, 3 * bi + 2] = bsx
    phiq[row + 1, 3 * bi + 2] = bsy
    gamma[row] = (ci * six - si * siy) * wi * wi
    gamma[row + 1] = (si * six + ci * siy) * wi * wi
    if bj >= 0:
        cj, sj = cs[2 * bj], cs[2 * bj + 1]
        wj = qd[3 * bj + 2]
        pjx, pjy = point(q, cs, bj, sjx, sjy)
        vjx, vjy = point_velocity(q, qd, cs, bj, sjx, sjy)
        phiq[row, 3 * bj] = -1.0
        phiq[row + 1, 3 * bj + 1] = -1.0
        phiq[row, 3 * bj + 2] = -(-sj * sjx - cj * sjy)
        phiq[row + 1, 3 * bj + 2] = -(cj * sjx - sj * sjy)
        gamma[row] -= (cj * sjx - sj * sjy) * wj * wj
        gamma[row + 1] -= (sj * sjx + cj * sjy) * wj * wj
    else:
        pjx, pjy, vjx, vjy = gx, gy, 0.0, 0.0
    phi[row] = pix - pjx
    phi[row + 1] = piy - pjy
    phidot[row] = vix - vjx
    phidot[row + 1] = viy - vjy


@njit(cache=True)
def driver(q, qd, t, body, phi0, omega, row, phi, phiq, gamma, phidot):
    """Row row: phi_body = phi0 + omega t (constant crank speed)."""
    phiq[row, 3 * body + 2] = 1.0
    gamma[row] = 0.0
    phi[row] = q[3 * body + 2] - phi0 - omega * t
    phidot[row] = qd[3 * body + 2] - omega


@njit(cache=True)
def fourier_series(t, omega, a, b):
    """sum_k (a[k-1] cos(k omega t) + b[k-1] sin(k omega t)) (rad) and its first and second time derivatives."""
    theta, rate, accel = 0.0, 0.0, 0.0
    for k in range(a.size):
        kw = (k + 1) * omega
        c, s = np.cos(kw * t), np.sin(kw * t)
        theta += a[k] * c + b[k] * s
        rate += kw * (b[k] * c - a[k] * s)
        accel -= kw * kw * (a[k] * c + b[k] * s)
    return theta, rate, accel


@njit(cache=True)
def angle_row(q, qd, body, theta, rate, accel, row, phi, phiq, gamma, phidot):
    """Row row: the driven body's angle phi_body = theta (rad) at the rate (rad/s) and acceleration (rad/s^2) given."""
    phiq[row, 3 * body + 2] = 1.0
    gamma[row] = accel
    phi[row] = q[3 * body + 2] - theta
    phidot[row] = qd[3 * body + 2] - rate


@njit(cache=True)
def driver_series(q, qd, t, body, phi0, omega, a, b, row, phi, phiq, gamma, phidot):
    """Row row: phi_body = phi0 + omega t + the Fourier series of the mean speed omega (rad/s; a given periodic
    motion of the driven body)."""
    s, sd, sdd = fourier_series(t, omega, a, b)
    angle_row(q, qd, body, phi0 + omega * t + s, omega + sd, sdd, row, phi, phiq, gamma, phidot)


@njit(cache=True)
def driver_rocking(q, qd, t, body, phi0, omega, a, b, row, phi, phiq, gamma, phidot):
    """Row row: phi_body = phi0 + the Fourier series of frequency omega (rad/s): a body rocked by a given periodic
    motion with no mean turning (a cam-driven lever)."""
    s, sd, sdd = fourier_series(t, omega, a, b)
    angle_row(q, qd, body, phi0 + s, sd, sdd, row, phi, phiq, gamma, phidot)


@njit(cache=True)
def ground_spring(q, qd, cs, g, body, sx, sy, rx, ry, kx, ky, cx, cy):
    """A linear spring-damper from a body point (local s, m) to a fixed rest point r (m): F = -k d - c v per axis
    (N/m, N s/m), added to the generalized forces; returns its potential energy (J)."""
    c, s = cs[2 * body], cs[2 * body + 1]
    ax, ay = c * sx - s * sy, s * sx + c * sy
    dx, dy = q[3 * body] + ax - rx, q[3 * body + 1] + ay - ry
    w = qd[3 * body + 2]
    vx, vy = qd[3 * body] - w * ay, qd[3 * body + 1] + w * ax
    apply_force(q, cs, g, body, sx, sy, -kx * dx - cx * vx, -ky * dy - cy * vy)
    return 0.5 * (kx * dx * dx + ky * dy * dy)


@njit(cache=True)
def apply_force(q, cs, g, body, sx, sy, fx, fy):
    """Add a force applied at a body point (local s) to the generalized forces."""
    c, s = cs[2 * body], cs[2 * body + 1]
    rx, ry = c * sx - s * sy, s * sx + c * sy
    g[3 * body] += fx
    g[3 * body + 1] += fy
    g[3 * body + 2] += rx * fy - ry * fx


@njit(cache=True)
def clearance_state(q, qd, cs, bj_journal, jx, jy, bb_bearing, bx, by, clearance, r_journal, r_bearing):
    """Kinematics of a clearance joint.

    Returns e (|eccentricity|, m), nx, ny (unit normal bearing -> journal centre), delta
    (penetration e - c), delta_dot (rate of e), v_t (relative tangential slip at the contact,
    journal minus bearing), omega_j, omega_b, gamma_dot (rate of the eccentricity direction).
    """
    pjx, pjy = point(q, cs, bj_journal, jx, jy)
    pbx, pby = point(q, cs, bb_bearing, bx, by)
    vjx, vjy = point_velocity(q, qd, cs, bj_journal, jx, jy)
    vbx, vby = point_velocity(q, qd, cs, bb_bearing, bx, by)
    ex, ey = pjx - pbx, pjy - pby
    e = np.sqrt(ex * ex + ey * ey)
    if e > 1e-300:
        nx, ny = ex / e, ey / e
    else:
        nx, ny = 1.0, 0.0
    tx, ty = -ny, nx
    dvx, dvy = vjx - vbx, vjy - vby
    e_dot = dvx * nx + dvy * ny
    wj, wb = qd[3 * bj_journal + 2], qd[3 * bb_bearing + 2]
    gamma_dot = (dvx * tx + dvy * ty) / e if e > 1e-300 else 0.0
    v_t = dvx * tx + dvy * ty + wj * r_journal - wb * r_bearing
    return e, nx, ny, e - clearance, e_dot, v_t, wj, wb, gamma_dot


@njit(cache=True)
def elastic_contact(law, stiffness, exponent, delta):
    """Elastic normal force (N) and its potential energy int_0^delta F (J) at the penetration delta > 0 (m).

    law 0, sphere (Hertz, the paper's eq. 9): K delta^1.5 and K delta^2.5 / 2.5 (``exponent`` unused);
    law 1, conformal cylinder (Pereira et al. 2011): K delta^n and K delta^(n+1) / (n+1) with n = ``exponent``.
    ``stiffness`` K in N/m^n.
    """
    if law == 0:
        return stiffness * delta ** 1.5, stiffness * delta ** 2.5 / 2.5
    m = exponent + 1.0
    return stiffness * delta ** exponent, stiffness * delta ** m / m


@njit(cache=True)
def hertz_damping_factor(law, restitution, delta_dot, impact_velocity):
    """1 + (damping coefficient) * delta_dot / delta_dot(-) for the three continuous contact laws.

    law 0: Lankarani-Nikravesh 3(1 - ce^2)/4; 1: Hunt-Crossley 3(1 - ce)/2; 2: Flores 8(1 - ce)/(5 ce).
    The factor is floored at 0 so that the contact never pulls.
    """
    if law == 0:
        chi = 3.0 * (1.0 - restitution * restitution) / 4.0
    elif law == 1:
        chi = 3.0 * (1.0 - restitution) / 2.0
    else:
        chi = 8.0 * (1.0 - restitution) / (5.0 * restitution)
    f = 1.0 + chi * delta_dot / impact_velocity
    return f if f > 0.0 else 0.0


@njit(cache=True)
def friction_coefficient(v_t, mu, v0, v1):
    """Ambrosio's modified Coulomb: -mu c_d sign(v_t), c_d = 0 below v0, linear to 1 at v1 (no division at v_t = 0)."""
    a = abs(v_t)
    if a <= v0:
        return 0.0
    cd = 1.0 if a >= v1 else (a - v0) / (v1 - v0)
    return -mu * cd if v_t > 0 else mu * cd


@njit(cache=True)
def film_forces(eps, eps_dot, omega_sum, gamma_dot, coefficient, eps_limit):
    """Long-bearing (Sommerfeld) squeeze and wedge forces (radial, tangential) on the journal, N.

    coefficient = 12 pi mu L R^3 / c^2 (times 1/c for eps_dot given in 1/s); the eccentricity ratio
    is capped at eps_limit, which keeps the film force continuous and bounded up to and beyond
    eps = 1 (where the dry contact takes over), instead of the printed eq. (23)'s singularity.
    """
    e = eps if eps < eps_limit else eps_limit
    f_r = -coefficient * eps_dot / (1.0 - e * e) ** 1.5
    f_t = coefficient * e * (omega_sum - 2.0 * gamma_dot) / ((2.0 + e * e) * np.sqrt(1.0 - e * e))
    return f_r, f_t


@njit(cache=True)
def gauss_solve_into(a, b, x):
    """x with a x = b by Gaussian elimination with partial pivoting, into x (a, b are overwritten).

    For the small Schur complements here (at most 9 x 9) this is faster than a LAPACK call and gives the same
    rounding on every CPU, so a chaotic impact sequence replays identically on another machine.
    """
    n = b.size
    for col in range(n):
        pivot = col
        for row in range(col + 1, n):
            if abs(a[row, col]) > abs(a[pivot, col]):
                pivot = row
        if pivot != col:
            for k in range(n):
                a[col, k], a[pivot, k] = a[pivot, k], a[col, k]
            b[col], b[pivot] = b[pivot], b[col]
        for row in range(col + 1, n):
            factor = a[row, col] / a[col, col]
            for k in range(col, n):
                a[row, k] -= factor * a[col, k]
            b[row] -= factor * b[col]
    for row in range(n - 1, -1, -1):
        acc = b[row]
        for k in range(row + 1, n):
            acc -= a[row, k] * x[k]
        x[row] = acc / a[row, row]


@njit(cache=True)
def solve_stack(a, b):
    """x[i] with a[i] x[i] = b[i] for a stack of small systems (a: (n, m, m), b: (n, m); neither is changed), each by
    ``gauss_solve_into``: for the engine's small constraint Jacobians this is faster than numpy's batched LAPACK
    call."""
    n, m = b.shape
    x = np.empty((n, m))
    aa = np.empty((m, m))
    bb = np.empty(m)
    for i in range(n):
        aa[:, :] = a[i]
        bb[:] = b[i]
        gauss_solve_into(aa, bb, x[i])
    return x
