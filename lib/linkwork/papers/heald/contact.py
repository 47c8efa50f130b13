"""The heald linkage with real clearance joints at E and F: does a journal lose contact, and where (a question the
paper could not answer; every length is assumed and labelled in config ``heald.contact``, the masses are model A's).

The paper's chains assume that the pins E and F keep contact in their clearances (Vulfson's elastic link).  Here the
linkage is a description for the shared multibody engine: the cam lever O1C (driven, rocking with the dwell cam's
motion, ``heald.cam``), the level link CD, the rod DEF (model A's masses m_D, m_E6, m_F6 at D, E, F), the bell cranks
EO3G and FO4K (m_E7 at E and M_G at G; m_F8 at F and M_K at K; levers eta7, eta8), the rods GH and KL (m_H9, m_L10),
the heald frame (M_P) on the warp (a spring k_O with damping c_O, vertical) and a level guide link that keeps the frame
from swaying.  E and F are dry clearance joints (the rod's pins in the bell cranks' bushings, frictionless as the
chain; radial clearances Delta_E, Delta_F); gravity acts, the frame hanging on the bell cranks.

At each main-shaft speed the state is found by ``engines.states.settle`` (section: both journals' eccentricities and
their rates once a cycle); over the judged cycles a journal has lost contact when its penetration is not positive at
some stored point (free flight).  Beside it, model A's linear chain under the same cam drive: its peak joint forces
over a cycle (``dynamics.periodic_peaks``).  SI units inside; rev/min at the output boundary.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import xarray as xr

from ...configformat import labelled
from ...engines.multibody import assembly
from ...engines.multibody.linkage import Body, Clearance, Driver, Joint, Linkage, Spring
from ...engines.multibody.integrators import DIAG_FIXED, DIAG_PER_JOINT
from ...engines.multibody.simulate import Run
from ...engines.states import settle
from ...units import RAD_S_PER_RPM, STANDARD_GRAVITY
from .adapter import DRIVE_RATIO, drive_ratio, parameters
from .dynamics import cam_harmonics, harmonic_transfer, periodic_peaks

#: Model A's masses carried by each body of the linkage, at its named points.
LUMPED = {
    "rod": {"D": "m_D", "E": "m_E6", "F": "m_F6"},
    "crank7": {"E": "m_E7", "G": "M_G"},
    "crank8": {"F": "m_F8", "K": "M_K"},
}
#: Diagnostic columns of the clearance joints E and F (``model``: per joint e, delta, delta', dry normal force, ...).
PENETRATION = [DIAG_FIXED + DIAG_PER_JOINT * k + 1 for k in range(2)]
CONTACT_FORCE = [DIAG_FIXED + DIAG_PER_JOINT * k + 3 for k in range(2)]
#: The judged measures per cycle, in order.
MEASURES = ("flight_E", "flight_F", "gap_E", "gap_F", "force_E", "force_F")


def points(geom: Mapping[str, float], p: Mapping[str, float]) -> dict[str, tuple[float, float]]:
    """The linkage's points (m) at the cam lever's mean angle, E at the origin's left of the pivot O3 = (0, 0)."""
    a, y = geom["arm_E"], -geom["arm_E"]
    e, f = (0.0, y), (geom["E_to_F"], y)
    d = (-geom["D_to_E"], y)
    c = (d[0] - geom["conrod"], y)
    g, k = (p["eta7"] * a, 0.0), (geom["E_to_F"] + p["eta8"] * a, 0.0)
    h, lp = (g[0], geom["rod_GH"]), (k[0], geom["rod_GH"])
    centre = ((h[0] + lp[0]) / 2, h[1])
    s = (lp[0] + 0.1 * (lp[0] - h[0]), h[1])
    return {
        "O1": (c[0], y - geom["lever"]),
        "C": c,
        "D": d,
        "E": e,
        "F": f,
        "O3": (0.0, 0.0),
        "O4": (geom["E_to_F"], 0.0),
        "G": g,
        "K": k,
        "H": h,
        "L": lp,
        "P": centre,
        "S": s,
        "Q": (s[0] + geom["guide"], s[1]),
    }


def _lumped(
    name: str, pts: Mapping[str, tuple[float, float]], masses: Mapping[str, float], inertia: float = 0.0
) -> Body:
    """A body of point masses at named points (kg at m), plus ``inertia`` about its centre of mass (kg m^2)."""
    m = sum(masses.values())
    cx = sum(masses[k] * pts[k][0] for k in masses) / m
    cy = sum(masses[k] * pts[k][1] for k in masses) / m
    j = inertia + sum(masses[k] * ((pts[k][0] - cx) ** 2 + (pts[k][1] - cy) ** 2) for k in masses)
    return Body(name, m, j, {k: (x - cx, y - cy) for k, (x, y) in pts.items()})


def _bar(name: str, a: str, b: str, pts, mass: float) -> Body:
    """A uniform slender bar from point a to point b (mass kg)."""
    (xa, ya), (xb, yb) = pts[a], pts[b]
    cx, cy = (xa + xb) / 2, (ya + yb) / 2
    return Body(
        name, mass, mass * ((xb - xa) ** 2 + (yb - ya) ** 2) / 12, {a: (xa - cx, ya - cy), b: (xb - cx, yb - cy)}
    )


def pin(cfg: Mapping[str, Any], clearance: float) -> Clearance:
    """A dry frictionless clearance joint of radial clearance ``clearance`` (m), from ``contact.pin``."""
    pn = cfg["pin"]
    r = labelled(pn["journal_radius_m"])
    return Clearance(
        r, r + clearance, ("contact",), (pn["youngs_modulus_Pa"],) * 2, (pn["poisson"],) * 2,
        labelled(pn["restitution"]), "lankarani-nikravesh", "hertz-sphere",
        impact_velocity_floor=pn["impact_velocity_floor_m_s"],
    )


def drive_coefficients(cam: Mapping[str, Any], stroke: float) -> np.ndarray:
    """Complex amplitudes (m) of the displacement at D, x(theta) = Re sum_h c_h exp(j h theta): the dwell cam's series
    with its first harmonic scaled to ``stroke`` (m), as the chain's cam study."""
    c = cam_harmonics(labelled(cam["rise_fraction"]), cam["harmonics"], cam["samples"])
    return c * stroke / abs(c[0])


def linkage(
    cfg: Mapping[str, Any], cam: Mapping[str, Any], p: Mapping[str, float], drive_omega: float, clearances: bool = True
) -> Linkage:
    """The heald linkage driven at the drive frequency ``drive_omega`` (rad/s); E and F clearance joints (or ideal)."""
    geom, mk = cfg["geometry_m"], cfg["masses_kg"]
    pts = points(geom, p)
    lever = _lumped(
        "lever", {"O": pts["O1"], "C": pts["C"]}, {"O": mk["lever"] / 2, "C": mk["lever"] / 2}, 1e-3 * mk["lever"]
    )
    rod = _lumped("rod", {k: pts[k] for k in "DEF"}, {k: p[v] for k, v in LUMPED["rod"].items()})
    c7 = _lumped(
        "crank7", {"O": pts["O3"], "E": pts["E"], "G": pts["G"]}, {k: p[v] for k, v in LUMPED["crank7"].items()}
    )
    c8 = _lumped(
        "crank8", {"O": pts["O4"], "F": pts["F"], "K": pts["K"]}, {k: p[v] for k, v in LUMPED["crank8"].items()}
    )
    frame = _lumped("frame", {k: pts[k] for k in "HLPS"}, {"P": p["M_P"]}, labelled(cfg["frame_inertia_kg_m2"]))
    bodies = (lever, _bar("conrod", "C", "D", pts, mk["conrod"]), rod, c7, c8, _bar("rodGH", "G", "H", pts, p["m_H9"]),
              _bar("rodKL", "K", "L", pts, p["m_L10"]), frame, _bar("guide", "S", "Q", pts, mk["guide"]))
    pe, pf = (pin(cfg, p["clearance_E"]), pin(cfg, p["clearance_F"])) if clearances else (None, None)
    joints = (Joint("O1", ("lever", "O"), ("ground", "O1")), Joint("C", ("lever", "C"), ("conrod", "C")),
              Joint("D", ("conrod", "D"), ("rod", "D")), Joint("E", ("rod", "E"), ("crank7", "E"), pe),
              Joint("F", ("rod", "F"), ("crank8", "F"), pf), Joint("O3", ("crank7", "O"), ("ground", "O3")),
              Joint("O4", ("crank8", "O"), ("ground", "O4")), Joint("G", ("crank7", "G"), ("rodGH", "G")),
              Joint("H", ("rodGH", "H"), ("frame", "H")), Joint("K", ("crank8", "K"), ("rodKL", "K")),
              Joint("L", ("rodKL", "L"), ("frame", "L")), Joint("S", ("frame", "S"), ("guide", "S")),
              Joint("Q", ("guide", "Q"), ("ground", "Q")))
    # the lever turns by the displacement at D over its length; D moves towards +x as the lever turns clockwise
    c = drive_coefficients(cam, p["stroke_D"]) / cfg["geometry_m"]["lever"]
    driver = Driver(
        "lever", drive_omega, 0.0, tuple(-c.real), tuple(c.imag), rocking=True
    )  # angles from the drawn configuration
    warp = Spring("warp", ("frame", "P"), pts["P"], (0.0, p["k_O"]), (0.0, p["c_O"]))
    ground = {k: pts[k] for k in ("O1", "O3", "O4", "Q")}
    return Linkage(bodies, ground, joints, driver, "frame", springs=(warp,))


def case_parameters(
    p: Mapping[str, float], ranges: Mapping[str, tuple[float, float]], case: Mapping[str, str]
) -> dict[str, float]:
    """The parameters of a named case: each key it names at the low or high end of its assumed range."""
    return {**p, **{k: float(ranges[k][0 if end == "low" else 1]) for k, end in case.items()}}


def reversal_loads(p: Mapping[str, float], cam: Mapping[str, Any]) -> tuple[float, float]:
    """Quasi-static check (closed form, small rotations, the warp unstretched at the cam's mean position): (the warp's
    largest pull on the frame k_O eta7 max|x_D|, the weight the bell cranks hold up at G and K: the frame, the rods GH
    and KL, the masses at G and K), N.  When the pull exceeds the weight, the load at E and F along the drive changes
    sign within a cycle at any speed, so the journals must cross their clearances."""
    c = drive_coefficients(cam, p["stroke_D"])
    theta = 2 * np.pi * np.arange(cam["samples"]) / cam["samples"]
    x = np.real(np.exp(1j * np.outer(theta, np.arange(1, c.size + 1))) @ c)
    weight = STANDARD_GRAVITY * (p["M_P"] + p["m_H9"] + p["m_L10"] + p["M_G"] + p["M_K"])
    return float(p["k_O"] * p["eta7"] * np.abs(x).max()), float(weight)


def reversal_margin(p: Mapping[str, float], cam: Mapping[str, Any]) -> float:
    """The warp's largest pull over the weight held up (``reversal_loads``); above 1 the load reverses at any speed."""
    pull, weight = reversal_loads(p, cam)
    return pull / weight


def rigid_reactions(cfg: Mapping[str, Any], cam: Mapping[str, Any], p: Mapping[str, float], drive_omega: float,
                    samples: int) -> np.ndarray:
    """The rigid linkage's (E and F closed) reactions at E and F over one drive cycle at ``drive_omega`` (rad/s):
    (samples, joint, component) in N, ground frame, the force each bell crank exerts on the rod DEF."""
    lk = linkage(cfg, cam, p, drive_omega, clearances=False)
    out = assembly.inverse_dynamics(lk, np.arange(samples) * lk.driver.period / samples, cfg["gravity"])
    return np.stack([out["reaction_E"], out["reaction_F"]], axis=1)


def reaction_turn(reactions: np.ndarray) -> np.ndarray:
    """How far the reaction's direction turns over the cycle (per joint, deg): the range of its unwrapped angle."""
    angle = np.unwrap(np.arctan2(reactions[..., 1], reactions[..., 0]), axis=0)
    return np.degrees(np.ptp(angle, axis=0))


def rigid_reversal(
    cfg: Mapping[str, Any], cam: Mapping[str, Any], p: Mapping[str, float], ratio: float, rpm: np.ndarray,
    samples: int,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Per joint (E, F): the lowest main-shaft speed (rev/min, in ``rpm``'s span) at which the rigid reaction's
    component along the rod DEF (horizontal) changes sign within a cycle, its smallest magnitude over that cycle
    there (N: the sideways component it turns past), and whether it reverses quasi-statically (already at the lowest
    speed: then no speed is given).  The speed from a scan of ``rpm`` refined by Brent's method to 1e-3 rev/min."""
    from scipy.optimize import brentq

    def along(shaft_rpm: float) -> np.ndarray:
        r = rigid_reactions(cfg, cam, p, ratio * shaft_rpm * RAD_S_PER_RPM, samples)
        return r

    low = along(float(rpm[0]))
    sign = np.sign(low[:, :, 0].mean(axis=0))  # the load's sense along the rod at the lowest speed

    def margin(shaft_rpm: float, j: int) -> float:
        return float((sign[j] * along(shaft_rpm)[:, j, 0]).min())

    speed, sideways = np.full(2, np.nan), np.full(2, np.nan)
    quasi_static = np.array([margin(float(rpm[0]), j) <= 0.0 for j in range(2)])
    grid = np.geomspace(float(rpm[0]), float(rpm[-1]), 61)
    for j in range(2):
        if quasi_static[j]:
            continue
        values = [margin(float(w), j) for w in grid]
        cross = next((k for k in range(1, grid.size) if values[k] <= 0.0), None)
        if cross is None:
            continue
        speed[j] = brentq(margin, grid[cross - 1], grid[cross], args=(j,), xtol=1e-3)
        sideways[j] = float(np.hypot(*along(speed[j])[:, j].T).min())
    return speed, sideways, quasi_static


class _Cycles:
    """Runs the scene cycle by cycle for ``engines.states.settle``; keeps each cycle's contact forces."""

    def __init__(self, lk: Linkage, gravity: bool, integrator, per: int, y0=None, memory=None):
        self.lk, self.per = lk, per
        self.run = Run(lk, gravity, integrator, y0=y0, memory=memory)
        cs = np.array([j.clearance.clearance for j in lk.clearance_joints])
        w = abs(lk.driver.speed)
        self.scale = np.stack([cs, cs, w * cs, w * cs], axis=-1)
        self.memories, self.forces = [], []

    def step(self, n: int):
        pts, measures = [], []
        for _ in range(n):
            self.memories.append(self.run.memory())
            pts.append((assembly.journal_offsets(self.lk, self.run.y) / self.scale).ravel())
            t = self.run.t + np.arange(self.per + 1) * self.lk.driver.period / self.per
            _, diags = self.run.advance(t)
            pen = diags[:, PENETRATION]  # penetration at E and F (m)
            force = diags[:, CONTACT_FORCE]  # dry contact force at E and F (N)
            self.forces.append(force)
            measures.append([*np.mean(pen <= 0.0, axis=0), *np.maximum(0.0, -pen.min(axis=0)), *force.max(axis=0)])
        return np.array(pts), np.array(measures)


def _settled(lk: Linkage, cfg, per: int) -> dict[str, Any]:
    """The settled state at one speed: status, judged measures' means and extremes, numerical error."""
    st = cfg["states"]
    runner = _Cycles(lk, cfg["gravity"], cfg["integrator"], per, y0=assembly.start_state(lk))
    found = settle(
        runner.step, st["chunk_cycles"], st["max_cycles"], st["max_period"], st["section_tolerance"], st["periods"],
        st["min_cycles"], 0.95, rows=(4, 5),
    )
    first, stop = found["window"]
    m = found["measures"][first:stop]
    n_check = min(st["check_cycles"], stop - first)
    check = _Cycles(lk, cfg["gravity"], cfg["check_integrator"], per, memory=runner.memories[first])
    _, cm = check.step(n_check)
    return {
        "status": found["status"],
        "period": found["period"],
        "transient": found["transient"],
        "cycles": len(runner.forces),
        "mean": m.mean(axis=0),
        "max": m.max(axis=0),
        "numerical": np.abs(cm.mean(axis=0) - m[:n_check].mean(axis=0)),
        "force": np.array(runner.forces[max(first, stop - 1)]),
    }


def study(section: Mapping[str, Any]) -> xr.Dataset:
    """Rule study: the heald linkage with clearance joints at E and F over the speeds, per named case."""
    cfg, cam = section["contact"], section["cam"]
    base = parameters(section)
    ranges = {k: tuple(v["range"]) for k, v in section["parameters"].items() if isinstance(v, Mapping) and "range" in v}
    ratio = drive_ratio(section)
    rpm = np.asarray(cfg["speeds_rpm"], dtype=float)
    w = rpm * RAD_S_PER_RPM
    per = int(cfg["points_per_cycle"])
    names = list(cfg["cases"])
    shape = (len(names), rpm.size)
    out = {k: np.empty(shape) for k in ("flight_E", "flight_F", "gap_E", "gap_F", "force_E", "force_F", "force_E_mean",
                                       "force_F_mean", "force_numerical", "chain_E", "chain_F")}
    status, periods, cycles = np.empty(shape, dtype=object), np.empty(shape, dtype=int), np.empty(shape, dtype=int)
    margins, forces = [], np.empty((*shape, per + 1, 2))
    reversal, turn = [], np.empty((*shape, 2))
    for i, name in enumerate(names):
        p = case_parameters(base, ranges, cfg["cases"][name])
        margins.append((*reversal_loads(p, cam), p["eta7"], p["eta8"]))
        reversal.append(rigid_reversal(cfg, cam, p, ratio, rpm, per))
        turn[i] = [reaction_turn(rigid_reactions(cfg, cam, p, ratio * wj, per)) for wj in w]
        coefficients = drive_coefficients(cam, p["stroke_D"])
        chain_e, chain_f = periodic_peaks(harmonic_transfer("A", p, w, cam["harmonics"]), coefficients, cam["samples"])
        out["chain_E"][i], out["chain_F"][i] = chain_e, chain_f
        for j, wj in enumerate(w):
            s = _settled(linkage(cfg, cam, p, ratio * wj), cfg, per)
            status[i, j], periods[i, j], cycles[i, j] = s["status"], s["period"], s["cycles"]
            for k, key in enumerate(MEASURES):  # the largest over the judged cycles
                out[key][i, j] = s["max"][k]
            out["force_E_mean"][i, j], out["force_F_mean"][i, j] = s["mean"][4], s["mean"][5]
            out["force_numerical"][i, j] = s["numerical"][4:6].max()
            forces[i, j] = s["force"]
            print(
                f"heald_contact: {name} at {rpm[j]:g} rev/min: {s['status']} (period {s['period']}, {s['cycles']}"
                f" cycles); free flight E {s['max'][0]:.3f}, F {s['max'][1]:.3f} of a cycle",
                flush=True,
            )
    ds = _dataset(names, rpm, out, status, periods, cycles, np.array(margins), forces, ratio)
    return ds.merge(_rigid_dataset(reversal, turn, ratio, rpm)).assign_attrs(ds.attrs)


def first_loss(rpm: np.ndarray, lost: np.ndarray) -> tuple[float, float]:
    """(highest speed below the first with contact lost, the first such speed), rev/min; (NaN, first) if contact is
    lost at the lowest speed, (last, NaN) if never."""
    idx = np.flatnonzero(lost)
    if idx.size == 0:
        return float(rpm[-1]), float("nan")
    k = int(idx[0])
    return (float(rpm[k - 1]) if k > 0 else float("nan")), float(rpm[k])


def _rigid_dataset(reversal, turn: np.ndarray, ratio: float, rpm: np.ndarray) -> xr.Dataset:
    """The rigid linkage's reactions at E and F: where their component along the rod first reverses, past what
    sideways force, and how far they turn over a cycle at each simulated speed."""
    speed, sideways, quasi = (np.array(x) for x in zip(*reversal, strict=True))  # case, joint
    scale = np.array([ratio / r for r in DRIVE_RATIO.values()])
    first, last = (  # per case (NaN: no reversal speed)
        np.array([f(row[np.isfinite(row)]) if np.isfinite(row).any() else np.nan for row in speed])
        for f in (np.min, np.max)
    )
    below = np.array([np.where(rpm < f, turn[i].max(axis=-1), -np.inf).max() for i, f in enumerate(first)])
    above = np.array([np.where(rpm > f, turn[i].max(axis=-1), -np.inf).max() for i, f in enumerate(last)])
    return xr.Dataset(
        {
            "rigid_reversal_rpm": (
                ("case", "joint", "drive"), speed[..., None] * scale,
                {
                    "units": "rev/min",
                    "long_name": (
                        "lowest shaft speed at which the rigid linkage's reaction (E and F closed) changes the sense of"
                        " its component along the rod DEF within a cycle, per drive scenario"
                    ),
                    "nan_meaning": "it reverses already at the lowest speed (rigid_reverses_quasi_statically), or not"
                    " up to the highest speed simulated",
                },
            ),
            "rigid_sideways_at_reversal": (
                ("case", "joint"), sideways,
                {
                    "units": "N",
                    "long_name": (
                        "smallest magnitude of the rigid reaction over the cycle at its reversal speed: the sideways"
                        " force it turns past"
                    ),
                    "nan_meaning": "no reversal speed (rigid_reversal_rpm)",
                },
            ),
            "rigid_reverses_quasi_statically": (
                ("case", "joint"), quasi.astype(int),
                {
                    "units": "1",
                    "long_name": "1 if the rigid reaction along the rod reverses already at the lowest speed",
                },
            ),
            "rigid_reaction_turn": (
                ("case", "speed", "joint"), turn,
                {"units": "deg", "long_name": "how far the rigid reaction's direction turns over a cycle"},
            ),
            "rigid_turn_range": (
                ("case", "bound"), np.stack([turn.min(axis=(1, 2)), turn.max(axis=(1, 2))], axis=-1),
                {
                    "units": "deg",
                    "long_name": "least and most the rigid reaction turns per cycle, over speeds and joints",
                },
            ),
            "rigid_turn_below_reversal": (
                "case", np.where(np.isfinite(below), below, np.nan),
                {
                    "units": "deg",
                    "long_name": "most the rigid reaction turns per cycle at the speeds simulated below its reversal",
                    "nan_meaning": "no reversal speed, or none simulated below it",
                },
            ),
            "rigid_turn_above_reversal": (
                "case", np.where(np.isfinite(above), above, np.nan),
                {
                    "units": "deg",
                    "long_name": "most the rigid reaction turns per cycle at the speeds simulated above its reversal",
                    "nan_meaning": "no reversal speed, or none simulated above it",
                },
            ),
        },
        coords={"bound": ("bound", ["least", "most"], {"units": "1", "long_name": "which bound"})},
    )


def _dataset(names, rpm, out, status, periods, cycles, margins, forces, ratio) -> xr.Dataset:
    dims = ("case", "speed")
    lost = (out["flight_E"] > 0.0) | (out["flight_F"] > 0.0)
    # the linkage sees only the drive frequency: at another drive scenario the same states fall at shaft speeds scaled
    # by the ratio of the two drive ratios
    scale = np.array([ratio / r for r in DRIVE_RATIO.values()])
    brackets = np.array([first_loss(rpm, row) for row in lost])[:, :, None] * scale
    pull, weight, eta7, eta8 = np.array(margins).T
    units = {
        "flight": (
            "1",
            "largest fraction of a judged cycle in which the journal at {j} is in free flight (no contact)",
        ),
        "gap": ("m", "largest separation of the journal at {j} from its bearing's wall over the judged cycles"),
        "force": ("N", "largest dry contact force at {j} over the judged cycles"),
    }
    data = {}
    for key in ("flight_E", "flight_F", "gap_E", "gap_F", "force_E", "force_F"):
        kind, joint = key.split("_")
        u, text = units[kind]
        data[key] = (dims, out[key], {"units": u, "long_name": text.format(j=joint)})
    data.update(
        {
            "force_E_mean": (
                dims, out["force_E_mean"],
                {"units": "N", "long_name": "mean over the judged cycles of each cycle's largest contact force at E"},
            ),
            "force_F_mean": (
                dims, out["force_F_mean"],
                {"units": "N", "long_name": "mean over the judged cycles of each cycle's largest contact force at F"},
            ),
            "force_numerical_error": (
                dims,
                out["force_numerical"],
                {
                    "units": "N",
                    "long_name": (
                        "change of the mean largest contact force (E or F, the larger) when the first judged cycles are"
                        " rerun at the check integrator"
                    ),
                },
            ),
            "chain_E": (
                dims,
                out["chain_E"],
                {
                    "units": "N",
                    "long_name": (
                        "model A's linear chain: peak |Q_E| over a cycle under the same cam drive (Vulfson's joints,"
                        " contact held)"
                    ),
                },
            ),
            "chain_F": (
                dims, out["chain_F"],
                {"units": "N", "long_name": "model A's linear chain: peak |Q_F| over a cycle under the same cam drive"},
            ),
            "contact_lost": (
                dims,
                lost,
                {
                    "units": "1",
                    "long_name": "a journal (E or F) in free flight at some stored point of the judged cycles",
                },
            ),
            "state_status": (dims, status.astype(str), {"units": "1", "long_name": "the settled state's status"}),
            "state_period": (
                dims, periods, {"units": "1", "long_name": "period of the settled state in cycles (0: not periodic)"},
            ),
            "cycles_run": (dims, cycles, {"units": "1", "long_name": "drive cycles integrated"}),
            "warp_pull": (
                "case",
                pull,
                {
                    "units": "N",
                    "long_name": (
                        "the warp's largest pull on the frame, k_O eta7 max|x_D| (closed form, quasi-static, the warp"
                        " unstretched at the cam's mean position)"
                    ),
                },
            ),
            "weight_held": (
                "case",
                weight,
                {
                    "units": "N",
                    "long_name": (
                        "the weight the bell cranks hold up at G and K (the frame, rods GH and KL, the masses at G"
                        " and K)"
                    ),
                },
            ),
            "reversal_margin": (
                "case",
                pull / weight,
                {
                    "units": "1",
                    "long_name": (
                        "warp's largest pull on the frame over the weight held up (above 1 the load at E and F reverses"
                        " at any speed)"
                    ),
                },
            ),
            "weight_share": (
                ("case", "joint"),
                np.stack([weight * eta7, weight * eta8], axis=-1) / 2,
                {
                    "units": "N",
                    "long_name": (
                        "the held weight's static share at each joint along the drive (weight times its lever ratio"
                        " over two)"
                    ),
                },
            ),
            "held_up_to_rpm": (
                ("case", "drive"),
                brackets[:, 0],
                {
                    "units": "rev/min",
                    "long_name": "highest shaft speed simulated below the first with contact lost, per drive scenario",
                    "nan_meaning": "contact is lost already at the lowest speed simulated",
                },
            ),
            "first_lost_rpm": (
                ("case", "drive"),
                brackets[:, 1],
                {
                    "units": "rev/min",
                    "long_name": "lowest shaft speed simulated with contact lost, per drive scenario",
                    "nan_meaning": "contact holds at every speed simulated",
                },
            ),
            "contact_force": (
                ("case", "speed", "cycle_point", "joint"), forces,
                {"units": "N", "long_name": "dry contact force over the last judged cycle"},
            ),
        }
    )
    coords = {
        "case": ("case", names, {"units": "1", "long_name": "named case of the assumed parameters"}),
        "speed": ("speed", rpm, {"units": "rev/min", "long_name": "main-shaft speed"}),
        "cycle_point": (
            "cycle_point", np.linspace(0.0, 360.0, forces.shape[2]),
            {"units": "deg", "long_name": "drive angle over a cycle"},
        ),
        "joint": ("joint", ["E", "F"], {"units": "1", "long_name": "clearance joint"}),
        "drive": (
            "drive", list(DRIVE_RATIO),
            {"units": "1", "long_name": "drive-frequency scenario (heald.drive.frequency's choices)"},
        ),
    }
    return xr.Dataset(
        data, coords=coords,
        attrs={"drive_ratio": float(ratio), "title": "Heald linkage with clearance joints at E and F"},
    )
