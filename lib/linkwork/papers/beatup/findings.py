"""The beat-up paper's comparison and findings: every published number beside ours, every Table 1 cell
classified with the evidence of which side is wrong, and what the printed weft windows constrain."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import pandas as pd
import xarray as xr

from ...pipeline.compare import compare_datasets, count_text, counts_dataset, expand_tables, findings_attrs, scalar
from ...units import DEG_PER_RAD
from .model import coarse_central_difference

CLASSES = ("within rounding", "parameter rounding", "marginal", "printed cell inconsistent", "inconclusive", "beyond parameter rounding")


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


def table1_evidence(ds: xr.Dataset, printed: dict[str, np.ndarray], tolerance: dict[str, float], step_deg: float) -> list[dict[str, Any]]:
    """Classify every printed Table 1 cell against our result, with evidence for the ones that differ.

    printed: column (our variable name) -> printed values on ds.crank_angle;
    tolerance: column -> half a unit of the printed last digit.  Classes:
    ``within rounding``; ``parameter rounding`` (within tolerance plus the
    worst-case effect of rounding the printed parameters); otherwise, for a
    derivative, the printed column it derives from is differenced at the paper's
    step and set beside the same difference of ours: if they agree within that
    column's rounding, the paper's own neighbouring cells agree with us and
    ``printed cell inconsistent``; if a neighbour is itself off, ``inconclusive``;
    a deviation smaller than what that check resolves is ``marginal``.
    Angles beyond both: ``beyond parameter rounding``.
    """
    h = np.radians(step_deg)
    rows = []
    for col, values in printed.items():
        ours = ds[col].values
        bound = ds[col + "_rounding_bound"].values
        tol = tolerance[col]
        if col in EVIDENCE_SOURCES:
            src, is_angle = EVIDENCE_SOURCES[col]
            src_values = np.radians(printed[src]) if is_angle else printed[src]
            printed_fd = coarse_central_difference(src_values, h, is_angle)
            our_fd = ds[col + "_coarse_fd"].values
            src_tol = np.radians(tolerance[src]) if is_angle else tolerance[src]
            fd_uncertainty = 2 * src_tol / (2 * h) * 2  # two rounded cells, with a factor 2 margin
        for i, angle in enumerate(ds.crank_angle.values):
            dev = values[i] - ours[i]
            row = {"column": col, "theta1": float(angle), "printed": float(values[i]), "ours": float(ours[i]), "deviation": float(dev),
                   "tolerance": tol, "rounding_bound": float(bound[i]), "printed_column_fd": np.nan, "our_coarse_fd": np.nan}
            if abs(dev) <= tol * (1 + 1e-9):
                row["class"] = "within rounding"
            elif abs(dev) <= tol + bound[i]:
                row["class"] = "parameter rounding"
            elif col in EVIDENCE_SOURCES:
                row["printed_column_fd"] = float(printed_fd[i])
                row["our_coarse_fd"] = float(our_fd[i])
                agree = abs(printed_fd[i] - our_fd[i]) <= fd_uncertainty
                if abs(dev) <= fd_uncertainty:
                    row["class"] = "marginal"
                else:
                    row["class"] = "printed cell inconsistent" if agree else "inconclusive"
            else:
                row["class"] = "beyond parameter rounding"
            rows.append(row)
    return rows


def evidence_dataset(rows: list[dict[str, Any]]) -> xr.Dataset:
    """The classified Table 1 cells as a Dataset along ``cell``."""
    df = pd.DataFrame(rows)
    units = {"theta1": "deg", "printed": "unit of the column", "ours": "unit of the column", "deviation": "unit of the column",
             "tolerance": "unit of the column", "rounding_bound": "unit of the column", "printed_column_fd": "unit of the column",
             "our_coarse_fd": "unit of the column"}
    long_names = {"theta1": "crank angle theta1", "printed": "printed value", "ours": "our value", "deviation": "printed - ours",
                  "tolerance": "half a unit of the printed last digit", "rounding_bound": "worst-case change from rounding the printed parameters",
                  "printed_column_fd": "15 deg central difference of the printed source column", "our_coarse_fd": "the same difference of ours"}
    data = {k: ("cell", df[k].to_numpy(dtype=float), {"units": units[k], "long_name": long_names[k]}) for k in units}
    for k in ("printed_column_fd", "our_coarse_fd"):
        data[k][2]["nan_meaning"] = "computed only for a cell that deviates beyond the parameters' rounding"
    data["column"] = ("cell", df["column"].to_numpy(dtype=object), {"units": "1", "long_name": "Table 1 column (our variable name)"})
    data["cell_class"] = ("cell", df["class"].to_numpy(dtype=object), {"units": "1", "long_name": "why the cell matches or not"})
    return xr.Dataset(data, coords={"cell": ("cell", np.arange(len(df)), {"units": "1", "long_name": "Table 1 cell"})})


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
        "fourbar_window_at_that_sw": ("arm_to_crank", w4_at, {"units": "deg", "long_name": "four-bar window at that S_w, per L/R"}),
        "fourbar_window_band": scalar(band, "deg", "band around the printed four-bar window (our reading)"),
        "arm_to_crank_in_band_min": scalar(ok.min() if ok.size else np.nan, "1", "smallest L/R giving the printed four-bar window within the band"),
        "arm_to_crank_in_band_max": scalar(ok.max() if ok.size else np.nan, "1", "largest L/R giving the printed four-bar window within the band"),
    }


def numerical_errors(published: Mapping[str, Any], sixbar: xr.Dataset) -> dict[str, tuple[float, str]]:
    """Our numerical error bar for every published number of the beat-up paper."""
    xtol = float(sixbar.attrs["root_xtol_rad"]) * DEG_PER_RAD
    half_grid = float(sixbar.crank_angle_fine[1] - sixbar.crank_angle_fine[0]) / 2
    rules = {
        "front_dead_centre": (xtol, "Brent's method on theta6' (x-tolerance)"),
        "swing": (1e-10, "theta6 at the dead centres, analytic"),
        "span_front_to_back": (2 * xtol, "two dead centres by Brent's method"),
        "span_front_to_back_forward_sense": (2 * xtol, "two dead centres by Brent's method"),
        "rate_peak_1": (half_grid, "located on the fine crank-angle grid (half a step)"),
        "rate_peak_2": (half_grid, "located on the fine crank-angle grid (half a step)"),
        "accel_peak": (half_grid, "located on the fine crank-angle grid (half a step)"),
    }
    out = {}
    for entry in [*published["quantities"], *expand_tables(published)]:
        if entry["id"] in rules:
            out[entry["id"]] = rules[entry["id"]]
        elif entry["id"].startswith("table1"):
            out[entry["id"]] = (1e-12, "analytic rates (the paper's corrected closed forms agree to 1e-12, tests)")
    return out


def compare(cfg: Mapping[str, Any], published: Mapping[str, Any], sixbar: xr.Dataset, window: xr.Dataset, uncertainty: xr.Dataset) -> tuple[pd.DataFrame, xr.Dataset]:
    """Comparison table and findings: Table 1 evidence, closed forms against Table 1, window constraints."""
    table = compare_datasets(published, [sixbar, window], errors={"": numerical_errors(published, sixbar)}, uncertainty=uncertainty)
    _, printed, tolerance = printed_table(published)
    evidence = evidence_dataset(table1_evidence(sixbar, printed, tolerance, cfg["grids"]["paper_step_deg"]))
    classes = [str(c) for c in evidence.cell_class.values]
    t1 = table.id.str.startswith("table1")
    pub = {q["id"]: q for q in published["quantities"]}
    data: dict[str, Any] = {
        "class_count": ("cell_class_name", [classes.count(c) for c in CLASSES], {"units": "1", "long_name": "Table 1 cells per class"}),
        "table1_matches": scalar((table[t1].verdict == "matches").sum(), "1", "Table 1 cells within half the printed digit"),
        "table1_total": scalar(t1.sum(), "1", "Table 1 cells compared"),
        "theta6_mean_offset": scalar(np.mean(printed["theta6"] - sixbar.theta6.values), "deg", "mean of printed theta6 - ours"),
    }
    for name in ("theta3_accel", "theta6_accel"):
        as_printed = np.abs(sixbar[f"{name}_eqs_printed"].values - printed[name]).max()
        corrected = np.abs(sixbar[f"{name}_eqs"].values - printed[name]).max()
        data[f"{name}_printed_eqs_vs_table"] = scalar(as_printed, "rad rad-2", f"max |printed eq. (7)/(13) - Table 1| of {name}")
        data[f"{name}_corrected_eqs_vs_table"] = scalar(corrected, "rad rad-2", f"max |corrected closed form - Table 1| of {name}")
    data["printed_eqs_worse_factor"] = scalar(
        min(data[f"{n}_printed_eqs_vs_table"][1] / data[f"{n}_corrected_eqs_vs_table"][1] for n in ("theta3_accel", "theta6_accel")),
        "1", "how many times further the printed (7)/(13) are from Table 1 than the corrected forms (smaller of the two)")
    data.update(window_constraints(window, pub["window_sixbar"]["value"], pub["window_fourbar"]["value"], cfg["comparison"]["fourbar_window_band_deg"]))
    findings = xr.Dataset(data, coords={
        "cell_class_name": ("cell_class_name", np.array(CLASSES, dtype=object), {"units": "1", "long_name": "Table 1 cell class"}),
        "arm_to_crank": ("arm_to_crank", window.arm_to_crank.values, {"units": "1", "long_name": "four-bar L/R"}),
    })
    findings = findings.merge(evidence).merge(counts_dataset(table))
    findings.attrs.update(findings_attrs("Beat-up paper: comparison findings", "", "", answer(table, findings, sixbar, pub)))
    return table, findings


def answer(table: pd.DataFrame, findings: xr.Dataset, sixbar: xr.Dataset, pub: Mapping[str, Any]) -> str:
    """Does the paper hold up? One sentence from the comparison and the Table 1 evidence."""
    classes = dict(zip(findings.cell_class_name.values, findings.class_count.values.astype(int)))
    return (
        f"Mostly. Its headline numbers: {count_text(table, '')}. The printed {pub['span_front_to_back']['value']:g}° from front to back dead "
        f"centre holds only for the crank turning towards decreasing θ1 (it is {float(sixbar.span_forward):.2f}° in the sense Table 1 is "
        f"tabulated). Table 1: {count_text(table, '', 'table cell')}; {classes['printed cell inconsistent']} printed cells are contradicted by "
        f"the paper's own neighbouring cells (errata), and eqs. (4), (7) and (13) carry typos that Table 1 does not follow. The weft-window "
        f"comparison cannot be reproduced: S_w and the 1511M dimensions are not given."
    )
