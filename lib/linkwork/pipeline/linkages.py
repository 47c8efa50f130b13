"""The study of a linkage of your own (config ``linkages.<name>``): written as a scene, run by the shared engine.

For each linkage: its ideal dynamics (every joint closed; kinematics by Newton's method on the description's
constraints, multipliers from Phi_q^T lambda = g - M q'') and its forward dynamics with exactly the effects its
clearance joints name (the compiled right-hand side generated from the description, integrated at the scene's
integrator setting from the assembled start, journals centred), over ``turns`` driven turns sampled at
``points_per_turn``.  SI units inside; the driver angle in degrees at the output boundary.
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from typing import Any

import numpy as np
import xarray as xr

from ..engines.multibody import assembly, describe
from ..engines.multibody.linkage import LinkageError
from ..engines.multibody.simulate import Run
from .errors import ConfigError


def study(cfg: Mapping[str, Any], name: str) -> xr.Dataset:
    """Rule study: one linkage scene of ``linkages``: its ideal dynamics and its forward dynamics with its joints'
    effects."""
    key = f"linkages.{name}.linkage"
    linkage = describe.from_config(cfg["linkage"], key)
    settings = describe.assembly_settings(f"{key}.assembly", cfg["linkage"].get("assembly"))
    turn = assembly.follow_turn(linkage, settings)
    period = linkage.driver.period
    t = np.arange(cfg["turns"] * cfg["points_per_turn"] + 1) * period / cfg["points_per_turn"]
    ideal = assembly.inverse_dynamics(linkage, t, cfg["gravity"], settings, turn)
    try:
        run = Run(
            linkage, cfg["gravity"], cfg["integrator"], y0=assembly.start_state(linkage, settings=settings),
            key=f"linkages.{name}.integrator",
        )
        states, diags = run.advance(t)
    except LinkageError as exc:  # a setting the run cannot go on with (a stall, a size guard): one line, its key
        raise ConfigError(f"config key {exc}") from None
    except RuntimeError as exc:  # the integrator's step fell below its floor: the scene is too stiff for the method
        if "underflow" not in str(exc):
            raise
        raise ConfigError(
            f"config key linkages.{name}: the integrator ({cfg['integrator']['method']}) cannot keep a step above"
            " its floor: the description is too stiff for it; check the clearance joints' youngs_modulus_Pa, the"
            " springs' stiffness and the bodies' mass_kg and inertia_kg_m2 (or use method ndf, for stiff scenes)"
        ) from None
    print(
        f"linkage {name}: {len(linkage.bodies)} bodies, {len(linkage.joints)} joints ({len(linkage.clearance_joints)}"
        f" with clearance), {cfg['turns']} turns, {run.steps} steps",
        flush=True,
    )
    ds = _dataset(linkage, cfg, t, ideal, diags, run)
    if ds.attrs["validity_warnings"]:  # written, and said where the run's reader sees it
        print(f"linkage {name}: outside its models: {ds.attrs['validity_warnings']}", flush=True)
    return ds


def joint_validity(linkage, eccentricity: np.ndarray, penetration: np.ndarray) -> dict[str, str]:
    """Where each clearance joint leaves the range of its own models (``engines.multibody.validity``): the deepest
    penetration against the elastic law's range, and the time beyond the film cap; the attributes
    ``validity_<joint>`` (the measures, JSON) and ``validity_warnings`` (one sentence per joint outside, '' if none)."""
    from ..engines.multibody import validity

    out, warnings = {}, []
    for k, joint in enumerate(linkage.clearance_joints):
        c = joint.clearance
        contact = "contact" in c.effects
        limit = validity.penetration_limit(c.elastic_law, c.journal_radius, c.bearing_radius) if contact else np.inf
        cap = 1.0 - c.e0 / c.clearance if "lubrication" in c.effects else None
        attrs = validity.attributes(penetration[k][None], eccentricity[k][None], c.clearance, cap, limit)
        out[f"validity_{joint.name}"] = json.dumps(
            {key: (float(v) if isinstance(v, (int, float, np.floating)) else v) for key, v in attrs.items()},
            sort_keys=True,
        )
        if attrs["validity_warnings"]:
            warnings.append(f"joint {joint.name}: {attrs['validity_warnings']}")
    out["validity_warnings"] = "; ".join(warnings)
    return out


def _dataset(linkage, cfg, t, ideal, diags, run) -> xr.Dataset:
    ideal_joints = [j.name for j in linkage.joints]
    clearance = [j.name for j in linkage.clearance_joints]
    per = np.array([diags[:, 4 + 6 * k : 10 + 6 * k] for k in range(len(clearance))]).reshape(len(clearance), t.size, 6)
    data = {
        "driver_angle": (
            "time", np.degrees(linkage.driver.angle(t)[0]), {"units": "deg", "long_name": "driver angle (unwrapped)"},
        ),
        "ideal_output_acceleration": (
            "time", ideal["output_acceleration"],
            {"units": "rad/s^2", "long_name": f"{linkage.output}'s angular acceleration, every joint ideal"},
        ),
        "ideal_driver_torque": (
            "time", ideal["driver_torque"], {"units": "N m", "long_name": "driver torque, every joint ideal"},
        ),
        "ideal_joint_force": (
            ("joint", "time"), np.array([ideal[f"force_{j}"] for j in ideal_joints]),
            {"units": "N", "long_name": "joint reaction force magnitude, every joint ideal"},
        ),
        "output_acceleration": (
            "time", diags[:, 0],
            {"units": "rad/s^2", "long_name": f"{linkage.output}'s angular acceleration, with the joints' effects"},
        ),
        "driver_torque": (
            "time", diags[:, 1], {"units": "N m", "long_name": "driver torque, with the joints' effects"},
        ),
        "energy": ("time", diags[:, 2], {"units": "J", "long_name": "kinetic + gravity + contact potential energy"}),
        "constraint_drift": (
            "time", diags[:, 3], {"units": "m", "long_name": "norm of the constraint violation (Baumgarte-stabilised)"},
        ),
        "eccentricity": (
            ("clearance_joint", "time"), per[:, :, 0], {"units": "m", "long_name": "journal centre to bearing centre"},
        ),
        "penetration": (
            ("clearance_joint", "time"), per[:, :, 1],
            {"units": "m", "long_name": "eccentricity minus the radial clearance (> 0: in contact)"},
        ),
        "contact_force": (
            ("clearance_joint", "time"), per[:, :, 3], {"units": "N", "long_name": "dry normal contact force"},
        ),
        "film_force": (("clearance_joint", "time"), per[:, :, 4], {"units": "N", "long_name": "film radial force"}),
    }
    attrs = {
        "integrator": json.dumps(dict(cfg["integrator"]), sort_keys=True),
        "gravity": int(cfg["gravity"]),
        "steps": run.steps,
        "rejected_steps": run.rejected,
        "baumgarte_per_s": linkage.baumgarte,
        "assembly": json.dumps(cfg["linkage"].get("assembly") or {}, sort_keys=True),
        "effects": json.dumps({j.name: list(j.clearance.effects) for j in linkage.clearance_joints}, sort_keys=True),
        **joint_validity(linkage, per[:, :, 0], per[:, :, 1]),
    }
    coords = {"time": ("time", t, {"units": "s", "long_name": "time from the start"}),
              "joint": ("joint", ideal_joints, {"units": "1", "long_name": "joint (its name in the description)"}),
              "clearance_joint": ("clearance_joint", clearance, {"units": "1", "long_name": "joint with a clearance"})}
    return xr.Dataset(data, coords=coords, attrs=attrs)
