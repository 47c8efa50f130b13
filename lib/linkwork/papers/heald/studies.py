"""The heald paper's studies: chain responses of models A and B with the claims' measures and their sweeps."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import xarray as xr

from ...engines.chains import resonances, solve_network
from ...units import RAD_S_PER_RPM
from .adapter import DRIVE_RATIO, amplitude, omega_grid, parameters, sweep_values
from .dynamics import (
    cam_harmonics, damped_modes, harmonic_transfer, joint_forces, kinetostatic_reactions, periodic_peaks,
    self_consistent_reactions,
)
from .model import (
    JOINTS, build, drive_frequency, eq2_mobility, eq2_node_mass_difference, joint_stiffness, model_b,
    model_b_parameters, node_mass,
)

def growth_fraction(model: str, p: Mapping[str, float], omega: np.ndarray, amplitude: float) -> float:
    """Fraction of the grid intervals over which |Q_E| and |Q_F| both grow (elastic joints)."""
    _, q_e, q_f, _ = joint_forces(model, p, "elastic", omega, amplitude)
    return float(np.mean((np.diff(np.abs(q_e)) > 0) & (np.diff(np.abs(q_f)) > 0)))


def claim_measures(model: str, p: Mapping[str, float], omega: np.ndarray, amplitude: float) -> dict[str, float]:
    """The numbers the paper's claims are judged on, for one model and parameter set (elastic joints)."""
    _, q_e, q_f, _ = joint_forces(model, p, "elastic", omega, amplitude)
    ratio = np.abs(q_e) / np.abs(q_f)
    growth = np.mean((np.diff(np.abs(q_e)) > 0) & (np.diff(np.abs(q_f)) > 0))
    return {"ratio_EF_min": float(ratio.min()), "ratio_EF_max": float(ratio.max()), "growth_fraction": float(growth),
            "first_resonance": lowest_resonance(model, p)}


def lowest_resonance(model: str, p: Mapping[str, float]) -> float:
    """The main-shaft frequency (rad/s) at which the drive meets the lowest resonance under the kinematic drive: the
    chain's lowest velocity resonance, K = 0, where the drive force peaks, over ``drive_ratio``.  A force resonance (K
    -> infinity) is an antiresonance of a velocity-driven chain, where the drive force dips, and is not counted."""
    vel, _ = resonances(build(model, p, "elastic"))
    return float(min([x for x in vel if x > 0], default=np.nan)) / p.get("drive_ratio", 1.0)


MEASURES = {
    "ratio_EF_min": ("1", "min over the band of |Q_E| / |Q_F| (elastic joints)"),
    "ratio_EF_max": ("1", "max over the band of |Q_E| / |Q_F| (elastic joints)"),
    "growth_fraction": ("1", "fraction of the band where |Q_E| and |Q_F| both grow with frequency"),
    "first_resonance": (
        "rad s-1",
        (
            "main-shaft frequency at which the drive meets the lowest undamped resonance (velocity resonance, K = 0),"
            " elastic joints"
        ),
    ),
}


def claims(cfg: Mapping[str, Any], refinement: bool = True) -> xr.Dataset:
    """The numbers the paper's claims are judged on, per chain model, at the config's parameters; with
    ``refinement`` also how much halving the frequency grid changes the growth measure (its error bar)."""
    p, amp, w = parameters(cfg), amplitude(cfg), omega_grid(cfg["speeds"])
    models = list(cfg["models"])
    measures = {m: claim_measures(m, p, w, amp) for m in models}
    data = {
        k: ("model", [measures[m][k] for m in models], {"units": unit, "long_name": text})
        for k, (unit, text) in MEASURES.items()
    }
    data["first_resonance_rpm"] = (
        "model", [measures[m]["first_resonance"] / RAD_S_PER_RPM for m in models],
        {"units": "min-1", "long_name": "shaft speed at which the drive meets the lowest undamped resonance"},
    )
    if refinement:
        fine = np.linspace(
            w[0], w[-1], 2 * w.size - 1
        )  # every interval halved: how much the grid decides the growth measure
        data["growth_fraction_refinement"] = (
            "model", [abs(growth_fraction(m, p, fine, amp) - measures[m]["growth_fraction"]) for m in models],
            {"units": "1", "long_name": "change of the growth fraction when the frequency grid is halved"},
        )
    return xr.Dataset(
        data,
        coords={
            "model": (
                "model", np.array(models, dtype=object),
                {"units": "1", "long_name": "A: physical linkage; B: chain of the form of eq. (2)"},
            )
        },
    )


def interlaced(zeros: np.ndarray, poles: np.ndarray, rtol: float = 1e-9) -> bool:
    """True if the sorted zeros and poles alternate, starting with a zero (w09 <= w07 <= w010 <= w08 <= w011);
    equality within ``rtol`` is allowed: two equal branches make a pole coincide with their zeros (it cancels)."""
    z, p = np.sort(np.asarray(zeros, dtype=float)), np.sort(np.asarray(poles, dtype=float))
    if z.size != p.size + 1:
        return False
    tol = rtol * max(float(np.max(z, initial=0.0)), 1.0)
    return bool(all(z[i] <= p[i] + tol and p[i] <= z[i + 1] + tol for i in range(p.size)))


def chain(cfg: Mapping[str, Any]) -> xr.Dataset:
    """Q, Q_E, Q_F with ideal and elastic joints for both models, resonances, claim measures, sweeps.  In named
    steps: the chains' responses over the band, model B against eq. (2), the claims, the sweeps of the parameter
    ranges, then the drive scenarios, damping, kinetostatics and the cam study."""
    p = parameters(cfg)
    amp = amplitude(cfg)
    w = omega_grid(cfg["speeds"])
    models = list(cfg["models"])
    data, coords = _responses(p, models, w, amp)
    data.update(_eq2_check(p, w))
    data.update(claims(cfg).data_vars)
    sweep_data, sweep_coords = _sweeps(cfg["sweeps"], p, models, w, amp)
    data.update(sweep_data)
    coords.update(sweep_coords)
    data.update(drive_scenarios(p, models, w, amp))
    data.update(damping(p, models))
    data.update(kinetostatics(p, models, w, amp))
    cam_data, cam_coords = cam_study(cfg, p, models, w, amp)
    data.update(cam_data)
    coords.update(cam_coords)
    ds = xr.Dataset(data, coords=coords)
    ds.attrs.update(title="Heald motion as mechanical chains")  # the parameters' reasons: results/heald/assumptions.nc
    ds.attrs.update(displacement_amplitude_m=amp, frequency_points=int(w.size))
    return ds


#: Resonances kept per chain (the mode axis).
N_MODES = 4


def _responses(p: Mapping[str, float], models: list[str], w: np.ndarray, amp: float) -> tuple[dict, dict]:
    """Each model's and joint variant's forces at D, E and F over the band (drive frequency ``w``, rad/s, at the
    displacement amplitude ``amp``, m), input mobility, undamped resonances and joint stiffnesses; with the
    coordinates they need."""
    shape = (len(models), len(JOINTS), w.size)
    q_in, q_e, q_f = (np.empty(shape) for _ in range(3))
    mobility = np.empty(shape, dtype=complex)
    vel_res = np.full((len(models), len(JOINTS), N_MODES), np.nan)
    force_res = np.full((len(models), len(JOINTS), N_MODES), np.nan)
    for i, model in enumerate(models):
        for j, variant in enumerate(JOINTS):
            qi, qe, qf, _ = joint_forces(model, p, variant, w, amp)
            q_in[i, j], q_e[i, j], q_f[i, j] = np.abs(qi), np.abs(qe), np.abs(qf)
            mobility[i, j] = 1j * drive_frequency(p, w) * amp / qi
            vr, fr = resonances(build(model, p, variant))
            vel_res[i, j, : min(N_MODES, vr.size)] = vr[:N_MODES]
            force_res[i, j, : min(N_MODES, fr.size)] = fr[:N_MODES]
    coords = {
        "model": ("model", np.array(models, dtype=object),
                  {"units": "1", "long_name": "A: physical linkage; B: chain of the form of eq. (2)"}),
        "joints": ("joints", np.array(JOINTS, dtype=object),
                   {"units": "1", "long_name": "ideal: no clearance (pin stiffness k_n); elastic: Vulfson clearance "
                                               "model"}),
        "omega": ("omega", w, {"units": "rad s-1", "long_name": "main-shaft circular frequency"}),
        "shaft_speed": ("omega", w / RAD_S_PER_RPM, {"units": "min-1", "long_name": "main-shaft speed"}),
        "mode": ("mode", np.arange(N_MODES), {"units": "1", "long_name": "resonance index (ascending)"}),
    }
    dims, modes = ("model", "joints", "omega"), ("model", "joints", "mode")
    fewer = "the chain has fewer resonances than the mode axis holds"

    def array(values, dims_, units, long_name, **extra):
        return xr.DataArray(values, dims=dims_, attrs={"units": units, "long_name": long_name, **extra})

    both = np.concatenate([q_e, q_f], axis=2)  # (model, joints, E then F over the band)
    data = {
        "Q": array(q_in, dims, "N", "|Q|, force at the driven joint D"),
        "Q_E": array(q_e, dims, "N", "|Q_E|, force in joint E"),
        "Q_F": array(q_f, dims, "N", "|Q_F|, force in joint F"),
        "K_abs": array(np.abs(mobility), dims, "m N-1 s-1", "|K|, input mobility V/Q"),
        "K_phase": array(np.angle(mobility), dims, "rad", "phase of the input mobility"),
        "velocity_resonance": array(vel_res, modes, "rad s-1", "velocity resonances (K = 0) of the chain, undamped, "
                                    "as drive frequencies", nan_meaning=fewer),
        "force_resonance": array(force_res, modes, "rad s-1", "force resonances (K -> infinity) of the chain, "
                                 "undamped, as drive frequencies", nan_meaning=fewer),
        "k_E": array([joint_stiffness(p, "E", v) for v in JOINTS], "joints", "N m-1",
                     "tangential stiffness of joint E"),
        "k_F": array([joint_stiffness(p, "F", v) for v in JOINTS], "joints", "N m-1",
                     "tangential stiffness of joint F"),
        "ideal_elastic_difference": array(np.max(np.abs(both[:, 0] - both[:, 1]) / both[:, 1], axis=1), "model",
                                          "1", "max relative difference of |Q_E|, |Q_F| between ideal and elastic "
                                          "joints over the band"),
    }
    return data, coords


def _eq2_check(p: Mapping[str, float], w: np.ndarray) -> dict[str, xr.DataArray]:
    """Model B against eq. (2), undamped, over the drive frequencies of the band (eq. (2) is a property of the
    chain): the network's mobility against the printed form, with and without the rod's masses on the driven node,
    and eq. (2)'s resonances."""
    undamped = {**p, "c_joint": 0.0, "c_O": 0.0}
    wd = drive_frequency(p, w)
    k_eq2, num_w, den_w = eq2_mobility(undamped, wd)
    r = solve_network(build("B", undamped, "elastic"), wd, 1.0)
    node_diff, node_at = eq2_node_mass_difference(p, wd)
    _, anti = resonances(model_b(undamped, "elastic", with_node_mass=True))

    def scalar(value, units, long_name):
        return xr.DataArray(value, attrs={"units": units, "long_name": long_name})

    return {
        "eq2_relative_difference": scalar(float(np.max(np.abs(1 / r.input_force - k_eq2) / np.abs(k_eq2))), "1",
                                          "max |K_network - K_eq2| / |K_eq2|, model B, undamped"),
        "eq2_node_mass_difference": scalar(node_diff, "1", "max over the band of |K_chain - K_eq2| / |K_eq2| with "
                                           "the rod's masses m_D + m_E6 + m_F6 on the driven node (undamped, frequency "
                                           "grid)"),
        "eq2_node_mass_difference_at": scalar(node_at, "rad s-1", "drive frequency at which that difference peaks on "
                                              "the grid"),
        "eq2_node_mass": scalar(node_mass(p), "kg", "mass on the driven node, m_D + m_E6 + m_F6"),
        "eq2_node_mass_antiresonance": scalar(float(anti[0]), "rad s-1", "lowest antiresonance (K -> infinity) of "
                                              "eq. (2)'s chain with the node mass; the relative difference is "
                                              "unbounded there"),
        "eq2_numerator_frequencies": xr.DataArray(num_w, dims="numerator_factor", attrs={
            "units": "rad s-1", "long_name": "w09, w010, w011 of eq. (2) (velocity resonances)"}),
        "eq2_denominator_frequencies": xr.DataArray(den_w, dims="denominator_factor", attrs={
            "units": "rad s-1", "long_name": "w07, w08 of eq. (2) (force resonances)"}),
        "eq2_interlaced": scalar(int(interlaced(num_w, den_w)), "1", "1 if zeros and poles of eq. (2) interlace, "
                                 "starting with a zero"),
    }


def _sweep_definitions(p: Mapping[str, float]) -> dict[str, tuple]:
    """Per sweep of ``heald.sweeps``: its dimension, unit, words and the parameters at a swept value."""
    return {
        "reaction_ratio": ("reaction_ratio", "1", "|R_E| / |R_F| (|R_F| fixed)",
                           lambda x: {**p, "reaction_E": x * p["reaction_F"]}),
        "clearance": ("clearance", "m", "clearance Delta of both joints",
                      lambda x: {**p, "clearance_E": x, "clearance_F": x}),
        "heald_mass": ("heald_mass", "kg", "heald-frame mass M_P", lambda x: {**p, "M_P": x}),
        "warp_stiffness": ("warp_stiffness", "N m-1", "warp stiffness k_O", lambda x: {**p, "k_O": x}),
    }


def _sweeps(sweeps: Mapping[str, Any], p: Mapping[str, float], models: list[str], w: np.ndarray,
            amp: float) -> tuple[dict, dict]:
    """The parameter ranges that support each claim: every claim measure along each sweep, per model, and whether
    the joint forces at E and F move at all along it (model B under a velocity drive: not with the warp branch)."""
    data, coords = {}, {}
    for key, (dim, unit, long_name, make) in _sweep_definitions(p).items():
        values = sweep_values(sweeps[key])
        coords[dim] = (dim, values, {"units": unit, "long_name": long_name})
        table = {k: np.empty((len(models), values.size)) for k in MEASURES}
        for i, m in enumerate(models):
            for j, x in enumerate(values):
                for k, v in claim_measures(m, make(x), w, amp).items():
                    table[k][i, j] = v
        for k, arr in table.items():
            measure_unit, text = MEASURES[k]
            data[f"{k}_vs_{key}"] = xr.DataArray(arr, dims=("model", dim),
                                                 attrs={"units": measure_unit, "long_name": f"{text} vs {long_name}"})
        change = []
        for m in models:
            ends = [joint_forces(m, make(x), "elastic", w, amp)[1:3] for x in (values[0], values[-1])]
            change.append(max(float(np.max(np.abs(np.abs(a) - np.abs(b)) / np.abs(a)))
                              for a, b in zip(ends[0], ends[1], strict=True)))
        data[f"joint_force_change_vs_{key}"] = xr.DataArray(np.array(change), dims="model", attrs={
            "units": "1", "long_name": "max relative change of |Q_E| and |Q_F| over the band between the ends of the "
                                       f"sweep of the {long_name}"})
    return data, coords


def drive_scenarios(p: Mapping[str, float], models: list[str], w: np.ndarray, amp: float) -> dict[str, xr.DataArray]:
    """The claims' measures with the drive at each drive-frequency choice (the other inputs as given)."""
    choices = list(DRIVE_RATIO)
    table = {k: np.empty((len(models), len(choices))) for k in MEASURES}
    for j, choice in enumerate(choices):
        for i, m in enumerate(models):
            for k, v in claim_measures(m, {**p, "drive_ratio": DRIVE_RATIO[choice]}, w, amp).items():
                table[k][i, j] = v
    out = {
        f"{k}_by_drive": xr.DataArray(
            arr, dims=("model", "drive"),
            attrs={"units": MEASURES[k][0], "long_name": f"{MEASURES[k][1]}, per drive frequency"},
        )
        for k, arr in table.items()
    }
    out["drive_ratio"] = xr.DataArray(
        [DRIVE_RATIO[c] for c in choices], dims="drive",
        attrs={"units": "1", "long_name": "drive frequency over the main-shaft frequency"},
    )
    return {
        **out,
        "drive": xr.DataArray(
            np.array(choices, dtype=object), dims="drive", attrs={"units": "1", "long_name": "drive-frequency scenario"}
        ),
    }


def damping(p: Mapping[str, float], models: list[str], n_modes: int = 4) -> dict[str, xr.DataArray]:
    """Damping ratios of the modes from the chains' own parameters: the resonances under the kinematic drive
    (driven node held) and the antiresonances (driven node free, where it carries mass)."""
    out = {}
    for held, name, what in ((True, "held", "resonances under the kinematic drive (driven node held)"),
                             (False, "free", "antiresonances (driven node free)")):
        freq = np.full((len(models), n_modes), np.nan)
        zeta = np.full((len(models), n_modes), np.nan)
        for i, m in enumerate(models):
            wn, z = damped_modes(build(m, p, "elastic"), held=held)
            freq[i, : min(n_modes, wn.size)], zeta[i, : min(n_modes, wn.size)] = wn[:n_modes], z[:n_modes]
        nan = {"nan_meaning": "no such mode (or a massless free driven node)"}
        out[f"mode_frequency_{name}"] = xr.DataArray(
            freq, dims=("model", "mode"),
            attrs={"units": "rad s-1", "long_name": f"natural frequency |lambda| of the damped {what}", **nan},
        )
        out[f"damping_ratio_{name}"] = xr.DataArray(
            zeta, dims=("model", "mode"),
            attrs={"units": "1", "long_name": f"damping ratio -Re(lambda)/|lambda| of the {what}", **nan},
        )
    return out


def kinetostatics(p: Mapping[str, float], models: list[str], w: np.ndarray, amp: float) -> dict[str, xr.DataArray]:
    """The joint reactions from the mechanism's own kinetostatics (ideal joints, heald stroke, operating speed),
    and model A's self-consistent reactions (Vulfson's stiffness fed by the forces it produces)."""
    out = {
        "reaction_kinetostatic": xr.DataArray(
            [list(kinetostatic_reactions(m, p)) for m in models],
            dims=("model", "joint"),
            attrs={
                "units": "N",
                "long_name": (
                    "|R| of the ideal-joint chain under the heald stroke at the operating speed (first harmonic)"
                ),
            },
        ),
        "reaction_assumed": xr.DataArray(
            [p["reaction_E"], p["reaction_F"]], dims="joint",
            attrs={"units": "N", "long_name": "assumed |R| (config; model A only)"},
        ),
        "omega_op": xr.DataArray(
            p["omega_op"], attrs={"units": "rad s-1", "long_name": "operating speed of the kinetostatic reactions"}
        ),
        "stroke_D": xr.DataArray(
            p["stroke_D"], attrs={"units": "m", "long_name": "first-harmonic amplitude of the heald stroke at D"}
        ),
    }
    b = model_b_parameters(p)
    out["reaction_model_B"] = xr.DataArray(
        [b["reaction_E"], b["reaction_F"]], dims="joint",
        attrs={"units": "N", "long_name": "the reactions model B uses (its kinetostatic ones, closed form)"},
    )
    if "A" in models:
        sc = self_consistent_reactions(p, "A")
        out["reaction_self_consistent_A"] = xr.DataArray(
            [sc["R_E"], sc["R_F"]], dims="joint",
            attrs={"units": "N", "long_name": "model A: reactions R = |Q(omega_op; k_tau(R))| (fixed point)"},
        )
        out["self_consistent_split_slope_A"] = xr.DataArray(
            sc["split_slope"],
            attrs={
                "units": "1",
                "long_name": (
                    "model A: slope of the fixed-point map along the E/F split (1: every split self-consistent)"
                ),
            },
        )
        out["self_consistent_converged_A"] = xr.DataArray(
            int(sc["converged"]), attrs={"units": "1", "long_name": "1 if the fixed point was found"}
        )
        at = {**p, "reaction_E": sc["R_E"], "reaction_F": sc["R_F"]}
        out["ratio_EF_min_self_consistent_A"] = xr.DataArray(
            claim_measures("A", at, w, amp)["ratio_EF_min"],
            attrs={
                "units": "1",
                "long_name": "model A: min |Q_E|/|Q_F| over the band with the self-consistent reactions",
            },
        )
        out["clearance_pin_product"] = xr.DataArray(
            [p["k_n"] * p["clearance_E"], p["k_n"] * p["clearance_F"]],
            dims="joint",
            attrs={
                "units": "N",
                "long_name": "k_n Delta of each joint (Vulfson: k_tau ~ |R|/Delta while |R| << k_n Delta)",
            },
        )
    return out


def cam_measures(
    model: str, p: Mapping[str, float], transfer, coefficients: np.ndarray, samples: int, significant: float
):
    """The claims' measures with a periodic (cam) drive: peaks over a turn instead of harmonic amplitudes; the
    limit as the lowest shaft speed at which a significant harmonic meets the lowest resonance.  Returns the
    measures and the peaks (|Q_E|, |Q_F|)."""
    pe, pf = periodic_peaks(transfer, coefficients, samples)
    mags = np.abs(coefficients)
    h_top = int(np.flatnonzero(mags >= significant * mags[0])[-1]) + 1
    return {
        "ratio_EF_min": float(np.min(pe / pf)),
        "growth_fraction": float(np.mean((np.diff(pe) > 0) & (np.diff(pf) > 0))),
        "first_resonance": lowest_resonance(model, p) / h_top,
        "top_harmonic": float(h_top),
        "largest_dip": largest_dip(pe, pf),
    }, (pe, pf)


def largest_dip(*peaks: np.ndarray) -> float:
    """Largest relative fall of a force from one grid speed to the next, max over the forces given (0 if they only
    grow)."""
    return float(max(np.max(np.maximum(0.0, -np.diff(q) / q[:-1]), initial=0.0) for q in peaks))


CAM_MEASURES = {
    "ratio_EF_min": ("1", "min over the band of peak |Q_E| / peak |Q_F| over a turn (cam drive)"),
    "growth_fraction": ("1", "fraction of the band where the peak |Q_E| and |Q_F| over a turn both grow (cam drive)"),
    "first_resonance": (
        "rad s-1",
        "lowest shaft speed at which a significant harmonic of the cam drive meets the lowest resonance",
    ),
    "top_harmonic": ("1", "highest harmonic of the cam drive counted as significant"),
    "largest_dip": (
        "1",
        (
            "largest relative fall of the peak |Q_E| or |Q_F| over a turn between neighbouring speeds of the grid (cam"
            " drive)"
        ),
    ),
}


def joint_branch_damping(model: str, p: Mapping[str, float]) -> float:
    """Damping ratio of the modes through the joints with D held: in model B the largest of the modes above the
    lowest (the warp branch), i.e. the joint branches E and F; in model A its one mode (frame on warp and joints)."""
    _, zeta = damped_modes(build(model, p, "elastic"), held=True)
    if zeta.size == 0:
        return float("nan")
    return float(np.max(zeta[1:])) if zeta.size > 1 else float(zeta[0])


def cam_study(cfg: Mapping[str, Any], p: Mapping[str, float], models: list[str], w: np.ndarray, amp: float):
    """A dwell cam's drive (Fourier series, first harmonic scaled to the excitation amplitude): its harmonics,
    the peak joint forces over a turn, and the claims' measures at the nominal rise fraction and its range ends."""
    cam = cfg["cam"]
    rise = cam["rise_fraction"]
    fractions = [float(rise["value"]), *map(float, rise["range"])]
    transfer = {m: harmonic_transfer(m, p, w, cam["harmonics"]) for m in models}
    variables: dict[str, Any] = {"Q_E_cam": np.empty((len(models), w.size)), "Q_F_cam": np.empty((len(models), w.size))}
    table = {k: np.empty((len(models), 3)) for k in CAM_MEASURES}
    for j, beta in enumerate(fractions):
        c = cam_harmonics(beta, cam["harmonics"], cam["samples"])
        c = c * amp / abs(c[0])
        if j == 0:
            variables["cam_harmonic_amplitude"] = xr.DataArray(
                np.abs(c) / amp, dims="harmonic",
                attrs={"units": "1", "long_name": "|c_h| / |c_1| of the cam drive (nominal rise fraction)"},
            )
            ratio = np.abs(c) / amp
            variables["cam_harmonic_window_low"] = xr.DataArray(
                np.array([ratio[h + 1 :].max(initial=0.0) for h in range(ratio.size)]),
                dims="harmonic",
                attrs={
                    "units": "1",
                    "long_name": (
                        "largest |c_k|/|c_1| of the higher harmonics k > h: a significance fraction above it and at"
                        " most |c_h|/|c_1| makes h the highest counted"
                    ),
                },
            )
            variables["cam_harmonic_present"] = xr.DataArray(
                (np.abs(c) / amp > 1e-9).astype(int),
                dims="harmonic",
                attrs={
                    "units": "1",
                    "long_name": (
                        "1 if the harmonic is in the drive (|c_h|/|c_1| above round-off; the even ones vanish by"
                        " half-wave symmetry)"
                    ),
                },
            )
        for i, m in enumerate(models):
            values, peaks = cam_measures(m, p, transfer[m], c, cam["samples"], cam["significant_harmonic"])
            for k, v in values.items():
                table[k][i, j] = v
            if j == 0:
                variables["Q_E_cam"][i], variables["Q_F_cam"][i] = peaks
    for k, arr in table.items():
        variables[f"{k}_cam"] = xr.DataArray(
            arr, dims=("model", "rise"), attrs={"units": CAM_MEASURES[k][0], "long_name": CAM_MEASURES[k][1]}
        )
    # the joints' damping over its assumed range (nominal rise fraction): do the cam's weak high harmonics still
    # break the growth once the joint branches they meet are damped?
    damping_values = [float(x) for x in cfg["parameters"]["c_joint"]["range"]]
    c = cam_harmonics(fractions[0], cam["harmonics"], cam["samples"])
    c = c * amp / abs(c[0])
    by_c = {k: np.empty((len(models), len(damping_values))) for k in CAM_MEASURES}
    zeta = np.full((len(models), len(damping_values)), np.nan)
    for j, cj in enumerate(damping_values):
        q = {**p, "c_joint": cj}
        for i, m in enumerate(models):
            values, _ = cam_measures(
                m, q, harmonic_transfer(m, q, w, cam["harmonics"]), c, cam["samples"], cam["significant_harmonic"]
            )
            for k, v in values.items():
                by_c[k][i, j] = v
            zeta[i, j] = joint_branch_damping(m, q)
    for k, arr in by_c.items():
        variables[f"{k}_cam_by_joint_damping"] = xr.DataArray(
            arr,
            dims=("model", "joint_damping"),
            attrs={
                "units": CAM_MEASURES[k][0],
                "long_name": f"{CAM_MEASURES[k][1]}, at the ends of the joint damping's range",
            },
        )
    variables["joint_branch_damping_ratio"] = xr.DataArray(
        zeta,
        dims=("model", "joint_damping"),
        attrs={
            "units": "1",
            "long_name": (
                "largest damping ratio of the modes with D held other than the lowest (the joint branches), at the ends"
                " of the joint damping's range"
            ),
        },
    )
    lowest = np.array([lowest_resonance(m, p) for m in models])
    variables["cam_harmonic_speed"] = xr.DataArray(
        lowest[:, None] / np.arange(1, cam["harmonics"] + 1)[None, :],
        dims=("model", "harmonic"),
        attrs={
            "units": "rad s-1",
            "long_name": "shaft speed at which harmonic h of the drive meets the lowest resonance",
        },
    )
    variables["significant_harmonic"] = xr.DataArray(
        float(cam["significant_harmonic"]),
        attrs={
            "units": "1",
            "long_name": "our reading: a harmonic counts for the speed limit if |c_h|/|c_1| is at least this",
        },
    )
    for k in ("Q_E_cam", "Q_F_cam"):
        variables[k] = xr.DataArray(
            variables[k],
            dims=("model", "omega"),
            attrs={
                "units": "N",
                "long_name": f"peak |{k[:3]}| over a turn, cam drive (nominal rise fraction), elastic joints",
            },
        )
    coords = {
        "rise": (
            "rise", np.array(["nominal", "low", "high"], dtype=object),
            {"units": "1", "long_name": "cam rise fraction: nominal and its range ends"},
        ),
        "rise_fraction": (
            "rise", np.array(fractions),
            {"units": "1", "long_name": "fraction of a turn of the rise (and of the return)"},
        ),
        "joint_damping": (
            "joint_damping", np.array(damping_values),
            {"units": "N s m-1", "long_name": "joint damping c_joint: the ends of its assumed range"},
        ),
        "harmonic": (
            "harmonic", np.arange(1, cam["harmonics"] + 1), {"units": "1", "long_name": "harmonic of the shaft speed"},
        ),
        "joint": ("joint", np.array(["E", "F"], dtype=object), {"units": "1", "long_name": "joint"}),
    }
    return variables, coords
