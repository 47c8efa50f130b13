"""Config adapter of the clearance paper: the config keys each scene reads, and the model parameters
built from exactly those keys.

A scene names its effects (contact, friction, lubrication, gravity); a parameter that only an effect
the scene does not name would use is neither passed to the scene's rule nor read (it is NaN in the
parameters, and the generated right-hand side never touches it).  Standard library only at import,
so that the Snakefile can ask for the keys cheaply.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

BODIES = ("crank", "coupler", "rocker")
#: The scenes the claims compare, dry then lubricated, in this order (here, not in studies, so that the Snakefile and
#: the batch planner name them without importing the simulation's modules).
DRY = ("dry_1", "dry_2", "dry_both")
LUBRICATED = ("lubricated_1", "lubricated_2", "lubricated_both")
COMPARED = DRY + LUBRICATED

#: Config keys (relative to the clearance section) that each effect adds to a scene with clearance joints.
EFFECT_KEYS: dict[str, tuple[str, ...]] = {
    "contact": (
        "joints.youngs_modulus_Pa",
        "joints.poisson",
        "joints.restitution",
        "joints.contact_law",
        "joints.elastic_law",
        "assumed.impact_velocity_floor_m_s",
        "joints.fixed_impact_velocity_m_s",
    ),
    "friction": ("joints.friction", "assumed.v0_m_s", "assumed.v1_m_s"),
    "lubrication": ("joints.viscosity_Pa_s", "assumed.joint_length_m", "assumed.e0_m"),
    "gravity": (),
}
#: Config keys the contact reads besides EFFECT_KEYS['contact'], by its elastic law (joints.elastic_law).
ELASTIC_LAW_KEYS: dict[str, tuple[str, ...]] = {"hertz-sphere": (), "pereira": ("assumed.joint_length_m",)}
#: What every scene reads: the linkage, the drive and the recorded window.
LINKAGE_KEYS = ("ground_m", "crank_speed_rad_s", *(f"bodies.{b}.{k}" for b in BODIES for k in ("length_m", "mass_kg")))
WINDOW_KEYS = ("numerics.points_per_cycle", "numerics.record_cycles")
#: What a scene with clearance joints reads to find its states and judge the claims' measures on them.
SETTLE_KEYS = (
    "states", "statistics.batch_cycles", "statistics.confidence", "claims.ripple_cutoff_hz",
    "claims.ripple_cutoff_sensitivity_hz",
)
#: What a scene with clearance joints reads besides its effects.
DYNAMIC_KEYS = ("joints.journal_radius_m", "joints.bearing_radius_m", "numerics.baumgarte")


def integrator_kind(scene: Mapping[str, Any]) -> str:
    """'explicit' or 'stiff': which integrator group setting a scene uses."""
    return scene.get("integrator", "explicit")


def model_keys(section: Mapping[str, Any], variant: str, scene: str) -> list[str]:
    """Keys the model of one scene of one variant reads (no recorded window, no integrator)."""
    keys = [*LINKAGE_KEYS, f"variants.{variant}", f"scenes.{scene}"]
    if section["variants"][variant]["inertia"] == "decoded":
        keys += [f"bodies.{b}.inertia_kg_m2" for b in BODIES]
    spec = section["scenes"][scene]
    if spec["clearance_joints"]:
        keys += DYNAMIC_KEYS
        for effect in spec["effects"]:
            keys += EFFECT_KEYS[effect]
        if "contact" in spec["effects"]:
            keys += ELASTIC_LAW_KEYS[section["joints"]["elastic_law"]]
    return list(dict.fromkeys(keys))


def scene_keys(section: Mapping[str, Any], variant: str, scene: str) -> list[str]:
    """Keys a scene run reads: its model, the recorded window and (with clearance joints) the settling rule, its
    integrator and the check integrators of its error bar."""
    keys = model_keys(section, variant, scene) + list(WINDOW_KEYS)
    spec = section["scenes"][scene]
    if spec["clearance_joints"]:
        kind = integrator_kind(spec)
        keys += [*SETTLE_KEYS, f"integrators.{kind}", f"check_integrators.{kind}"]
    return keys


def parameters(cfg: Mapping[str, Any], variant: str, scene: str):
    """FourBarParameters of a scene from the keys ``model_keys`` names (SI units).

    Inertias are the decoded ones as printed, or J = m L^2 / 12 for the 'slender' variant.
    Parameters of effects the scene does not name are NaN; the joint length is read by the lubrication and by
    a contact whose elastic law needs it (ELASTIC_LAW_KEYS).
    """
    from .fourbar import FourBarParameters

    nan = float("nan")
    b = cfg["bodies"]
    lengths = tuple(float(b[n]["length_m"]) for n in BODIES)
    masses = tuple(float(b[n]["mass_kg"]) for n in BODIES)
    if cfg["variants"][variant]["inertia"] == "decoded":
        inertias = tuple(float(b[n]["inertia_kg_m2"]) for n in BODIES)
    else:
        inertias = tuple(m * length**2 / 12 for m, length in zip(masses, lengths, strict=True))
    spec = cfg["scenes"][scene]
    effects = set(spec["effects"]) if spec["clearance_joints"] else set()
    values: dict[str, Any] = {
        "journal_radius": nan, "bearing_radius": nan, "youngs_modulus": (nan, nan), "poisson": (nan, nan),
        "joint_length": nan, "restitution": nan, "friction": nan, "v0": nan, "v1": nan, "viscosity": nan,
        "e0": nan, "impact_velocity_floor": nan, "baumgarte_alpha": nan, "baumgarte_beta": nan,
    }
    if spec["clearance_joints"]:
        j, n = cfg["joints"], cfg["numerics"]
        values.update(journal_radius=j["journal_radius_m"], bearing_radius=j["bearing_radius_m"],
                      baumgarte_alpha=n["baumgarte"], baumgarte_beta=n["baumgarte"])
    if "contact" in effects:
        j = cfg["joints"]
        values.update(
            youngs_modulus=(j["youngs_modulus_Pa"],) * 2, poisson=(j["poisson"],) * 2, restitution=j["restitution"],
            impact_velocity_floor=cfg["assumed"]["impact_velocity_floor_m_s"]["value"], contact_law=j["contact_law"],
            elastic_law=j["elastic_law"], fixed_impact_velocity=nan if j["fixed_impact_velocity_m_s"] is None
            else j["fixed_impact_velocity_m_s"],
        )
        if "assumed.joint_length_m" in ELASTIC_LAW_KEYS[j["elastic_law"]]:
            values.update(joint_length=cfg["assumed"]["joint_length_m"]["value"])
    if "friction" in effects:
        a = cfg["assumed"]
        values.update(friction=cfg["joints"]["friction"], v0=a["v0_m_s"]["value"], v1=a["v1_m_s"]["value"])
    if "lubrication" in effects:
        a = cfg["assumed"]
        values.update(
            viscosity=cfg["joints"]["viscosity_Pa_s"], joint_length=a["joint_length_m"]["value"], e0=a["e0_m"]["value"]
        )
    return FourBarParameters(ground=cfg["ground_m"], lengths=lengths, masses=masses, inertias=inertias,
                             crank_speed=cfg["crank_speed_rad_s"], **values)


def scene_effects(cfg: Mapping[str, Any], scene: str) -> tuple[tuple[int, ...], tuple[str, ...]]:
    """(clearance joints, effects) of a scene."""
    spec = cfg["scenes"][scene]
    return tuple(spec["clearance_joints"]), tuple(spec["effects"])
