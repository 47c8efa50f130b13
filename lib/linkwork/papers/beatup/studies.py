"""The beat-up paper's studies: six-bar motion with its independent routes and dead centres, the weft
windows of the scaled six-bar and a parametric four-bar, and analytic vs finite-difference derivatives."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import xarray as xr

from ...units import DEG_PER_RAD, angle_grid_deg
from .adapter import crank_sense, four_bar_beatup, six_bar
from .model import (
    CRANK_SENSES,
    dead_centres,
    rate_extremes,
    sense_reading,
    paper_closed_form,
    radius_for_stroke,
    reed_displacement,
    sley_motion,
    window_span,
)

DEG = DEG_PER_RAD
MOTION_VARS = {
    "theta3": ("deg", "rocker DC angle theta3"),
    "theta3_rate": ("rad rad-1", "theta3' per unit crank angle"),
    "theta3_accel": ("rad rad-2", "theta3'' per unit crank angle squared"),
    "theta6": ("deg", "sley sword FE angle theta6"),
    "theta6_rate": ("rad rad-1", "theta6' per unit crank angle"),
    "theta6_accel": ("rad rad-2", "theta6'' per unit crank angle squared"),
}


def _motion_vars(motion, dim: str, suffix: str = "") -> dict[str, xr.DataArray]:
    out = {}
    for name, (unit, long_name) in MOTION_VARS.items():
        value = getattr(motion, name)
        out[name + suffix] = xr.DataArray(
            value * DEG if unit == "deg" else value, dims=dim, attrs={"units": unit, "long_name": long_name}
        )
    return out


def _scalar(value: float, unit: str, long_name: str) -> xr.DataArray:
    return xr.DataArray(float(value), attrs={"units": unit, "long_name": long_name})


def fd_rates(mechanism, theta1: np.ndarray, step: float) -> tuple[np.ndarray, ...]:
    """Central differences of the solved angles (independent of the analytic rates)."""
    plus, minus, mid = (sley_motion(mechanism, theta1 + d) for d in (step, -step, 0.0))
    out = []
    for name in ("theta3", "theta6"):
        p, m, c = (getattr(x, name) for x in (plus, minus, mid))
        dp, dm = np.angle(np.exp(1j * (p - c))), np.angle(np.exp(1j * (m - c)))
        out += [(dp - dm) / (2 * step), (dp + dm) / step**2]
    return tuple(out)


def _grids(section: Mapping[str, Any]):
    grids = section["grids"]
    return angle_grid_deg(grids["paper_step_deg"]), angle_grid_deg(grids["fine_step_deg"])


#: The sense-dependent features: scenario variable -> (SenseReading field, long name).
SENSE_FEATURES = {
    "span_front_to_back": ("span_front_to_back", "crank angle turned from the front to the back dead centre"),
    "rate_peak_1": (
        "rate_peak_backward",
        "crank angle from the front dead centre of the largest sley speed towards the back (first peak)",
    ),
    "rate_peak_2": (
        "rate_peak_forward",
        "crank angle from the front dead centre of the largest sley speed towards the front (second peak)",
    ),
    "accel_peak": ("accel_peak", "crank-angle distance of the largest |theta6''| from the front dead centre"),
}


def headline(mech, fine, fine_deg: np.ndarray, numerics: Mapping[str, Any], sense: str) -> dict[str, xr.DataArray]:
    """Dead centres, swing, and the sense-dependent features (front-to-back span, velocity and acceleration peaks)
    in both crank senses (``<name>_by_sense`` along ``crank_sense``) and in the scenario's ``sense`` (``<name>``)."""
    data = {}
    dc = dead_centres(mech, numerics["scan_points"], numerics["root_xtol_rad"])
    data["front_dead_centre"] = _scalar(dc.front * DEG, "deg", "crank angle of the front dead centre (theta6 maximum)")
    data["back_dead_centre"] = _scalar(dc.back * DEG, "deg", "crank angle of the back dead centre (theta6 minimum)")
    data["swing"] = _scalar(dc.swing * DEG, "deg", "total sley swing")
    extremes = rate_extremes(mech, numerics["scan_points"], numerics["root_xtol_rad"])
    data["rate_max_theta1"] = _scalar(
        extremes[0] * DEG, "deg", "crank angle theta1 of the largest theta6' (a zero of theta6'')"
    )
    data["rate_min_theta1"] = _scalar(
        extremes[1] * DEG, "deg", "crank angle theta1 of the smallest theta6' (a zero of theta6'')"
    )
    accel_theta1 = float(np.radians(fine_deg[np.argmax(np.abs(fine.theta6_accel))]))
    readings = [sense_reading(dc, extremes, accel_theta1, CRANK_SENSES[name]) for name in CRANK_SENSES]
    names = list(CRANK_SENSES)
    for var, (field, long_name) in SENSE_FEATURES.items():
        values = np.array([getattr(r, field) for r in readings]) * DEG
        data[f"{var}_by_sense"] = xr.DataArray(values, dims="crank_sense", coords={"crank_sense": names},
                                               attrs={"units": "deg", "long_name": f"{long_name}, in each crank sense"})
        data[var] = _scalar(values[names.index(sense)], "deg", f"{long_name} (crank turning towards {sense} theta1)")
    data["theta6_accel_abs_max"] = _scalar(
        np.abs(fine.theta6_accel).max(), "rad rad-2", "largest |theta6''| over a turn"
    )
    return data


def motion(section: Mapping[str, Any]) -> tuple[xr.Dataset, Any, Any]:
    """Six-bar angles and derivatives on the paper's and the fine grid with the headline numbers: what the
    published numbers are read from, the sense-dependent ones in the crank sense of the scenario
    (``sixbar.crank_sense``) and, beside them, in both senses.  Returns (Dataset, mechanism, paper-grid motion)."""
    mech = six_bar(section["sixbar"])
    paper_deg, fine_deg = _grids(section)
    paper, fine = (sley_motion(mech, np.radians(g)) for g in (paper_deg, fine_deg))
    coords = {
        "crank_angle": ("crank_angle", paper_deg, {"units": "deg", "long_name": "crank angle theta1 (paper grid)"}),
        "crank_angle_fine": (
            "crank_angle_fine", fine_deg, {"units": "deg", "long_name": "crank angle theta1 (fine grid)"},
        ),
    }
    sense = crank_sense(section["sixbar"])
    data = {**_motion_vars(paper, "crank_angle"), **_motion_vars(fine, "crank_angle_fine", "_fine"),
            **headline(mech, fine, fine_deg, section["numerics"], sense)}
    ds = xr.Dataset(data, coords=coords)
    ds["crank_sense"].attrs.update(
        units="1", long_name="sense the crank turns in: towards decreasing or increasing theta1"
    )
    ds.attrs.update(crank_sense=sense)
    return ds, mech, paper


def sixbar(section: Mapping[str, Any]) -> xr.Dataset:
    """Six-bar angles and derivatives on the paper's and a fine grid, dead centres, extremes, typo checks."""
    base, mech, _ = motion(section)
    paper_deg, _ = _grids(section)
    data = {}

    # independent routes on the paper grid: the paper's closed forms (corrected and printed) and finite differences
    signs = section["closed_form_signs"]
    for printed, tag in ((False, "eqs"), (True, "eqs_printed")):
        cf = paper_closed_form(mech, np.radians(paper_deg), signs["eq5"], signs["eq11"], printed=printed)
        for name in ("theta3_accel", "theta6_accel") if printed else MOTION_VARS:
            unit, long_name = MOTION_VARS[name]
            value = getattr(cf, name)
            label = "as printed (eqs. 7, 13)" if printed else "paper's closed forms, corrected"
            data[f"{name}_{tag}"] = xr.DataArray(
                value * DEG if unit == "deg" else value, dims="crank_angle",
                attrs={"units": unit, "long_name": f"{long_name}, {label}"},
            )
    step = np.radians(section["numerics"]["fd_step_deg"])
    for name, value in zip(
        ("theta3_rate", "theta3_accel", "theta6_rate", "theta6_accel"), fd_rates(mech, np.radians(paper_deg), step),
        strict=True,
    ):
        unit, long_name = MOTION_VARS[name]
        data[name + "_fd"] = xr.DataArray(
            value, dims="crank_angle", attrs={"units": unit, "long_name": f"{long_name}, central differences"}
        )

    # how far the paper's closed forms are from the chain solver (corrected: rounding; printed (7)/(13): their typos)
    for name in MOTION_VARS:
        diff = np.abs(data[f"{name}_eqs"].values - base[name].values)
        unit = MOTION_VARS[name][0]
        data[f"{name}_eqs_max_difference"] = _scalar(
            diff.max(), unit, f"max |corrected closed form - chain solver| of {name} on the paper grid"
        )
    for name in ("theta3_accel", "theta6_accel"):
        diff = np.abs(data[f"{name}_eqs_printed"].values - base[name].values)
        data[f"{name}_eqs_printed_max_difference"] = _scalar(
            diff.max(), MOTION_VARS[name][0], f"max |printed eq. (7)/(13) - chain solver| of {name} on the paper grid"
        )
    ds = base.assign(data)
    ds.attrs.update(
        title="GN721 six-bar beating-up mechanism: sley motion", fd_step_deg=section["numerics"]["fd_step_deg"],
        scan_points=section["numerics"]["scan_points"], root_xtol_rad=section["numerics"]["root_xtol_rad"],
    )
    return ds


def _displacement_from_front(angles: np.ndarray, radius: float) -> np.ndarray:
    return reed_displacement(angles, float(angles.max()), radius)


def window(section: Mapping[str, Any]) -> xr.Dataset:
    """Reed displacement at cloth-fell height of the scaled six-bar and the four-bar; weft windows; sweeps."""
    cmp = section["comparison"]
    stroke = float(cmp["stroke_m"])
    grid_deg = angle_grid_deg(section["grids"]["fine_step_deg"])
    theta1 = np.radians(grid_deg)

    six = six_bar(section["sixbar"], crank_m=cmp["scaled_crank_m"])
    six_angle = sley_motion(six, theta1).theta6
    r6 = radius_for_stroke(six_angle.max(), six_angle.min(), stroke)
    s6 = _displacement_from_front(six_angle, r6)
    front6 = theta1[np.argmax(six_angle)]

    fourbar_cfg = section["fourbar"]
    four = four_bar_beatup(fourbar_cfg)
    four_angle = four.sword_angle(theta1)
    r4 = radius_for_stroke(four_angle.max(), four_angle.min(), stroke)
    s4 = _displacement_from_front(four_angle, r4)
    front4 = theta1[np.argmax(four_angle)]

    sw = float(fourbar_cfg["weft_clearance_m"]["value"])
    phi = xr.DataArray(
        grid_deg, dims="angle_from_front", attrs={"units": "deg", "long_name": "crank angle from the front dead centre"}
    )

    def shifted(s: np.ndarray, front: float) -> np.ndarray:
        return np.roll(s, -int(round(front / (theta1[1] - theta1[0]))))

    data = {
        "reed_sixbar": xr.DataArray(
            shifted(s6, front6) * 1e3, dims="angle_from_front",
            attrs={"units": "mm", "long_name": "reed displacement from the front, scaled six-bar"},
        ),
        "reed_fourbar": xr.DataArray(
            shifted(s4, front4) * 1e3, dims="angle_from_front",
            attrs={"units": "mm", "long_name": "reed displacement from the front, four-bar"},
        ),
        "reed_radius_sixbar": _scalar(r6 * 1e3, "mm", "cloth-fell radius on the six-bar sword giving the stroke"),
        "reed_radius_fourbar": _scalar(r4 * 1e3, "mm", "cloth-fell radius on the four-bar sword giving the stroke"),
        "swing_sixbar_scaled": _scalar(
            (six_angle.max() - six_angle.min()) * DEG, "deg", "sley swing of the scaled six-bar"
        ),
        "window_sixbar": _scalar(window_span(theta1, s6, sw) * DEG, "deg", "crank angle with S > S_w, scaled six-bar"),
        "window_fourbar": _scalar(window_span(theta1, s4, sw) * DEG, "deg", "crank angle with S > S_w, four-bar"),
    }
    data["window_difference"] = _scalar(
        float(data["window_sixbar"] - data["window_fourbar"]), "deg", "six-bar window minus four-bar window"
    )

    sweep = section["sweep"]
    ratios = np.asarray(sweep["arm_to_crank"], dtype=float)
    span = sweep["weft_clearance_m"]
    sw_grid = np.linspace(span["start"], span["stop"], span["num"])
    six_windows = np.array([window_span(theta1, s6, x) for x in sw_grid])
    four_windows = np.empty((ratios.size, sw_grid.size))
    for i, ratio in enumerate(ratios):
        angle = four_bar_beatup(fourbar_cfg, arm_to_crank=ratio).sword_angle(theta1)
        s = _displacement_from_front(angle, radius_for_stroke(angle.max(), angle.min(), stroke))
        four_windows[i] = [window_span(theta1, s, x) for x in sw_grid]
    coords = {
        "angle_from_front": phi,
        "arm_to_crank": ("arm_to_crank", ratios, {"units": "1", "long_name": "four-bar connecting arm / crank L/R"}),
        "weft_clearance": (
            "weft_clearance", sw_grid * 1e3,
            {"units": "mm", "long_name": "S_w, reed distance from the front that lets the weft carrier pass"},
        ),
    }
    data["window_sixbar_sweep"] = xr.DataArray(
        six_windows * DEG, dims="weft_clearance", attrs={"units": "deg", "long_name": "six-bar window vs S_w"}
    )
    data["window_fourbar_sweep"] = xr.DataArray(
        four_windows * DEG, dims=("arm_to_crank", "weft_clearance"),
        attrs={"units": "deg", "long_name": "four-bar window vs L/R and S_w"},
    )
    return xr.Dataset(data, coords=coords, attrs={"title": "Six-bar vs four-bar weft window"})
