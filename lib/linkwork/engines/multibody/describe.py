"""A linkage description read from config (``linkages.<name>``), checked before any job with the key named.

The config form (degrees for angles, SI otherwise, units in the key names)::

    bodies:
      crank: {mass_kg: 0.5, inertia_kg_m2: 2.0e-3, points: {O: [-0.05, 0.0], A: [0.05, 0.0]}, angle_guess_deg: 60}
      ...
    ground: {O2: [0.0, 0.0], O4: [0.3, 0.0]}
    joints:
      O2: {journal: crank.O, bearing: ground.O2}
      A: {journal: crank.A, bearing: coupler.A, clearance: {...}}   # a clearance joint names its effects
    driver: {body: crank, speed_rad_s: 10.0, start_angle_deg: 60, cos_deg: [], sin_deg: []}   # a negative speed turns
    the other way
    # or a rocking lever: {body: lever, speed_rad_s: 10.0, start_angle_deg: 90, cos_deg: [...], sin_deg: [...], rocking:
    true} springs:                   # optional: a body point pulled towards a fixed rest point, per axis
      warp: {point: frame.C, rest_m: [0.8, 0.6], stiffness_N_m: [0.0, 2.0e+4], damping_N_s_m: [0.0, 20.0]}
    output: rocker
    gravity_m_s2: 9.81         # optional (default: standard gravity)
    baumgarte_per_s: 250.0     # optional
    assembly: {steps_per_turn: 720, tolerance: 1.0e-13, max_iterations: 50, condition_limit: 1.0e8}   # optional

A point of a body is given in the body's frame, whose origin is the centre of mass.  A clearance joint's block::

    clearance: {journal_radius_m, bearing_radius_m, effects: [contact, friction, lubrication],
                youngs_modulus_Pa, poisson, restitution, contact_law, elastic_law, impact_velocity_floor_m_s,   #
                contact friction, v0_m_s, v1_m_s,                                                                   #
                friction viscosity_Pa_s, length_m, e0_m}                                                             #
                lubrication

Each effect reads exactly its keys; a key of an effect not named is refused (it would be silently unused).  The
pereira elastic law reads ``length_m`` too, and needs a radial clearance above 1 µm.
``check`` assembles the linkage and follows it through the driven turn, so that a linkage that cannot assemble or
locks up is refused before any job, with its key.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from .assembly import AssemblySettings, follow_turn
from ...units import STANDARD_GRAVITY
from .linkage import (
    CONTACT_LAWS, ELASTIC_LAWS, GROUND, JOINT_EFFECTS, PEREIRA_MIN_CLEARANCE, Body, Clearance, Driver, Joint, Linkage,
    LinkageError, Spring,
)

#: The slowest drive a linkage accepts (rad/s, either sense): slower, one turn is hours of simulated time.
MIN_SPEED = 1e-3

#: Clearance keys every clearance joint reads, and those each effect adds.
CLEARANCE_KEYS = ("journal_radius_m", "bearing_radius_m", "effects")
EFFECT_KEYS = {
    "contact": (
        "youngs_modulus_Pa", "poisson", "restitution", "contact_law", "elastic_law", "impact_velocity_floor_m_s",
    ),
    "friction": ("friction", "v0_m_s", "v1_m_s"),
    "lubrication": ("viscosity_Pa_s", "length_m", "e0_m"),
}
ASSEMBLY_KEYS = {"steps_per_turn": "steps_per_turn", "tolerance": "tolerance", "max_iterations": "max_iterations",
                 "condition_limit": "condition_limit"}
TOP_KEYS = ("bodies", "ground", "joints", "driver", "output", "springs", "gravity_m_s2", "baumgarte_per_s", "assembly")


def _number(key: str, value: Any, positive: bool = False, nonnegative: bool = False) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise LinkageError(key, f"must be a finite number, got {value!r}")
    if positive and value <= 0:
        raise LinkageError(key, f"must be positive, got {value!r}")
    if nonnegative and value < 0:
        raise LinkageError(key, f"must not be negative, got {value!r}")
    return float(value)


def _mapping(key: str, value: Any) -> Mapping[str, Any]:
    if not isinstance(value, Mapping) or not value:
        raise LinkageError(key, f"must be a non-empty mapping, got {value!r}")
    return value


def _xy(key: str, value: Any) -> tuple[float, float]:
    if not isinstance(value, (list, tuple)) or len(value) != 2:
        raise LinkageError(key, f"must be a point [x, y] in m, got {value!r}")
    return _number(f"{key}[0]", value[0]), _number(f"{key}[1]", value[1])


def _only(key: str, spec: Mapping[str, Any], allowed, required=()) -> None:
    unknown = sorted(set(spec) - set(allowed))
    if unknown:
        raise LinkageError(f"{key}.{unknown[0]}", f"unknown key; known here: {', '.join(allowed)}")
    for name in required:
        if name not in spec:
            raise LinkageError(f"{key}.{name}", "missing")


def _bodies(key: str, spec: Mapping[str, Any]) -> tuple[Body, ...]:
    out = []
    for name, b in _mapping(key, spec).items():
        k = f"{key}.{name}"
        if name == GROUND:
            raise LinkageError(k, f"'{GROUND}' is the fixed frame, not a body")
        _only(
            k, _mapping(k, b), ("mass_kg", "inertia_kg_m2", "points", "angle_guess_deg"),
            ("mass_kg", "inertia_kg_m2", "points"),
        )
        points = {str(p): _xy(f"{k}.points.{p}", xy) for p, xy in _mapping(f"{k}.points", b["points"]).items()}
        out.append(Body(str(name), _number(f"{k}.mass_kg", b["mass_kg"], positive=True),
                        _number(f"{k}.inertia_kg_m2", b["inertia_kg_m2"], positive=True), points,
                        math.radians(_number(f"{k}.angle_guess_deg", b.get("angle_guess_deg", 0.0)))))
    return tuple(out)


def _ref(key: str, value: Any, bodies: tuple[Body, ...], ground: Mapping[str, tuple[float, float]]) -> tuple[str, str]:
    """A 'body.point' reference, resolved: the body known (or 'ground'), the point one of its points."""
    if not isinstance(value, str) or value.count(".") != 1:
        raise LinkageError(key, f"must name a point as 'body.point', got {value!r}")
    body, point = value.split(".")
    if body == GROUND:
        if point not in ground:
            raise LinkageError(key, f"unknown ground point {point!r}; ground points: {', '.join(ground) or 'none'}")
        return body, point
    names = {b.name: b for b in bodies}
    if body not in names:
        raise LinkageError(key, f"unknown body {body!r}; bodies: {', '.join(names)}")
    if point not in names[body].points:
        raise LinkageError(
            key, f"unknown point {point!r} of body {body!r}; its points: {', '.join(names[body].points)}"
        )
    return body, point


def _clearance(key: str, spec: Mapping[str, Any]) -> Clearance:
    spec = _mapping(key, spec)
    effects = spec.get("effects")
    if not isinstance(effects, list) or len(set(map(str, effects))) != len(effects):
        raise LinkageError(
            f"{key}.effects", f"must be a list of distinct effects among {', '.join(JOINT_EFFECTS)}, got {effects!r}"
        )
    unknown = [e for e in effects if e not in JOINT_EFFECTS]
    if unknown:
        raise LinkageError(f"{key}.effects", f"unknown effect {unknown[0]!r}; known: {', '.join(JOINT_EFFECTS)}")
    if "friction" in effects and "contact" not in effects:
        raise LinkageError(f"{key}.effects", "friction needs contact (it acts with the normal contact force)")
    if not {"contact", "lubrication"} & set(effects):
        raise LinkageError(
            f"{key}.effects",
            f"needs contact or lubrication: nothing else holds the journal in its bearing, got {effects!r}",
        )
    allowed = (*CLEARANCE_KEYS, *(k for e in effects for k in EFFECT_KEYS[e]))
    if "contact" in effects and spec.get("elastic_law") == "pereira" and "length_m" not in allowed:
        allowed += ("length_m",)  # Pereira's stiffness reads the joint's length
    _only(key, spec, allowed, allowed)
    rj, rb = _number(f"{key}.journal_radius_m", spec["journal_radius_m"], positive=True), _number(
        f"{key}.bearing_radius_m", spec["bearing_radius_m"], positive=True
    )
    if rb <= rj:
        raise LinkageError(f"{key}.bearing_radius_m", f"must exceed the journal radius ({rj:g} m), got {rb:g} m")
    values: dict[str, Any] = {}
    if "contact" in effects:
        values.update(_contact(key, spec))
        if values["elastic_law"] == "pereira":
            values["length"] = _number(f"{key}.length_m", spec["length_m"], positive=True)
        if values["elastic_law"] == "pereira" and rb - rj <= PEREIRA_MIN_CLEARANCE:
            raise LinkageError(
                f"{key}.elastic_law",
                f"pereira needs a radial clearance above {PEREIRA_MIN_CLEARANCE:g} m (its fitted exponent is undefined"
                f" below), got {rb - rj:g} m: widen the clearance or use hertz-sphere",
            )
    if "friction" in effects:
        values.update(
            friction=_number(f"{key}.friction", spec["friction"], nonnegative=True),
            v0=_number(f"{key}.v0_m_s", spec["v0_m_s"], nonnegative=True),
            v1=_number(f"{key}.v1_m_s", spec["v1_m_s"], positive=True),
        )
        if values["v1"] <= values["v0"]:
            raise LinkageError(f"{key}.v1_m_s", f"must exceed v0_m_s ({values['v0']:g}), got {values['v1']:g}")
    if "lubrication" in effects:
        values.update(
            viscosity=_number(f"{key}.viscosity_Pa_s", spec["viscosity_Pa_s"], positive=True),
            length=_number(f"{key}.length_m", spec["length_m"], positive=True),
            e0=_number(f"{key}.e0_m", spec["e0_m"], positive=True),
        )
        if values["e0"] >= rb - rj:
            raise LinkageError(
                f"{key}.e0_m", f"must be below the radial clearance ({rb - rj:g} m), got {values['e0']:g} m"
            )
    return Clearance(rj, rb, tuple(effects), **values)


def _pair(key: str, value: Any, positive: bool) -> tuple[float, float]:
    """A material value for journal and bearing: one number for both, or [journal, bearing]."""
    if isinstance(value, (list, tuple)):
        if len(value) != 2:
            raise LinkageError(key, f"must be one number or [journal, bearing], got {value!r}")
        return _number(f"{key}[0]", value[0], positive=positive), _number(f"{key}[1]", value[1], positive=positive)
    v = _number(key, value, positive=positive)
    return v, v


def _contact(key: str, spec: Mapping[str, Any]) -> dict[str, Any]:
    law, elastic = spec["contact_law"], spec["elastic_law"]
    if law not in CONTACT_LAWS:
        raise LinkageError(f"{key}.contact_law", f"unknown contact law {law!r}; known: {', '.join(CONTACT_LAWS)}")
    if elastic not in ELASTIC_LAWS:
        raise LinkageError(f"{key}.elastic_law", f"unknown elastic law {elastic!r}; known: {', '.join(ELASTIC_LAWS)}")
    poisson = _pair(f"{key}.poisson", spec["poisson"], positive=False)
    if not all(-1.0 < nu < 0.5 for nu in poisson):
        raise LinkageError(f"{key}.poisson", f"must lie in (-1, 0.5), got {spec['poisson']!r}")
    restitution = _number(f"{key}.restitution", spec["restitution"], positive=True)
    if restitution > 1.0:
        raise LinkageError(f"{key}.restitution", f"must lie in (0, 1], got {restitution!r}")
    return {
        "youngs_modulus": _pair(f"{key}.youngs_modulus_Pa", spec["youngs_modulus_Pa"], positive=True),
        "poisson": poisson,
        "restitution": restitution,
        "contact_law": law,
        "elastic_law": elastic,
        "impact_velocity_floor": _number(
            f"{key}.impact_velocity_floor_m_s", spec["impact_velocity_floor_m_s"], positive=True
        ),
    }


def _joints(key: str, spec: Mapping[str, Any], bodies, ground) -> tuple[Joint, ...]:
    out = []
    for name, j in _mapping(key, spec).items():
        k = f"{key}.{name}"
        _only(k, _mapping(k, j), ("journal", "bearing", "clearance"), ("journal", "bearing"))
        journal, bearing = _ref(f"{k}.journal", j["journal"], bodies, ground), _ref(
            f"{k}.bearing", j["bearing"], bodies, ground
        )
        if journal[0] == bearing[0]:
            raise LinkageError(k, f"joins body {journal[0]!r} to itself")
        clearance = _clearance(f"{k}.clearance", j["clearance"]) if j.get("clearance") is not None else None
        if clearance is not None and GROUND in (journal[0], bearing[0]):
            raise LinkageError(
                f"{k}.clearance",
                "a clearance joint with the ground is not supported yet (journal and bearing must be bodies)",
            )
        out.append(Joint(str(name), journal, bearing, clearance))
    return tuple(out)


def _driver(key: str, spec: Mapping[str, Any], bodies, joints) -> Driver:
    _only(
        key, _mapping(key, spec), ("body", "speed_rad_s", "start_angle_deg", "cos_deg", "sin_deg", "rocking"),
        ("body", "speed_rad_s", "start_angle_deg"),
    )
    body = spec["body"]
    if body not in [b.name for b in bodies]:
        raise LinkageError(f"{key}.body", f"unknown body {body!r}; bodies: {', '.join(b.name for b in bodies)}")
    if not any(j.clearance is None and {j.journal[0], j.bearing[0]} == {body, GROUND} for j in joints):
        raise LinkageError(
            f"{key}.body", f"{body!r} is not pinned to the ground by an ideal joint: a driver turns a grounded body"
        )
    cos, sin = spec.get("cos_deg", []), spec.get("sin_deg", [])
    if not isinstance(cos, list) or not isinstance(sin, list) or len(cos) != len(sin):
        raise LinkageError(
            f"{key}.cos_deg", f"cos_deg and sin_deg must be lists of equal length, got {cos!r} and {sin!r}"
        )
    speed = _number(f"{key}.speed_rad_s", spec["speed_rad_s"])
    if abs(speed) < MIN_SPEED:
        raise LinkageError(
            f"{key}.speed_rad_s",
            f"must be at least {MIN_SPEED:g} rad/s either way (its sign is the sense of turning; slower, one turn takes"
            f" more than {2 * math.pi / MIN_SPEED / 3600:.1f} h of simulated time), got {speed:g}",
        )
    rocking = spec.get("rocking", False)
    if not isinstance(rocking, bool):
        raise LinkageError(f"{key}.rocking", f"must be true or false, got {rocking!r}")
    if rocking and not cos:
        raise LinkageError(f"{key}.cos_deg", "a rocking driver needs its motion as a Fourier series (cos_deg, sin_deg)")
    return Driver(str(body), speed,
                  math.radians(_number(f"{key}.start_angle_deg", spec["start_angle_deg"])),
                  tuple(math.radians(_number(f"{key}.cos_deg[{i}]", v)) for i, v in enumerate(cos)),
                  tuple(math.radians(_number(f"{key}.sin_deg[{i}]", v)) for i, v in enumerate(sin)), rocking)


def _springs(key: str, spec: Mapping[str, Any] | None, bodies, ground) -> tuple[Spring, ...]:
    """Springs from a body point to a fixed rest point (optional section)."""
    if spec is None:
        return ()
    out = []
    for name, sp in _mapping(key, spec).items():
        k = f"{key}.{name}"
        _only(
            k, _mapping(k, sp), ("point", "rest_m", "stiffness_N_m", "damping_N_s_m"),
            ("point", "rest_m", "stiffness_N_m"),
        )
        point = _ref(f"{k}.point", sp["point"], bodies, ground)
        if point[0] == GROUND:
            raise LinkageError(f"{k}.point", "must be a point of a body, not of the ground")
        stiffness = _xy(f"{k}.stiffness_N_m", sp["stiffness_N_m"])
        damping = _xy(f"{k}.damping_N_s_m", sp.get("damping_N_s_m", [0.0, 0.0]))
        for label, pair in (("stiffness_N_m", stiffness), ("damping_N_s_m", damping)):
            if min(pair) < 0:
                raise LinkageError(f"{k}.{label}", f"must not be negative, got {list(pair)!r}")
        if max(stiffness) == 0 and max(damping) == 0:
            raise LinkageError(k, "has neither stiffness nor damping")
        out.append(Spring(str(name), point, _xy(f"{k}.rest_m", sp["rest_m"]), stiffness, damping))
    return tuple(out)


def _connected(key: str, bodies: tuple[Body, ...], joints: tuple[Joint, ...]) -> None:
    """Every body reaches the ground through a chain of joints."""
    reached, changed = {GROUND}, True
    while changed:
        changed = False
        for j in joints:
            a, b = j.journal[0], j.bearing[0]
            if (a in reached) != (b in reached):
                reached |= {a, b}
                changed = True
    for b in bodies:
        if b.name not in reached:
            raise LinkageError(f"{key}.bodies.{b.name}", "is not connected to the ground by any chain of joints")


def _mobility(key: str, bodies, joints) -> None:
    """Grübler's count with every joint closed: a driven linkage has none left (3 per body = 2 per joint + the
    driver)."""
    dof = 3 * len(bodies) - 2 * len(joints) - 1
    if dof != 0:
        plural = "s" if abs(dof) != 1 else ""
        what = f"free motion{plural} besides the driver" if dof > 0 else f"redundant constraint{plural}"
        raise LinkageError(
            f"{key}.joints",
            f"the linkage has {abs(dof)} {what} (Grübler: 3 x {len(bodies)} bodies - 2 x "
            f"{len(joints)} joints - 1 driver = {dof}); a driven linkage needs 0",
        )


def assembly_settings(key: str, spec: Mapping[str, Any] | None) -> AssemblySettings:
    """The assembly settings of a description (defaults where absent)."""
    spec = dict(spec or {})
    _only(key, spec, tuple(ASSEMBLY_KEYS))
    defaults = AssemblySettings()
    values = {}
    for name in ASSEMBLY_KEYS:
        if name in spec:
            v = _number(f"{key}.{name}", spec[name], positive=True)
            if name in ("steps_per_turn", "max_iterations"):
                if v != int(v):
                    raise LinkageError(f"{key}.{name}", f"must be a whole number, got {spec[name]!r}")
                v = int(v)
            values[name] = v
    settings = AssemblySettings(**{**defaults.__dict__, **values})
    if not 16 <= settings.steps_per_turn <= 100_000:
        raise LinkageError(
            f"{key}.steps_per_turn", f"must lie in 16..100000 (a size guard), got {settings.steps_per_turn}"
        )
    return settings


def from_config(spec: Mapping[str, Any], key: str = "linkage") -> Linkage:
    """The ``Linkage`` of a config description (see the module's docstring); LinkageError naming the key of the first
    problem.  Topology only: ``check`` also assembles it and follows the turn."""
    spec = _mapping(key, spec)
    _only(key, spec, TOP_KEYS, ("bodies", "ground", "joints", "driver", "output"))
    bodies = _bodies(f"{key}.bodies", spec["bodies"])
    ground = {str(n): _xy(f"{key}.ground.{n}", xy) for n, xy in _mapping(f"{key}.ground", spec["ground"]).items()}
    joints = _joints(f"{key}.joints", spec["joints"], bodies, ground)
    _connected(key, bodies, joints)
    _mobility(key, bodies, joints)
    driver = _driver(f"{key}.driver", spec["driver"], bodies, joints)
    if spec["output"] not in [b.name for b in bodies]:
        raise LinkageError(
            f"{key}.output", f"unknown body {spec['output']!r}; bodies: {', '.join(b.name for b in bodies)}"
        )
    names = {"linkage": key, "driver": f"{key}.driver"}
    return Linkage(bodies, ground, joints, driver, str(spec["output"]),
                   _number(f"{key}.gravity_m_s2", spec.get("gravity_m_s2", STANDARD_GRAVITY), nonnegative=True),
                   _number(f"{key}.baumgarte_per_s", spec.get("baumgarte_per_s", 250.0), positive=True), names,
                   _springs(f"{key}.springs", spec.get("springs"), bodies, ground))


def check(spec: Mapping[str, Any], key: str = "linkage") -> Linkage:
    """``from_config``, then the linkage assembled at its start and followed through one driven turn (LinkageError
    where it does not assemble, locks up or changes branch)."""
    linkage = from_config(spec, key)
    follow_turn(linkage, assembly_settings(f"{key}.assembly", spec.get("assembly")))
    return linkage


def errors(spec: Mapping[str, Any], key: str) -> list[str]:
    """The problems of a description as lines ``key: message`` (empty if it is sound), for config validation."""
    try:
        check(spec, key)
    except LinkageError as exc:
        return [str(exc)]
    except (
        np.linalg.LinAlgError,
        FloatingPointError,
    ) as exc:  # pragma: no cover - a guard; check names the cases it knows
        return [f"{key}: {exc}"]
    return []
