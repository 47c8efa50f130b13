"""The beat-up paper's comparison and findings: every published number beside ours, every Table 1 cell
classified with the evidence of which side is wrong, and what the printed weft windows constrain."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import pandas as pd
import xarray as xr

from ...pipeline.compare import compare as compare_one
from ...pipeline.compare import tolerance_of
from ...pipeline.compare import (compare_datasets, counts_dataset, expand_tables, findings_attrs, scalar)
from ...units import DEG_PER_RAD
from .adapter import crank_sense, rounding_half_units, sense_labels, six_bar
from .model import (
    CRANK_SENSES, ParameterFit, SleyMotion, coarse_central_difference, dead_centres, fit_table_angles, sley_motion,
    with_parameters,
)

CLASSES = (
    "matches the fitted model", "printed cell inconsistent", "inconclusive", "marginal",
    "matches the refit with the offset parameter unbounded", "matches only the printed parameters",
    "beyond the fitted model",
)
MOTION_UNITS = {
    "theta3": "deg",
    "theta3_rate": "rad rad-1",
    "theta3_accel": "rad rad-2",
    "theta6": "deg",
    "theta6_rate": "rad rad-1",
    "theta6_accel": "rad rad-2",
}
SOLVER_ERROR = 1.0e-12  # the chain solver against the paper's corrected closed forms (tests)
# theta3 and its derivatives depend only on the crank-rocker ABCD; a parameter outside it moves theta6 alone
ROCKER_PARAMETERS = frozenset({"l1", "l2", "l3", "l4", "theta4"})
ROCKER_COLUMNS = frozenset({"theta3", "theta3_rate", "theta3_accel"})


def columns_moved_by(parameter: str) -> frozenset[str]:
    """The Table 1 columns a six-bar parameter moves (theta6 ones always; theta3 ones only for the crank-rocker's)."""
    return frozenset(MOTION_UNITS) if parameter in ROCKER_PARAMETERS else frozenset(MOTION_UNITS) - ROCKER_COLUMNS


def printed_table(published: Mapping[str, Any]) -> tuple[np.ndarray, dict[str, np.ndarray], dict[str, float]]:
    """(crank angles in deg, printed column by our variable name, half a printed digit by variable) of Table 1."""
    spec = next(t for t in published["tables"] if t["id"] == "table1")
    rows = np.array(spec["rows"], dtype=float)
    printed, tolerance = {}, {}
    for j, name in enumerate(spec["column_names"]):
        col = spec["columns"][name]
        printed[col["variable"]] = rows[:, j + 1]
        tolerance[col["variable"]] = float(col["tolerance"]["abs"])
    return rows[:, 0], printed, tolerance


EVIDENCE_SOURCES = {
    # derivative column -> (the printed column it is checked against, whether that column is an angle in deg)
    "theta3_rate": ("theta3", True),
    "theta3_accel": ("theta3_rate", False),
    "theta6_rate": ("theta6", True),
    "theta6_accel": ("theta6_rate", False),
}


def motion_columns(motion: SleyMotion) -> dict[str, np.ndarray]:
    """A SleyMotion as Table 1's columns (angles in deg, derivatives per unit crank angle)."""
    return {
        name: getattr(motion, name) * (DEG_PER_RAD if unit == "deg" else 1.0) for name, unit in MOTION_UNITS.items()
    }


def coarse_differences(motion: SleyMotion, step_deg: float) -> dict[str, np.ndarray]:
    """Each derivative column of ours recomputed as the paper-step central difference of its source column."""
    h = np.radians(step_deg)
    return {
        col: coarse_central_difference(getattr(motion, src), h, is_angle)
        for col, (src, is_angle) in EVIDENCE_SOURCES.items()
    }


def table1_evidence(
    ours: dict[str, np.ndarray],
    ours_fd: dict[str, np.ndarray],
    error: dict[str, float],
    theta1: np.ndarray,
    printed: dict[str, np.ndarray],
    tolerance: dict[str, float],
    step_deg: float,
    offset_model: dict[str, np.ndarray] | None = None,
    nominal_model: dict[str, np.ndarray] | None = None,
    offset_moves: frozenset[str] | None = None,
) -> list[dict[str, Any]]:
    """Classify every printed Table 1 cell against one model (the joint fit), with the evidence why a cell differs.

    ours: column -> model values at theta1; ours_fd: derivative column -> the model's paper-step central
    difference of its source column; error: column -> our numerical error of the model; printed, tolerance:
    the printed columns and half a unit of their last digit.  Rule: a cell **matches the fitted model** if
    |printed - ours| <= tolerance + error.  Otherwise, for a derivative, the printed column it derives from (theta for
    theta', theta' for theta'') is differenced at the paper's step and set beside the same difference of ours: if they
    agree within that column's rounding, the paper's own neighbouring cells agree with us (**printed cell
    inconsistent**); if a neighbour is itself off, **inconclusive**; a deviation smaller than what that check resolves
    is **marginal**.  Before that check, a cell of a column the offset parameter moves (``offset_moves``; all columns if
    None) that matches ``offset_model`` (the joint fit refitted with the parameter that removes the systematic theta6
    offset freed of its bound; the other parameters re-adjust within rounding) **matches the refit with the offset
    parameter unbounded**.  A column the offset parameter cannot move is not given that class: its change in the refit
    would come from the other parameters' re-adjustment, not from the offset.  An angle that matches neither but matches
    ``nominal_model`` (the printed parameters; the joint fit traded it for others) **matches only the
    printed parameters**; else it is **beyond the fitted model**.
    """
    h = np.radians(step_deg)
    rows = []
    for col, values in printed.items():
        model, tol, err = ours[col], tolerance[col], error[col]
        if col in EVIDENCE_SOURCES:
            src, is_angle = EVIDENCE_SOURCES[col]
            src_values = np.radians(printed[src]) if is_angle else printed[src]
            printed_fd = coarse_central_difference(src_values, h, is_angle)
            src_tol = np.radians(tolerance[src]) if is_angle else tolerance[src]
            fd_uncertainty = 2 * src_tol / (2 * h) * 2  # two rounded cells, with a factor 2 margin
        for i, angle in enumerate(theta1):
            dev = values[i] - model[i]
            row = {
                "column": col,
                "theta1": float(angle),
                "printed": float(values[i]),
                "ours": float(model[i]),
                "deviation": float(dev),
                "tolerance": tol,
                "numerical_error": err,
                "deviation_in_tolerances": float(dev / (tol + err)),
                "printed_column_fd": np.nan,
                "our_coarse_fd": np.nan,
                "offset_model": np.nan if offset_model is None else float(offset_model[col][i]),
                "nominal_model": np.nan if nominal_model is None else float(nominal_model[col][i]),
            }
            if abs(dev) <= (tol + err) * (1 + 1e-9):
                row["class"] = "matches the fitted model"
            elif (offset_model is not None and (offset_moves is None or col in offset_moves)
                  and abs(values[i] - offset_model[col][i]) <= (tol + err) * (1 + 1e-9)):
                row["class"] = "matches the refit with the offset parameter unbounded"
            elif col in EVIDENCE_SOURCES:
                row["printed_column_fd"] = float(printed_fd[i])
                row["our_coarse_fd"] = float(ours_fd[col][i])
                agree = abs(printed_fd[i] - ours_fd[col][i]) <= fd_uncertainty
                if abs(dev) <= fd_uncertainty:
                    row["class"] = "marginal"
                else:
                    row["class"] = "printed cell inconsistent" if agree else "inconclusive"
            elif nominal_model is not None and abs(values[i] - nominal_model[col][i]) <= (tol + err) * (1 + 1e-9):
                row["class"] = "matches only the printed parameters"
            else:
                row["class"] = "beyond the fitted model"
            rows.append(row)
    return rows


def evidence_dataset(rows: list[dict[str, Any]]) -> xr.Dataset:
    """The classified Table 1 cells as a Dataset along ``cell``."""
    df = pd.DataFrame(rows)
    same = "unit of the column"
    long_names = {
        "theta1": ("deg", "crank angle theta1"),
        "printed": (same, "printed value"),
        "ours": (same, "the fitted model's value"),
        "deviation": (same, "printed - fitted model"),
        "tolerance": (same, "half a unit of the printed last digit"),
        "numerical_error": (same, "our numerical error of the fitted model (fit tolerance and chain solver)"),
        "deviation_in_tolerances": (
            "1",
            "(printed - fitted model) / (half a printed digit + numerical error); |.| <= 1: matches",
        ),
        "printed_column_fd": (same, "15 deg central difference of the printed source column"),
        "our_coarse_fd": (same, "the same difference of the fitted model"),
        "offset_model": (
            same,
            "the joint fit refitted with the offset parameter unbounded (the others within rounding)",
        ),
        "nominal_model": (same, "the model at the printed parameters"),
    }
    data = {k: ("cell", df[k].to_numpy(dtype=float), {"units": u, "long_name": n}) for k, (u, n) in long_names.items()}
    for k in ("printed_column_fd", "our_coarse_fd"):
        data[k][2]["nan_meaning"] = "computed only for a cell that does not match the fitted model"
    data["column"] = (
        "cell", df["column"].to_numpy(dtype=object), {"units": "1", "long_name": "Table 1 column (our variable name)"},
    )
    data["cell_class"] = (
        "cell", df["class"].to_numpy(dtype=object), {"units": "1", "long_name": "why the cell matches or not"},
    )
    return xr.Dataset(data, coords={"cell": ("cell", np.arange(len(df)), {"units": "1", "long_name": "Table 1 cell"})})


SYMBOL = {
    "l4": "l4",
    "l7": "l7",
    "theta4": "θ4",
    "theta7": "θ7",
    "l1": "l1",
    "l2": "l2",
    "l3": "l3",
    "l5": "l5",
    "l6": "l6",
}
PARAMETER_DISPLAY = {"l": ("mm", 1e3), "theta": ("deg", DEG_PER_RAD)}


def _display(name: str) -> tuple[str, float]:
    return PARAMETER_DISPLAY["theta" if name.startswith("theta") else "l"]


def table1_fit(
    cfg: Mapping[str, Any], crank_deg: np.ndarray, printed: dict[str, np.ndarray], tolerance: dict[str, float]
) -> dict[str, Any]:
    """The joint fit of the printed parameters to Table 1's 48 angles, and what explains the theta6 offset.

    Fits (least squares, ``table1_fit.tolerance``): the parameters of ``printed_rounding`` jointly within
    their rounding intervals (the model every cell is judged against), jointly without bounds, and each
    alone without bounds.  The bounded fit is repeated at ``check_tolerance``: the change of each column
    plus the chain solver's error is our numerical error.  A parameter moved alone *explains* the offset
    if it leaves at most ``offset_explained_fraction`` of the mean theta6 offset at the printed values.
    """
    mech = six_bar(cfg["sixbar"])
    half = rounding_half_units(cfg["printed_rounding"])
    fcfg = cfg["table1_fit"]
    t1 = np.radians(crank_deg)
    t3, t6 = np.radians(printed["theta3"]), np.radians(printed["theta6"])
    scale = np.radians(tolerance["theta3"])

    def fit(names: tuple[str, ...], bounded: bool, tol: float, unbounded: tuple[str, ...] = ()) -> ParameterFit:
        return fit_table_angles(
            mech, t1, t3, t6, {n: half[n] for n in names}, bounded=bounded, tol=tol, scale=scale, unbounded=unbounded
        )

    names = tuple(half)
    joint = fit(names, True, fcfg["tolerance"])
    check = fit(names, True, fcfg["check_tolerance"])
    free = fit(names, False, fcfg["tolerance"])
    alone = {n: fit((n,), False, fcfg["tolerance"]) for n in names}

    def motion_of(f: ParameterFit | None) -> SleyMotion:
        return sley_motion(mech if f is None else with_parameters(mech, f.names, f.value), t1)

    fitted, checked = motion_of(joint), motion_of(check)
    cols, check_cols = motion_columns(fitted), motion_columns(checked)
    error = {
        c: (
            float(np.abs(cols[c] - check_cols[c]).max())
            + SOLVER_ERROR * (DEG_PER_RAD if MOTION_UNITS[c] == "deg" else 1.0)
        )
        for c in cols
    }

    cases = {"printed parameters": None, "joint fit within rounding": joint, "joint fit without bounds": free,
             **{f"{n} alone, without bounds": f for n, f in alone.items()}}
    case_cols = {label: motion_columns(motion_of(f)) for label, f in cases.items()}

    def offset(label: str) -> float:
        return float(np.mean(printed["theta6"] - case_cols[label]["theta6"]))

    # the parameters that, moved alone, remove the mean theta6 offset; the one that needs the smallest change
    explains = np.array(
        [
            abs(offset(f"{n} alone, without bounds"))
            <= fcfg["offset_explained_fraction"] * abs(offset("printed parameters"))
            for n in names
        ]
    )
    alone_shift = np.array([alone[n].shift[0] for n in names])
    best = (
        int(np.argmin(np.where(explains, np.abs(alone_shift), np.inf)))
        if explains.any()
        else int(np.argmin(np.abs(alone_shift)))
    )
    best_name = names[best]
    unit, factor = _display(best_name)
    # the joint fit with that parameter freed: the model a cell is set against to see whether the offset explains it
    offset_label = f"joint fit, {best_name} without bounds"
    cases[offset_label] = fit(names, True, fcfg["tolerance"], unbounded=(best_name,))
    case_cols[offset_label] = motion_columns(motion_of(cases[offset_label]))

    mean3, mean6, rms, n_match, same_sign = [], [], [], [], []
    for label in cases:
        c = case_cols[label]
        d3, d6 = printed["theta3"] - c["theta3"], printed["theta6"] - c["theta6"]
        mean3.append(d3.mean())
        mean6.append(d6.mean())
        rms.append(np.sqrt(np.mean(np.concatenate([d3, d6]) ** 2)))
        n_match.append(
            int(
                (np.abs(d3) <= tolerance["theta3"] * (1 + 1e-9)).sum()
                + (np.abs(d6) <= tolerance["theta6"] * (1 + 1e-9)).sum()
            )
        )
        same_sign.append(int(max((d6 > 0).sum(), (d6 < 0).sum())))
    shift = np.full((len(cases), len(names)), np.nan)
    for k, f in enumerate(cases.values()):
        if f is not None:
            for n, u in zip(f.names, f.shift, strict=True):
                shift[k, names.index(n)] = u
    display_units = [_display(n)[0] for n in names]
    data = {
        "fit_printed_value": (
            "fit_parameter", [joint.start[i] * _display(n)[1] for i, n in enumerate(names)],
            {"units": "mm or deg (fit_parameter_unit)", "long_name": "printed value"},
        ),
        "fit_half_width": (
            "fit_parameter",
            [joint.half_width[i] * _display(n)[1] for i, n in enumerate(names)],
            {
                "units": "mm or deg (fit_parameter_unit)",
                "long_name": "half a unit of the printed last digit (rounding half-width)",
            },
        ),
        "fit_value": (
            "fit_parameter", [joint.value[i] * _display(n)[1] for i, n in enumerate(names)],
            {"units": "mm or deg (fit_parameter_unit)", "long_name": "joint fit within rounding"},
        ),
        "fit_parameter_unit": (
            "fit_parameter", np.array(display_units, dtype=object),
            {"units": "1", "long_name": "unit of the parameter's values"},
        ),
        "fit_shift": (
            ("fit_case", "fit_parameter"),
            shift,
            {
                "units": "1",
                "long_name": "parameter change in rounding half-widths (|shift| <= 1: inside rounding)",
                "nan_meaning": "the parameter is held at its printed value in this fit",
            },
        ),
        "fit_theta3_mean_offset": (
            "fit_case", mean3, {"units": "deg", "long_name": "mean of printed theta3 - model over the 24 rows"},
        ),
        "fit_theta6_mean_offset": (
            "fit_case", mean6, {"units": "deg", "long_name": "mean of printed theta6 - model over the 24 rows"},
        ),
        "fit_rms": ("fit_case", rms, {"units": "deg", "long_name": "rms of printed - model over the 48 angles"}),
        "fit_angles_within_printing": (
            "fit_case", n_match, {"units": "1", "long_name": "angle cells within half a unit of the printed digit"},
        ),
        "fit_theta6_same_sign": (
            "fit_case", same_sign,
            {"units": "1", "long_name": "theta6 rows whose printed - model has the majority sign"},
        ),
        "fit_explains_offset": (
            "fit_parameter",
            explains.astype(int),
            {
                "units": "1",
                "long_name": (
                    "1 if the parameter moved alone removes the mean theta6 offset (offset_explained_fraction)"
                ),
            },
        ),
        "fit_condition": scalar(
            free.condition, "1",
            "condition number of the Jacobian of the joint fit without bounds (in rounding half-widths)",
        ),
        "fit_at_bound": scalar(
            int((np.abs(joint.shift) >= 1 - 1e-9).sum()), "1", "parameters of the joint fit at a rounding bound"
        ),
        "fit_numerical_error_theta6": scalar(error["theta6"], "deg", "our numerical error of the fitted theta6 column"),
        "fit_numerical_error_max": scalar(
            max(error.values()), "unit of the column",
            "largest numerical error of the fitted model over Table 1's columns",
        ),
        "offset_shift": scalar(
            alone_shift[best], "1",
            f"change of {best_name} alone that removes the theta6 offset, in rounding half-widths",
        ),
        "offset_change": scalar(
            alone[best_name].value[0] * factor - alone[best_name].start[0] * factor, unit,
            f"change of {best_name} alone that removes the theta6 offset",
        ),
    }
    coords = {
        "fit_parameter": (
            "fit_parameter", np.array(names, dtype=object),
            {"units": "1", "long_name": "fitted printed parameter (SixBar field)"},
        ),
        "fit_case": (
            "fit_case", np.array(list(cases), dtype=object),
            {"units": "1", "long_name": "which parameters are fitted, and how"},
        ),
    }
    return {
        "data": data,
        "coords": coords,
        "fitted": fitted,
        "fitted_mechanism": with_parameters(mech, joint.names, joint.value),
        "columns": cols,
        "error": error,
        "offset_columns": case_cols[offset_label],
        "nominal_columns": case_cols["printed parameters"],
        "offset_parameter": best_name,
        "offset_unit": unit,
        "names": names,
    }


def printed_parameter_cells(evidence: xr.Dataset) -> dict[str, tuple]:
    """How many Table 1 cells the model at the printed parameters (no fit) gives within half a unit and within one
    unit of the printed last digit (our numerical error added to the band)."""
    gap = np.abs(evidence.printed.values - evidence.nominal_model.values) - evidence.numerical_error.values
    half = evidence.tolerance.values
    return {
        "table1_printed_within_half_digit": scalar(
            int((gap <= half).sum()), "1", "Table 1 cells within half a printed digit, model at the printed parameters"
        ),
        "table1_printed_within_one_digit": scalar(
            int((gap <= 2 * half).sum()), "1", "Table 1 cells within one printed digit, model at the printed parameters"
        ),
    }


def fitted_dataset(crank_deg: np.ndarray, columns: dict[str, np.ndarray]) -> xr.Dataset:
    """The fitted model's Table 1 columns on the printed crank angles (what the table cells are compared with)."""
    return xr.Dataset(
        {
            c: ("crank_angle", v, {"units": MOTION_UNITS[c], "long_name": f"{c}, joint fit within rounding"})
            for c, v in columns.items()
        },
        coords={"crank_angle": ("crank_angle", crank_deg, {"units": "deg", "long_name": "crank angle theta1"})},
    )


PEAK_IDS = (
    "rate_peak_1",
    "rate_peak_2",
)  # the velocity peaks: the evidence for the crank sense that is not the 167.28 deg itself


def sense_dependent(published: Mapping[str, Any], sixbar: xr.Dataset) -> list[dict[str, Any]]:
    """The published quantities whose measured variable depends on the crank sense (it has a ``_by_sense`` twin)."""
    return [q for q in published["quantities"] if q["measure"] and f"{q['measure']['variable']}_by_sense" in sixbar]


def in_sense(sixbar: xr.Dataset, sense: str) -> xr.Dataset:
    """The result Dataset with every sense-dependent variable read in ``sense`` (what the scenario would give)."""
    out = sixbar.copy()
    for name in [v for v in sixbar.data_vars if str(v).endswith("_by_sense")]:
        out[str(name).removesuffix("_by_sense")] = sixbar[name].sel(crank_sense=sense, drop=True)
    return out.drop_vars([v for v in sixbar.data_vars if str(v).endswith("_by_sense")] + ["crank_sense"])


def sense_comparison(published: Mapping[str, Any], sixbar: xr.Dataset, errors: Mapping[str, tuple[float, str]],
                     labels: Mapping[str, str]) -> dict[str, Any]:
    """Every sense-dependent claim judged in both crank senses at the printed parameters (compare's verdict rule),
    and which sense the velocity peaks pick on their own (both peaks match in that sense only)."""
    entries = sense_dependent(published, sixbar)
    senses = [str(s) for s in sixbar.crank_sense.values]
    tables = {
        s: (
            compare_one(
                {**published, "quantities": entries, "tables": []}, in_sense(sixbar, s), errors=errors
            ).set_index("id")
        )
        for s in senses
    }
    ids = [q["id"] for q in entries]
    value = np.array([[tables[s].loc[q, "reproduced"] for s in senses] for q in ids])
    verdict = np.array([[tables[s].loc[q, "verdict"] for s in senses] for q in ids], dtype=object)
    published_value = np.array([q["value"] for q in entries], dtype=float)
    peaks_hold = [all(tables[s].loc[q, "verdict"] == "reproduced" for q in PEAK_IDS) for s in senses]
    picked = senses[peaks_hold.index(True)] if sum(peaks_hold) == 1 else ("none" if not any(peaks_hold) else "both")
    return {
        "data": {
            "sense_value": (
                ("sense_quantity", "crank_sense"), value,
                {"units": "deg", "long_name": "our value in each crank sense (printed parameters)"},
            ),
            "sense_distance": (
                ("sense_quantity", "crank_sense"), np.abs(value - published_value[:, None]),
                {"units": "deg", "long_name": "|ours - published| in each crank sense"},
            ),
            "sense_verdict": (
                ("sense_quantity", "crank_sense"), verdict,
                {"units": "1", "long_name": "verdict in each crank sense (printed parameters)"},
            ),
            "sense_tolerance": (
                "sense_quantity", np.array([tolerance_of(q) for q in entries]),
                {"units": "deg", "long_name": "published tolerance"},
            ),
            "sense_peaks_hold": (
                "crank_sense", np.array(peaks_hold, dtype=int),
                {"units": "1", "long_name": "1 if both velocity peaks match in this sense"},
            ),
            "sense_claims_matched": (
                "crank_sense", np.array([int((verdict[:, j] == "reproduced").sum()) for j in range(len(senses))]),
                {"units": "1", "long_name": "sense-dependent claims that match in this sense"},
            ),
        },
        "coords": {
            "sense_quantity": (
                "sense_quantity", np.array(ids, dtype=object), {"units": "1", "long_name": "published id"},
            ),
            "crank_sense": (
                "crank_sense", np.array(senses, dtype=object), {"units": "1", "long_name": "sense the crank turns in"},
            ),
            "crank_sense_label": (
                "crank_sense", np.array([labels[s] for s in senses], dtype=object),
                {"units": "1", "long_name": "readable name"},
            ),
        },
        "picked": picked,
    }


def window_constraints(window: xr.Dataset, sixbar_window: float, fourbar_window: float, band: float) -> dict[str, Any]:
    """S_w at which our six-bar reaches the printed window, our four-bar windows there, and the L/R that give
    the printed four-bar window within ``band`` (deg)."""
    sw_grid = window.weft_clearance.values
    w6, w4 = window.window_sixbar_sweep.values, window.window_fourbar_sweep.values
    ratios = window.arm_to_crank.values
    sw = float(np.interp(sixbar_window, w6[::-1], sw_grid[::-1]))
    w4_at = np.array([np.interp(sw, sw_grid, w4[i]) for i in range(ratios.size)])
    ok = ratios[np.abs(w4_at - fourbar_window) <= band]
    return {
        "sw_for_printed_sixbar_window": scalar(sw, "mm", "S_w at which our six-bar window equals the printed one"),
        "fourbar_window_at_that_sw": (
            "arm_to_crank", w4_at, {"units": "deg", "long_name": "four-bar window at that S_w, per L/R"},
        ),
        "fourbar_window_band": (
            (), float(band),
            {"units": "deg", "long_name": "band around the printed four-bar window", "tolerance_source": "our reading"},
        ),
        "arm_to_crank_in_band_min": scalar(
            ok.min() if ok.size else np.nan, "1", "smallest L/R giving the printed four-bar window within the band"
        ),
        "arm_to_crank_in_band_max": scalar(
            ok.max() if ok.size else np.nan, "1", "largest L/R giving the printed four-bar window within the band"
        ),
    }


def numerical_errors(published: Mapping[str, Any], sixbar: xr.Dataset) -> dict[str, tuple[float, str]]:
    """Our numerical error bar for every headline number of the beat-up paper."""
    xtol = float(sixbar.attrs["root_xtol_rad"]) * DEG_PER_RAD
    half_grid = float(sixbar.crank_angle_fine[1] - sixbar.crank_angle_fine[0]) / 2
    rules = {
        "front_dead_centre": (xtol, "Brent's method on theta6' (x-tolerance)"),
        "swing": (1e-10, "theta6 at the dead centres, analytic"),
        "span_front_to_back": (2 * xtol, "two dead centres by Brent's method"),
        "rate_peak_1": (2 * xtol, "Brent's method on theta6'' and on theta6' (the front dead centre)"),
        "rate_peak_2": (2 * xtol, "Brent's method on theta6'' and on theta6' (the front dead centre)"),
        "accel_peak": (half_grid, "located on the fine crank-angle grid (half a step)"),
    }
    return {q["id"]: rules[q["id"]] for q in published["quantities"] if q["id"] in rules}


FIT_SOURCE = "one joint least-squares fit of {names} to Table 1's 48 angles, within their rounding"


def compare_table1(published: Mapping[str, Any], crank_deg: np.ndarray, fit: Mapping[str, Any]) -> pd.DataFrame:
    """Table 1's cells against the fitted model: matches, deviates or undetermined (numerics); no input range
    (the rounding of the printed parameters is taken up by the fit)."""
    tables_only = {**published, "quantities": []}
    source = "fit repeated at the check tolerance, plus the chain solver"
    errors = {e["id"]: (fit["error"][e["measure"]["variable"]], source) for e in expand_tables(tables_only)}
    table = compare_one(tables_only, fitted_dataset(crank_deg, fit["columns"]), errors=errors)
    table["input_source"] = FIT_SOURCE.format(names=", ".join(fit["names"]))
    return table


# headline numbers read as a note at the fitted parameters: published id -> DeadCentres field (rad) in each crank sense
FITTED_NOTES = {
    "front_dead_centre": {1: "front", -1: "front"},
    "span_front_to_back": {1: "span_forward", -1: "span_reverse"},
    "swing": {1: "swing", -1: "swing"},
}


def fitted_headline_notes(fit: Mapping[str, Any], numerics: Mapping[str, Any], pub: Mapping[str, Any],
                          errors: Mapping[str, tuple[float, str]], sense: int) -> dict[str, Any]:
    """The dead-centre headline numbers at the joint fit of Table 1 (not at the printed parameters), for a crank
    turning in ``sense`` (+1 or -1): a note beside each verdict, not a second verdict.  Within = |fitted -
    published| <= tolerance + numerical error."""
    dc = dead_centres(fit["fitted_mechanism"], numerics["scan_points"], numerics["root_xtol_rad"])
    ids = list(FITTED_NOTES)
    values = np.array([getattr(dc, FITTED_NOTES[q][sense]) * DEG_PER_RAD for q in ids])
    tol = np.array([pub[q]["tolerance"]["abs"] for q in ids], dtype=float)
    err = np.array([errors[q][0] for q in ids])
    within = np.abs(values - np.array([pub[q]["value"] for q in ids], dtype=float)) <= tol + err
    return {
        "data": {
            "fitted_note_value": (
                "fitted_note_id", values,
                {"units": "deg", "long_name": "headline number at the joint fit of Table 1 (a note, not a verdict)"},
            ),
            "fitted_note_within": (
                "fitted_note_id", within.astype(int),
                {"units": "1", "long_name": "1 if within the published tolerance plus our numerical error"},
            ),
        },
        "coords": {
            "fitted_note_id": (
                "fitted_note_id", np.array(ids, dtype=object), {"units": "1", "long_name": "published id"},
            )
        },
    }


def compare(
    cfg: Mapping[str, Any],
    published: Mapping[str, Any],
    sixbar: xr.Dataset,
    window: xr.Dataset,
    uncertainty: xr.Dataset,
) -> tuple[pd.DataFrame, xr.Dataset]:
    """Comparison table and findings: headline numbers (in the crank sense of the scenario; the sense-dependent ones in
    both senses), Table 1 against one joint fit of the printed parameters, the theta6 offset, closed forms, window
    constraints."""
    crank_deg, printed, tolerance = printed_table(published)
    fit = table1_fit(cfg, crank_deg, printed, tolerance)
    headline = compare_datasets(
        {**published, "tables": []}, [sixbar, window], errors={"": numerical_errors(published, sixbar)},
        uncertainty=uncertainty,
    )
    table = pd.concat([headline, compare_table1(published, crank_deg, fit)], ignore_index=True)
    rows = table1_evidence(
        fit["columns"], coarse_differences(fit["fitted"], cfg["grids"]["paper_step_deg"]), fit["error"], crank_deg,
        printed, tolerance, cfg["grids"]["paper_step_deg"], offset_model=fit["offset_columns"],
        nominal_model=fit["nominal_columns"], offset_moves=columns_moved_by(fit["offset_parameter"]),
    )
    evidence = evidence_dataset(rows)
    classes = [str(c) for c in evidence.cell_class.values]
    t1 = table.role == "table cell"
    pub = {q["id"]: q for q in published["quantities"]}
    sense = crank_sense(cfg["sixbar"])
    labels = sense_labels(cfg["sixbar"])
    notes = sense_comparison(published, sixbar, numerical_errors(published, sixbar), labels)
    fitted_notes = fitted_headline_notes(
        fit, cfg["numerics"], pub, numerical_errors(published, sixbar), CRANK_SENSES[sense]
    )
    data: dict[str, Any] = {
        **fit["data"],
        **notes["data"],
        **fitted_notes["data"],
        "class_count": (
            "cell_class_name", [classes.count(c) for c in CLASSES],
            {"units": "1", "long_name": "Table 1 cells per class"},
        ),
        "table1_matches": scalar(
            (table[t1].verdict == "reproduced").sum(), "1", "Table 1 cells that match the fitted model"
        ),
        "table1_total": scalar(t1.sum(), "1", "Table 1 cells compared"),
        **printed_parameter_cells(evidence),
    }
    for name in ("theta3_accel", "theta6_accel"):
        as_printed = np.abs(sixbar[f"{name}_eqs_printed"].values - printed[name]).max()
        corrected = np.abs(sixbar[f"{name}_eqs"].values - printed[name]).max()
        data[f"{name}_printed_eqs_vs_table"] = scalar(
            as_printed, "rad rad-2", f"max |printed eq. (7)/(13) - Table 1| of {name}"
        )
        data[f"{name}_corrected_eqs_vs_table"] = scalar(
            corrected, "rad rad-2", f"max |corrected closed form - Table 1| of {name}"
        )
    data["printed_eqs_worse_factor"] = scalar(
        min(
            data[f"{n}_printed_eqs_vs_table"][1] / data[f"{n}_corrected_eqs_vs_table"][1]
            for n in ("theta3_accel", "theta6_accel")
        ),
        "1",
        "how many times further the printed (7)/(13) are from Table 1 than the corrected forms (smaller of the two)",
    )
    data.update(
        window_constraints(
            window, pub["window_sixbar"]["value"], pub["window_fourbar"]["value"],
            cfg["comparison"]["fourbar_window_band_deg"],
        )
    )
    findings = xr.Dataset(
        data,
        coords={
            **fit["coords"],
            **notes["coords"],
            **fitted_notes["coords"],
            "cell_class_name": (
                "cell_class_name", np.array(CLASSES, dtype=object), {"units": "1", "long_name": "Table 1 cell class"},
            ),
            "arm_to_crank": ("arm_to_crank", window.arm_to_crank.values, {"units": "1", "long_name": "four-bar L/R"}),
        },
    )
    findings = findings.merge(evidence).merge(counts_dataset(table))
    findings.attrs.update(crank_sense=sense, crank_sense_label=labels[sense], sense_picked_by_peaks=notes["picked"])
    findings.attrs.update(findings_attrs("Beat-up paper: comparison findings", "", ""))
    findings.attrs.update(offset_parameter=fit["offset_parameter"], offset_unit=fit["offset_unit"])
    return table, findings


