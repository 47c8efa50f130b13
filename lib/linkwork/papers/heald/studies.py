"""The heald paper's studies: chain responses of models A and B with the claims' measures and their sweeps."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import xarray as xr

from ...engines.chains import resonances, solve_network
from ...units import RAD_S_PER_RPM
from .adapter import amplitude, omega_grid, parameters, sweep_values
from .model import JOINTS, build, eq2_mobility, joint_stiffness


def joint_forces(model: str, p: Mapping[str, float], variant: str, omega: np.ndarray, amplitude: float):
    """(input force, Q_E, Q_F, singular) for a drive displacement amplitude (m): V = j w X."""
    r = solve_network(build(model, p, variant), omega, 1j * omega * amplitude)
    q_e = r.element_force["joint_E"] + r.element_force["joint_E_damping"]
    q_f = r.element_force["joint_F"] + r.element_force["joint_F_damping"]
    return r.input_force, q_e, q_f, r.singular


def growth_fraction(model: str, p: Mapping[str, float], omega: np.ndarray, amplitude: float) -> float:
    """Fraction of the grid intervals over which |Q_E| and |Q_F| both grow (elastic joints)."""
    _, q_e, q_f, _ = joint_forces(model, p, "elastic", omega, amplitude)
    return float(np.mean((np.diff(np.abs(q_e)) > 0) & (np.diff(np.abs(q_f)) > 0)))


def claim_measures(model: str, p: Mapping[str, float], omega: np.ndarray, amplitude: float) -> dict[str, float]:
    """The numbers the paper's claims are judged on, for one model and parameter set (elastic joints)."""
    _, q_e, q_f, _ = joint_forces(model, p, "elastic", omega, amplitude)
    ratio = np.abs(q_e) / np.abs(q_f)
    growth = np.mean((np.diff(np.abs(q_e)) > 0) & (np.diff(np.abs(q_f)) > 0))
    vel, force = resonances(build(model, p, "elastic"))
    first = min([x for x in (*vel, *force) if x > 0], default=np.nan)
    return {"ratio_EF_min": float(ratio.min()), "ratio_EF_max": float(ratio.max()), "growth_fraction": float(growth), "first_resonance": float(first)}


MEASURES = {
    "ratio_EF_min": ("1", "min over the band of |Q_E| / |Q_F| (elastic joints)"),
    "ratio_EF_max": ("1", "max over the band of |Q_E| / |Q_F| (elastic joints)"),
    "growth_fraction": ("1", "fraction of the band where |Q_E| and |Q_F| both grow with frequency"),
    "first_resonance": ("rad s-1", "lowest undamped resonance (velocity or force), elastic joints"),
}


def claims(cfg: Mapping[str, Any], refinement: bool = True) -> xr.Dataset:
    """The numbers the paper's claims are judged on, per chain model, at the config's parameters; with
    ``refinement`` also how much halving the frequency grid changes the growth measure (its error bar)."""
    p, amp, w = parameters(cfg), amplitude(cfg), omega_grid(cfg["speeds"])
    models = list(cfg["models"])
    measures = {m: claim_measures(m, p, w, amp) for m in models}
    data = {k: ("model", [measures[m][k] for m in models], {"units": unit, "long_name": text}) for k, (unit, text) in MEASURES.items()}
    data["first_resonance_rpm"] = ("model", [measures[m]["first_resonance"] / RAD_S_PER_RPM for m in models],
                                   {"units": "min-1", "long_name": "lowest undamped resonance as a shaft speed"})
    if refinement:
        fine = np.linspace(w[0], w[-1], 2 * w.size - 1)  # every interval halved: how much the grid decides the growth measure
        data["growth_fraction_refinement"] = ("model", [abs(growth_fraction(m, p, fine, amp) - measures[m]["growth_fraction"]) for m in models],
                                              {"units": "1", "long_name": "change of the growth fraction when the frequency grid is halved"})
    return xr.Dataset(data, coords={"model": ("model", np.array(models, dtype=object), {"units": "1", "long_name": "A: physical linkage; B: chain of the form of eq. (2)"})})


def interlaced(zeros: np.ndarray, poles: np.ndarray) -> bool:
    """True if the sorted zeros and poles alternate, starting with a zero (w09 < w07 < w010 < w08 < w011)."""
    merged = sorted([(w, 0) for w in zeros] + [(w, 1) for w in poles])
    kinds = [k for _, k in merged]
    return kinds[0] == 0 and all(kinds[i] != kinds[i + 1] for i in range(len(kinds) - 1))


def _labelled_attrs(cfg: Mapping[str, Any]) -> dict[str, str]:
    return {f"param_{k}": f"{v['value']:g} ({v['status']}: {v['reason']})" for k, v in cfg["parameters"].items()}


def chain(cfg: Mapping[str, Any]) -> xr.Dataset:
    """Q, Q_E, Q_F with ideal and elastic joints for both models, resonances, claim measures, sweeps."""
    p = parameters(cfg)
    amp = amplitude(cfg)
    w = omega_grid(cfg["speeds"])
    models = list(cfg["models"])
    shape = (len(models), len(JOINTS), w.size)
    q_in, q_e, q_f = (np.empty(shape) for _ in range(3))
    mobility = np.empty(shape, dtype=complex)
    n_modes = 4
    vel_res = np.full((len(models), len(JOINTS), n_modes), np.nan)
    force_res = np.full((len(models), len(JOINTS), n_modes), np.nan)
    for i, model in enumerate(models):
        for j, variant in enumerate(JOINTS):
            qi, qe, qf, _ = joint_forces(model, p, variant, w, amp)
            q_in[i, j], q_e[i, j], q_f[i, j] = np.abs(qi), np.abs(qe), np.abs(qf)
            mobility[i, j] = 1j * w * amp / qi
            vr, fr = resonances(build(model, p, variant))
            vel_res[i, j, : min(n_modes, vr.size)] = vr[:n_modes]
            force_res[i, j, : min(n_modes, fr.size)] = fr[:n_modes]
    coords = {
        "model": ("model", np.array(models, dtype=object), {"units": "1", "long_name": "A: physical linkage; B: chain of the form of eq. (2)"}),
        "joints": ("joints", np.array(JOINTS, dtype=object), {"units": "1", "long_name": "ideal: no clearance (pin stiffness k_n); elastic: Vulfson clearance model"}),
        "omega": ("omega", w, {"units": "rad s-1", "long_name": "main-shaft circular frequency"}),
        "shaft_speed": ("omega", w / RAD_S_PER_RPM, {"units": "min-1", "long_name": "main-shaft speed"}),
        "mode": ("mode", np.arange(n_modes), {"units": "1", "long_name": "resonance index (ascending)"}),
    }
    dims = ("model", "joints", "omega")
    data = {
        "Q": xr.DataArray(q_in, dims=dims, attrs={"units": "N", "long_name": "|Q|, force at the driven joint D"}),
        "Q_E": xr.DataArray(q_e, dims=dims, attrs={"units": "N", "long_name": "|Q_E|, force in joint E"}),
        "Q_F": xr.DataArray(q_f, dims=dims, attrs={"units": "N", "long_name": "|Q_F|, force in joint F"}),
        "K_abs": xr.DataArray(np.abs(mobility), dims=dims, attrs={"units": "m N-1 s-1", "long_name": "|K|, input mobility V/Q"}),
        "K_phase": xr.DataArray(np.angle(mobility), dims=dims, attrs={"units": "rad", "long_name": "phase of the input mobility"}),
        "velocity_resonance": xr.DataArray(vel_res, dims=("model", "joints", "mode"), attrs={"units": "rad s-1", "long_name": "velocity resonances (K = 0), undamped", "nan_meaning": "the chain has fewer resonances than the mode axis holds"}),
        "force_resonance": xr.DataArray(force_res, dims=("model", "joints", "mode"), attrs={"units": "rad s-1", "long_name": "force resonances (K -> infinity), undamped", "nan_meaning": "the chain has fewer resonances than the mode axis holds"}),
        "k_E": xr.DataArray([joint_stiffness(p, "E", v) for v in JOINTS], dims="joints", attrs={"units": "N m-1", "long_name": "tangential stiffness of joint E"}),
        "k_F": xr.DataArray([joint_stiffness(p, "F", v) for v in JOINTS], dims="joints", attrs={"units": "N m-1", "long_name": "tangential stiffness of joint F"}),
    }
    # model B against eq. (2) (undamped)
    undamped = {**p, "c_joint": 0.0, "c_O": 0.0}
    k_eq2, num_w, den_w = eq2_mobility(undamped, w)
    r = solve_network(build("B", undamped, "elastic"), w, 1.0)
    data["eq2_relative_difference"] = xr.DataArray(
        float(np.max(np.abs(1 / r.input_force - k_eq2) / np.abs(k_eq2))), attrs={"units": "1", "long_name": "max |K_network - K_eq2| / |K_eq2|, model B, undamped"}
    )
    data["eq2_numerator_frequencies"] = xr.DataArray(num_w, dims="numerator_factor", attrs={"units": "rad s-1", "long_name": "w09, w010, w011 of eq. (2) (velocity resonances)"})
    data["eq2_denominator_frequencies"] = xr.DataArray(den_w, dims="denominator_factor", attrs={"units": "rad s-1", "long_name": "w07, w08 of eq. (2) (force resonances)"})
    data["eq2_interlaced"] = xr.DataArray(int(interlaced(num_w, den_w)), attrs={"units": "1", "long_name": "1 if zeros and poles of eq. (2) interlace, starting with a zero"})
    data.update(claims(cfg).data_vars)

    # sweeps: the parameter ranges that support each claim
    sw = cfg["sweeps"]
    sweep_defs = {
        "reaction_ratio": ("reaction_ratio", "1", "|R_E| / |R_F| (|R_F| fixed)", lambda x: {**p, "reaction_E": x * p["reaction_F"]}),
        "clearance": ("clearance", "m", "clearance Delta of both joints", lambda x: {**p, "clearance_E": x, "clearance_F": x}),
        "heald_mass": ("heald_mass", "kg", "heald-frame mass M_P", lambda x: {**p, "M_P": x}),
        "warp_stiffness": ("warp_stiffness", "N m-1", "warp stiffness k_O", lambda x: {**p, "k_O": x}),
    }
    for key, (dim, unit, long_name, make) in sweep_defs.items():
        spec = sw[key]
        values = sweep_values(spec)
        coords[dim] = (dim, values, {"units": unit, "long_name": long_name})
        table = {k: np.empty((len(models), values.size)) for k in MEASURES}
        for i, m in enumerate(models):
            for j, x in enumerate(values):
                for k, v in claim_measures(m, make(x), w, amp).items():
                    table[k][i, j] = v
        for k, arr in table.items():
            unit, text = MEASURES[k]
            data[f"{k}_vs_{key}"] = xr.DataArray(arr, dims=("model", dim), attrs={"units": unit, "long_name": f"{text} vs {long_name}"})
    ds = xr.Dataset(data, coords=coords)
    ds.attrs.update(_labelled_attrs(cfg), title="Heald motion as mechanical chains")
    ds.attrs.update(displacement_amplitude_m=amp, frequency_points=int(w.size))
    return ds
