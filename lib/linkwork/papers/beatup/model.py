"""Beating-up mechanisms: the GN721 six-bar and a 1511M-type four-bar (paper ``beatup``, Gao 1983).

Frame of the paper: origin at the rocking shaft F, x horizontal.  The six-bar
is the crank-rocker ABCD (crank AB = l1, coupler BC = l2, rocker DC = l3, frame
AD = l4 at angle theta4) driving the double rocker CDEF (link CE = l5, sley
sword FE = l6, frame DF = l7 at angle theta7):

    l1 e^{i th1} + l2 e^{i th2} = l4 e^{i th4} + l3 e^{i th3}      (loop 1)
    l3 e^{i th3} + l5 e^{i th5} = l7 e^{i th7} + l6 e^{i th6}      (loop 2)

so D = F - l7 e^{i th7} and A = D - l4 e^{i th4}.  It is solved by the shared
chain solver (linkwork.engines.kinematics.solve_chain); the paper's own tangent
half-angle closed forms, eqs. (5)-(7) and (11)-(13), are kept here, both as
printed and corrected, as an independent route and to document its typos.

Derivatives are per unit crank angle (theta' in rad/rad, theta'' in rad/rad^2),
which is the unit of the paper's Table 1.  SI units, radians.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ...engines.kinematics import Chain, Dyad, FourBar, four_bar, solve_chain

FloatArray = NDArray[np.float64]
TWO_PI = 2.0 * np.pi


def _e(angle: float) -> FloatArray:
    return np.array([np.cos(angle), np.sin(angle)])


@dataclass(frozen=True)
class SixBar:
    """GN721 six-bar beating-up mechanism (lengths in m, angles in rad).

    branch_rocker, branch_sley: assembly signs of the dyads B-C-D and C-E-F
    (sign of (q - p) x (joint - p), see linkwork.engines.kinematics.Dyad).
    """

    l1: float
    l2: float
    l3: float
    l4: float
    l5: float
    l6: float
    l7: float
    theta4: float
    theta7: float
    branch_rocker: int = -1
    branch_sley: int = -1
    assembly_tol: float = 1.0e-9

    def __post_init__(self) -> None:
        for name in ("l1", "l2", "l3", "l4", "l5", "l6", "l7"):
            value = getattr(self, name)
            if not np.isfinite(value) or value <= 0.0:
                raise ValueError(f"six-bar length {name} must be positive and finite, got {value!r}")
        for name in ("branch_rocker", "branch_sley"):
            if getattr(self, name) not in (1, -1):
                raise ValueError(f"six-bar {name} must be +1 or -1, got {getattr(self, name)!r}")

    def chain(self) -> Chain:
        f = np.zeros(2)
        d = f - self.l7 * _e(self.theta7)
        a = d - self.l4 * _e(self.theta4)
        return Chain(
            ground={"A": tuple(a), "D": tuple(d), "F": tuple(f)},
            crank_pivot="A",
            crank_tip="B",
            crank_length=self.l1,
            dyads=(
                Dyad("C", "B", "D", self.l2, self.l3, self.branch_rocker),
                Dyad("E", "C", "F", self.l5, self.l6, self.branch_sley),
            ),
            assembly_tol=self.assembly_tol,
        )


@dataclass(frozen=True)
class SleyMotion:
    """Rocker (theta3) and sley sword (theta6) angles with crank-angle derivatives.

    Angles in rad wrapped to [0, 2 pi); rates in rad/rad; accelerations in rad/rad^2.
    """

    theta1: FloatArray
    theta3: FloatArray
    theta3_rate: FloatArray
    theta3_accel: FloatArray
    theta6: FloatArray
    theta6_rate: FloatArray
    theta6_accel: FloatArray


def sley_motion(mechanism: SixBar, theta1: ArrayLike) -> SleyMotion:
    """Solve the six-bar (chain solver) at the given crank angles (rad)."""
    m = solve_chain(mechanism.chain(), theta1)
    rocker, sley = m.links["D-C"], m.links["F-E"]
    return SleyMotion(
        m.crank_angle,
        np.mod(rocker.angle, TWO_PI),
        rocker.rate,
        rocker.accel,
        np.mod(sley.angle, TWO_PI),
        sley.rate,
        sley.accel,
    )


# --- the paper's closed forms ----------------------------------------------------------------------


def _half_angle_solution(a, b, c, sign):
    """theta = 2 arctan((A +- sqrt(A^2 + B^2 - C^2)) / (B + C)), eqs. (5)/(11), via atan2."""
    root = np.sqrt(np.clip(a * a + b * b - c * c, 0.0, None))
    return np.mod(2.0 * np.arctan2(a + sign * root, b + c), TWO_PI)


def _loop_closed_form(inp, out, coupler, frame, frame_angle, t_in, w_in, e_in, sign, squares):
    """One four-bar loop of the paper, input link -> output link (eqs. 4-7 and 10-13 have this shape).

    Solves A sin(t) + B cos(t) = C for the output angle (eqs. 5, 11), then its rate (6, 12) and
    acceleration (7, 13).  ``squares(w_in, w_out, e_in)`` returns the factors standing where
    the derivation has w_in^2 and w_out^2; that is where the printed equations differ.
    """
    a = np.sin(t_in) - frame / inp * np.sin(frame_angle)
    b = np.cos(t_in) - frame / inp * np.cos(frame_angle)
    c = (frame**2 + out**2 + inp**2 - coupler**2) / (2 * inp * out) - frame / out * np.cos(t_in - frame_angle)
    t_out = _half_angle_solution(a, b, c, sign)
    den = frame / inp * np.sin(t_out - frame_angle) + np.sin(t_in - t_out)
    w_out = w_in * (frame / out * np.sin(t_in - frame_angle) + np.sin(t_in - t_out)) / den
    q_in, q_out = squares(w_in, w_out, e_in)
    num = (
        frame / out * e_in * np.sin(t_in - frame_angle)
        + frame / out * q_in * np.cos(t_in - frame_angle)
        - frame / inp * q_out * np.cos(t_out - frame_angle)
        + e_in * np.sin(t_in - t_out)
        + (w_in - w_out) ** 2 * np.cos(t_in - t_out)
    )
    return t_out, w_out, num / den


def _derived_squares(w_in, w_out, e_in):
    return w_in**2, w_out**2


def _eq7_printed(w_in, w_out, e_in):
    return e_in, e_in  # eq. (7) prints theta1'' in both places


def _eq13_printed(w_in, w_out, e_in):
    return w_in, w_in  # eq. (13) prints theta3' in both places


def paper_closed_form(
    mechanism: SixBar, theta1: ArrayLike, sign3: int, sign6: int, printed: bool = False
) -> SleyMotion:
    """The paper's eqs. (5)-(7) and (11)-(13) for a crank turning uniformly (theta1' = 1, theta1'' = 0).

    ``printed=True`` uses eqs. (7) and (13) as printed, which put theta1'' (zero)
    where theta1'^2 and theta3'^2 belong in (7), and theta3' where theta3'^2 and
    theta6'^2 belong in (13).  ``printed=False`` uses the forms derived by
    differentiating eqs. (3) and (10) twice; eq. (4) is read with theta3 as the
    unknown, as (5) requires.  sign3, sign6: the +- of eqs. (5), (11).
    """
    m = mechanism
    t1 = np.asarray(theta1, dtype=float)
    ones, zeros = np.ones_like(t1), np.zeros_like(t1)
    t3, w3, e3 = _loop_closed_form(
        m.l1, m.l3, m.l2, m.l4, m.theta4, t1, ones, zeros, sign3, _eq7_printed if printed else _derived_squares
    )
    t6, w6, e6 = _loop_closed_form(
        m.l3, m.l6, m.l5, m.l7, m.theta7, t3, w3, e3, sign6, _eq13_printed if printed else _derived_squares
    )
    return SleyMotion(t1, t3, w3, e3, t6, w6, e6)


# --- dead centres, swing, spans, extremes ------------------------------------------------------------


@dataclass(frozen=True)
class DeadCentres:
    """Sley dead centres (rad): front = theta6 maximum, back = theta6 minimum.

    span_forward: crank angle from front to back turning the crank in the
    sense of increasing theta1; span_reverse: the same in the opposite sense.
    """

    front: float
    back: float
    theta6_front: float
    theta6_back: float
    swing: float
    span_forward: float
    span_reverse: float


def _roots_of(f, grid: FloatArray, values: FloatArray, xtol: float) -> list[float]:
    from scipy.optimize import brentq

    roots = []
    for i in np.flatnonzero(np.sign(values[:-1]) * np.sign(values[1:]) < 0):
        roots.append(brentq(f, grid[i], grid[i + 1], xtol=xtol))
    return roots


def dead_centres(mechanism: SixBar, scan_points: int = 3601, xtol: float = 1.0e-13) -> DeadCentres:
    """Locate the sley's dead centres as zeros of theta6' (brentq on a scan grid)."""
    grid = np.linspace(0.0, TWO_PI, scan_points)
    rate = lambda t: float(sley_motion(mechanism, np.array([t])).theta6_rate[0])  # noqa: E731
    roots = _roots_of(rate, grid, sley_motion(mechanism, grid).theta6_rate, xtol)
    if len(roots) != 2:
        raise ValueError(f"expected two sley dead centres per turn, found {len(roots)}")
    angles = sley_motion(mechanism, np.array(roots)).theta6
    front, back = (roots[int(np.argmax(angles))], roots[int(np.argmin(angles))])
    forward = float(np.mod(back - front, TWO_PI))
    return DeadCentres(
        front, back, float(angles.max()), float(angles.min()), float(angles.max() - angles.min()), forward,
        TWO_PI - forward,
    )


def from_front(theta1: ArrayLike, front: float, sense: int = 1) -> FloatArray:
    """Crank angle measured from the front dead centre, in [0, 2 pi), for a crank turning in ``sense``."""
    return np.mod(sense * (np.asarray(theta1, dtype=float) - front), TWO_PI)


#: The two senses the crank may turn in (the paper does not say which): name -> sign of dtheta1/dt.
CRANK_SENSES = {"decreasing": -1, "increasing": 1}


def rate_extremes(mechanism: SixBar, scan_points: int = 3601, xtol: float = 1.0e-13) -> tuple[float, float]:
    """Crank angles theta1 (rad) of the largest and of the smallest theta6' over a turn.

    Both are zeros of theta6'' (brentq on a scan grid of ``scan_points``, x-tolerance ``xtol`` rad); of the
    zeros found, the ones with the largest and smallest theta6' are returned.  Sense-free: theta6' is per unit
    of increasing theta1.
    """
    grid = np.linspace(0.0, TWO_PI, scan_points)
    accel = lambda t: float(sley_motion(mechanism, np.array([t])).theta6_accel[0])  # noqa: E731
    roots = np.array(_roots_of(accel, grid, sley_motion(mechanism, grid).theta6_accel, xtol))
    if roots.size < 2:
        raise ValueError(f"expected at least two extremes of the sley rate per turn, found {roots.size}")
    rates = sley_motion(mechanism, roots).theta6_rate
    return float(roots[np.argmax(rates)]), float(roots[np.argmin(rates)])


@dataclass(frozen=True)
class SenseReading:
    """The sense-dependent features of the sley motion for a crank turning in ``sense`` (rad).

    sense: +1 towards increasing theta1, -1 towards decreasing.  span_front_to_back: crank angle turned
    from the front to the back dead centre.  rate_peak_backward / rate_peak_forward: crank angle from the
    front dead centre, counted in the sense of rotation, of the largest sley speed towards the back (theta6
    falling; the first peak after the front) and towards the front (the second).  accel_peak: crank-angle
    distance of the largest |theta6''| from the front dead centre (the same in both senses).
    """

    sense: int
    span_front_to_back: float
    rate_peak_backward: float
    rate_peak_forward: float
    accel_peak: float


def sense_reading(
    centres: DeadCentres, extremes: tuple[float, float], accel_peak_theta1: float, sense: int
) -> SenseReading:
    """Read the dead centres (``dead_centres``), the rate extremes (``rate_extremes``: theta1 of the largest
    and smallest theta6') and the theta1 of the largest |theta6''| (rad) for a crank turning in ``sense``.

    The sley's angular velocity is sense * theta6' * |crank speed|: it moves towards the back (theta6
    falling) fastest where sense * theta6' is most negative.
    """
    if sense not in (1, -1):
        raise ValueError(f"crank sense must be +1 or -1, got {sense!r}")
    largest, smallest = extremes
    backward, forward = (smallest, largest) if sense == 1 else (largest, smallest)
    phi = lambda t: float(from_front(t, centres.front, sense))  # noqa: E731
    accel = phi(accel_peak_theta1)
    return SenseReading(
        sense,
        centres.span_forward if sense == 1 else centres.span_reverse,
        phi(backward),
        phi(forward),
        min(accel, TWO_PI - accel),
    )


# --- reed displacement and the weft window ------------------------------------------------------------


def reed_displacement(sword_angle: ArrayLike, front_angle: float, radius: float) -> FloatArray:
    """Horizontal distance (m) of the reed at ``radius`` on the sword from its foremost position.

    The sword points at ``sword_angle`` from the rocking shaft; the front is the
    position with the largest sword angle (the reed furthest towards -x when the
    sword leans past vertical, as in both mechanisms here).
    """
    return radius * (np.cos(np.asarray(sword_angle, dtype=float)) - np.cos(front_angle))


def radius_for_stroke(theta_front: float, theta_back: float, stroke: float) -> float:
    """Reed radius (m) on the sword that gives the horizontal stroke ``stroke`` (m)."""
    return stroke / (np.cos(theta_back) - np.cos(theta_front))


def window_span(theta1: FloatArray, displacement: FloatArray, threshold: float) -> float:
    """Crank angle (rad) during which displacement > threshold, over one periodic turn.

    theta1 is a uniform grid over [0, 2 pi) (end point excluded); crossings are
    located by linear interpolation between grid points.
    """
    d = np.asarray(displacement, dtype=float) - threshold
    step = TWO_PI / d.size
    nxt = np.roll(d, -1)
    total = 0.0
    for di, dn in zip(d, nxt, strict=True):
        if di > 0 and dn > 0:
            total += step
        elif di > 0 or dn > 0:
            total += step * max(di, dn) / abs(dn - di)
    return total


# --- a parametric 1511M-type four-bar beating-up mechanism ---------------------------------------


@dataclass(frozen=True)
class FourBarBeatup:
    """Crank R at O, connecting arm L to the sword pin E at radius r from the rocking shaft F.

    Geometry (an assumption: the paper gives no 1511M dimensions): the sword is
    vertical at the front dead centre, as loom practice prescribes (J. T. Taylor,
    Cotton Weaving and Designing: "when the crank is at the front centre the
    slay-swords should be perpendicular, or nearly so").  The crank centre O is
    behind the sley (+x), ``offset`` below the pin's front position (0, r), at
    the distance L + R from it (crank and arm in line at the front centre).
    Lengths in m.
    """

    crank: float
    arm: float
    sword_radius: float
    offset: float = 0.0
    branch: int = -1  # -1 puts the sword at the front when crank and arm are in line

    def __post_init__(self) -> None:
        for name in ("crank", "arm", "sword_radius"):
            value = getattr(self, name)
            if not np.isfinite(value) or value <= 0.0:
                raise ValueError(f"four-bar beat-up {name} must be positive and finite, got {value!r}")
        if abs(self.offset) >= self.arm + self.crank:
            raise ValueError(f"four-bar beat-up offset {self.offset!r} must be smaller than arm + crank")

    def crank_centre(self) -> FloatArray:
        reach = self.arm + self.crank
        return np.array([np.sqrt(reach**2 - self.offset**2), self.sword_radius - self.offset])

    def linkage(self) -> FourBar:
        d = -self.crank_centre()  # from O to F
        return FourBar(
            crank=self.crank,
            coupler=self.arm,
            rocker=self.sword_radius,
            ground=float(np.hypot(*d)),
            branch=self.branch,
            ground_angle=float(np.arctan2(d[1], d[0])),
        )

    def sword_angle(self, theta1: ArrayLike) -> FloatArray:
        """Direction of F->E (rad) at crank angles theta1 (rad, measured at O)."""
        return np.mod(four_bar(self.linkage(), theta1).rocker_angle, TWO_PI)


# --- one joint fit of the printed parameters to Table 1's angles ------------------------------------

def with_parameters(mechanism: SixBar, names: tuple[str, ...], values: ArrayLike) -> SixBar:
    """The mechanism with the named parameters (SixBar fields, m or rad) set to ``values``."""
    from dataclasses import replace

    return replace(mechanism, **{n: float(v) for n, v in zip(names, np.atleast_1d(values), strict=True)})


@dataclass(frozen=True)
class ParameterFit:
    """Least-squares fit of six-bar parameters to tabulated theta3 and theta6 angles.

    names: fitted SixBar fields; start: their printed values and half_width: half a unit of the printed
    last digit (m or rad); value: the fitted values; shift: (value - start) / half_width, so |shift| <= 1
    is inside the rounding interval; residual: model - table (rad), the theta3 cells then the theta6
    cells; condition: condition number of the Jacobian in half-width units (large: the parameters
    trade off against each other); bounded: whether the fit was held inside the rounding intervals.
    """

    names: tuple[str, ...]
    start: FloatArray
    half_width: FloatArray
    value: FloatArray
    shift: FloatArray
    residual: FloatArray
    condition: float
    nfev: int
    bounded: bool


def fit_table_angles(
    mechanism: SixBar,
    theta1: ArrayLike,
    theta3: ArrayLike,
    theta6: ArrayLike,
    half_widths: dict[str, float],
    bounded: bool = True,
    tol: float = 1.0e-12,
    scale: float = 1.0,
    unbounded: tuple[str, ...] = (),
) -> ParameterFit:
    """Fit the parameters named in ``half_widths`` (SixBar field -> half a printed unit, m or rad) to the
    tabulated angles theta3, theta6 (rad) at crank angles theta1 (rad) by least squares
    (scipy.optimize.least_squares, trust-region reflective, 3-point Jacobian).

    The unknowns are the shifts in half-widths from the printed values; ``bounded`` keeps every shift in
    [-1, 1], the rounding interval of the printed digits, except for the parameters named in
    ``unbounded``.  The residuals are divided by ``scale`` (rad; half
    a unit of the table's printed angle digit makes them of order one, so that the gradient test of
    least_squares means something); ``tol`` is its ftol = xtol = gtol.
    """
    from scipy.optimize import least_squares

    names = tuple(half_widths)
    start = np.array([getattr(mechanism, n) for n in names], dtype=float)
    half = np.array([half_widths[n] for n in names], dtype=float)
    t1 = np.asarray(theta1, dtype=float)
    target = np.concatenate([np.asarray(theta3, dtype=float), np.asarray(theta6, dtype=float)])

    def residual(u: FloatArray) -> FloatArray:
        m = sley_motion(with_parameters(mechanism, names, start + u * half), t1)
        return np.angle(np.exp(1j * (np.concatenate([m.theta3, m.theta6]) - target))) / scale

    limit = np.array([np.inf if (not bounded or n in unbounded) else 1.0 for n in names])
    bounds = (-limit, limit)
    sol = least_squares(
        residual, np.zeros(len(names)), jac="3-point", bounds=bounds, method="trf", ftol=tol, xtol=tol, gtol=tol
    )
    s = np.linalg.svd(sol.jac, compute_uv=False)
    return ParameterFit(
        names, start, half, start + sol.x * half, sol.x, sol.fun * scale, float(s[0] / s[-1]), int(sol.nfev), bounded
    )


def coarse_central_difference(values: ArrayLike, step: float, angles: bool) -> FloatArray:
    """Periodic central difference of a tabulated column (step in rad); angle columns unwrapped."""
    v = np.asarray(values, dtype=float)
    fwd, back = np.roll(v, -1), np.roll(v, 1)
    diff = np.angle(np.exp(1j * (fwd - back))) if angles else fwd - back
    return diff / (2 * step)
