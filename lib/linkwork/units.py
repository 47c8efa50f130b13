"""Units and physical constants: the one home of every conversion the project makes.

Inside the library everything is SI with angles in radians; degrees and rev/min appear only
at the config and report boundaries, and are converted here.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

#: Standard acceleration of gravity (m/s^2), CGPM 1901.
STANDARD_GRAVITY = 9.80665

#: rad/s per rev/min (one revolution is 2 pi rad, one minute 60 s).
RAD_S_PER_RPM = 2.0 * math.pi / 60.0

#: degrees per radian.
DEG_PER_RAD = 180.0 / math.pi


def rpm_to_rad_s(rpm: ArrayLike) -> NDArray[np.float64] | float:
    """Shaft speed in rev/min -> angular speed in rad/s."""
    return np.asarray(rpm, dtype=float) * RAD_S_PER_RPM if np.ndim(rpm) else float(rpm) * RAD_S_PER_RPM


def rad_s_to_rpm(omega: ArrayLike) -> NDArray[np.float64] | float:
    """Angular speed in rad/s -> shaft speed in rev/min."""
    return np.asarray(omega, dtype=float) / RAD_S_PER_RPM if np.ndim(omega) else float(omega) / RAD_S_PER_RPM


def angle_grid_deg(step_deg: float) -> NDArray[np.float64]:
    """Crank angles 0, step, ... < 360 (deg) for a step that divides 360 deg."""
    n = int(round(360.0 / step_deg))
    return np.arange(n) * (360.0 / n)


def divides_turn(step_deg: float, tol: float = 1e-9) -> bool:
    """True if ``step_deg`` (deg) divides a full turn into a whole number of steps."""
    n = 360.0 / step_deg
    return abs(n - round(n)) <= tol
