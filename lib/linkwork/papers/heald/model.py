"""Heald-motion mechanism of an STB loom as mechanical chains (paper ``heald``, Grigoriev & Kheylo 2021).

The paper prints no parameters, so both chain models are built from a
parameter dict (SI units; every value is labelled sourced/assumed in config):

``m_D``, ``m_E6``, ``m_F6``
    masses of the longitudinal rod DEF (link 6) lumped at D, E, F (kg);
``m_E7``, ``M_G``, ``m_H9``
    bell crank EO3G (7) at E and at G (with rod GH, 9), rod 9 at H (kg);
``m_F8``, ``M_K``, ``m_L10``
    the same for the bell crank FO4K (8) and rod KL (10) (kg);
``M_P``
    the heald frame with its healds (the paper's "M_P"; kg);
``eta7``, ``eta8``
    lever ratios of the bell cranks (velocity at G over velocity at E, ...);
``k_O``
    warp stiffness per frame (N/m); ``c_O`` warp damping (N s/m);
``k_n``
    pin bending stiffness (N/m); ``c_joint`` damping in a joint (N s/m);
``clearance_E``, ``clearance_F`` (m), ``reaction_E``, ``reaction_F`` (N)
    Vulfson's clearance model of the joints E and F (the assumed reactions enter model A only);
``drive_ratio``
    drive frequency over the main-shaft frequency (1, or 1/2 when a frame cycles once in two picks);
``omega_op`` (rad/s), ``stroke_D`` (m)
    operating main-shaft speed and heald stroke at D (amplitude of the first harmonic): model B's reactions are its
    own kinetostatic ones, |R_i| = |Q_i| of the ideal-joint branch under that stroke at that speed.

Model A (the physical linkage): the rigid rod DEF moves with the drive D; the
joints E and F are springs k_tau (Vulfson) into the bell cranks, whose levers
drive G and K; the rigid rods GH, KL and the heald frame make G, K and the frame
P move together; the warp spring holds P.  Model B (the form of eq. 2): three
spring->mass branches hang on the driven node: joint E with the bell-crank-7
side reduced to E, joint F likewise, and the warp spring with the heald frame.

An "ideal" joint is Vulfson's Delta -> 0 limit, the pin's own stiffness k_n:
with both joints rigid the linkage is a redundant closed loop (the frame is
driven from both sides) and the split of force between E and F is undefined.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from ...engines.chains import GROUND, Element, Lever, Network, Parallel, Series, vulfson_stiffness

MODELS = ("A", "B")
JOINTS = ("ideal", "elastic")
#: The parameters each model's chain reads (its joint forces, drive force and resonances move with each of them and
#: with no other): model A takes the assumed reactions, not the kinetostatic state that sets model B's; model B has
#: no mass on its driven node (eq. (2)) and takes its own kinetostatic reactions.
_COMMON = (
    "m_E7", "M_G", "m_H9", "m_F8", "M_K", "m_L10", "M_P", "eta7", "eta8", "k_O", "c_O", "k_n", "c_joint", "clearance_E",
    "clearance_F",
)
MODEL_INPUTS = {"A": ("m_D", "m_E6", "m_F6", *_COMMON, "reaction_E", "reaction_F"),
                "B": (*_COMMON, "operating_speed_rpm", "stroke_D")}


def drive_frequency(p: Mapping[str, float], shaft):
    """The chain's drive frequency (rad/s) at a main-shaft frequency (rad/s): times ``drive_ratio`` (1 if absent)."""
    return p.get("drive_ratio", 1.0) * np.asarray(shaft, dtype=float)


def joint_stiffness(p: Mapping[str, float], joint: str, variant: str) -> float:
    """k_tau of joint E or F (N/m); the ideal variant has no clearance."""
    clearance = 0.0 if variant == "ideal" else p[f"clearance_{joint}"]
    return float(vulfson_stiffness(p[f"reaction_{joint}"], clearance, p["k_n"]))


def reduced_masses(p: Mapping[str, float]) -> tuple[float, float]:
    """Bell-crank sides reduced to E and to F through their levers (kg), used by model B."""
    m_e = p["m_E7"] + p["eta7"] ** 2 * (p["M_G"] + p["m_H9"])
    m_f = p["m_F8"] + p["eta8"] ** 2 * (p["M_K"] + p["m_L10"])
    return m_e, m_f


def kinetostatic_reactions_b(p: Mapping[str, float]) -> tuple[float, float]:
    """Model B's joint reactions from its own kinetostatics (closed form): each joint carries only its own
    branch, a pin (stiffness k_n, damping c_joint) into the reduced mass m_i, so under the heald stroke X at
    omega_op the force is |z X omega^2 m_i / (z - omega^2 m_i)| with z = k_n + j omega c_joint.  Not circular:
    the ideal joint has no clearance, so its stiffness does not depend on the reaction."""
    w, x = drive_frequency(p, p["omega_op"]), p["stroke_D"]
    z = p["k_n"] + 1j * w * p["c_joint"]
    return tuple(float(abs(z * x * w**2 * m / (z - w**2 * m))) for m in reduced_masses(p))


def model_b_parameters(p: Mapping[str, float]) -> dict[str, float]:
    """The parameter set with model B's kinetostatic reactions in place of the assumed ones."""
    r_e, r_f = kinetostatic_reactions_b(p)
    return {**p, "reaction_E": r_e, "reaction_F": r_f}


def model_a(p: Mapping[str, float], variant: str = "elastic") -> Network:
    """The physical linkage as a chain (bridge network: not series/parallel)."""
    k_e, k_f = joint_stiffness(p, "E", variant), joint_stiffness(p, "F", variant)
    els = (
        Element("rod", "mass", "D", GROUND, p["m_D"] + p["m_E6"] + p["m_F6"]),
        Element("joint_E", "spring", "D", "e", k_e),
        Element("joint_E_damping", "damper", "D", "e", p["c_joint"]),
        Element("joint_F", "spring", "D", "f", k_f),
        Element("joint_F_damping", "damper", "D", "f", p["c_joint"]),
        Element("crank7_E", "mass", "e", GROUND, p["m_E7"]),
        Element("crank8_F", "mass", "f", GROUND, p["m_F8"]),
        Element("output", "mass", "P", GROUND, p["M_G"] + p["m_H9"] + p["M_K"] + p["m_L10"] + p["M_P"]),
        Element("warp", "spring", "P", GROUND, p["k_O"]),
        Element("warp_damping", "damper", "P", GROUND, p["c_O"]),
    )
    levers = (
        Lever("lever7", "e", "g", p["eta7"]), Lever("lever8", "f", "k", p["eta8"]), Lever("rod9", "g", "P", 1.0),
        Lever("rod10", "k", "P", 1.0),
    )
    return Network(("D", "e", "f", "g", "k", "P"), els, levers, "D", "velocity")


def node_mass(p: Mapping[str, float]) -> float:
    """Mass on the driven node D (kg): the rod DEF lumped at D, E and F (m_D + m_E6 + m_F6); rigid, it moves with D."""
    return p["m_D"] + p["m_E6"] + p["m_F6"]


def model_b(p: Mapping[str, float], variant: str = "elastic", with_node_mass: bool = False) -> Network:
    """Eq. (2)'s chain: three spring->mass branches on the driven node, which carries no mass.

    ``with_node_mass``: put the rod's masses m_D + m_E6 + m_F6 on the driven node (the chain the linkage gives;
    eq. (2) is then no longer its mobility).  Under a velocity drive the node mass moves only the drive force."""
    p = model_b_parameters(p)
    k_e, k_f = joint_stiffness(p, "E", variant), joint_stiffness(p, "F", variant)
    m_e, m_f = reduced_masses(p)
    els = (
        Element("joint_E", "spring", "D", "e", k_e),
        Element("joint_E_damping", "damper", "D", "e", p["c_joint"]),
        Element("side_E", "mass", "e", GROUND, m_e),
        Element("joint_F", "spring", "D", "f", k_f),
        Element("joint_F_damping", "damper", "D", "f", p["c_joint"]),
        Element("side_F", "mass", "f", GROUND, m_f),
        Element("warp", "spring", "D", "o", p["k_O"]),
        Element("warp_damping", "damper", "D", "o", p["c_O"]),
        Element("frame", "mass", "o", GROUND, p["M_P"]),
    )
    if with_node_mass:
        els = (*els, Element("rod", "mass", "D", GROUND, node_mass(p)))
    return Network(("D", "e", "f", "o"), els, (), "D", "velocity")


def model_b_tree(p: Mapping[str, float], variant: str = "elastic"):
    """Model B without dampers as a series/parallel tree (for eq. (2) and the closed-form route)."""
    p = model_b_parameters(p)
    k_e, k_f = joint_stiffness(p, "E", variant), joint_stiffness(p, "F", variant)
    m_e, m_f = reduced_masses(p)

    def branch(k: float, m: float) -> Series:
        return Series((Element("k", "spring", "a", "b", k), Element("m", "mass", "b", GROUND, m)))

    return Parallel((branch(k_e, m_e), branch(k_f, m_f), branch(p["k_O"], p["M_P"])))


def eq2_mobility(p: Mapping[str, float], omega, variant: str = "elastic"):
    """The paper's eq. (2) with model B's (undamped) parameters.

    Numerator: the branch frequencies w09..w011 = sqrt(k_i / m_i) (velocity resonances);
    denominator: j w (k_E7 + k_F8 + k_O) (w07^2 - w^2)(w08^2 - w^2), where w07, w08 are the
    roots of sum_i k_i prod_{j != i} (w_j^2 - w^2) (force resonances).
    Returns (mobility, numerator frequencies, denominator frequencies).
    """
    p = model_b_parameters(p)
    k_e, k_f = joint_stiffness(p, "E", variant), joint_stiffness(p, "F", variant)
    m_e, m_f = reduced_masses(p)
    k = np.array([k_e, k_f, p["k_O"]])
    wi2 = k / np.array([m_e, m_f, p["M_P"]])
    # sum_i k_i prod_{j!=i} (wj^2 - x) as a polynomial in x = w^2
    poly = np.zeros(3)  # coefficients in x = w^2, highest power first
    for i in range(3):
        others = [wi2[j] for j in range(3) if j != i]
        poly = np.polyadd(poly, float(k[i]) * np.polymul([1.0, -others[0]], [1.0, -others[1]]))
    roots = np.sort(np.real(np.roots(poly)))
    w = np.asarray(omega, dtype=float)
    x = w**2
    num = np.prod([wi2[i] - x for i in range(3)], axis=0)
    den = 1j * w * k.sum() * (roots[0] - x) * (roots[1] - x)
    return num / den, np.sqrt(np.sort(wi2)), np.sqrt(roots)


def eq2_with_node_mass(p: Mapping[str, float], omega, variant: str = "elastic"):
    """Closed form of the mobility (m N^-1 s^-1) of eq. (2)'s chain with the node mass m on the driven node: the mass
    is one more branch in parallel, 1/K = 1/K_2 + j w m, so K = K_2 / (1 + j w m K_2)."""
    k2, _, _ = eq2_mobility(p, omega, variant)
    w = np.asarray(omega, dtype=float)
    return k2 / (1.0 + 1j * w * node_mass(p) * k2)


def eq2_node_mass_difference(p: Mapping[str, float], omega, variant: str = "elastic") -> tuple[float, float]:
    """How far eq. (2) is from the mobility of its chain once the driven node carries the rod's mass (undamped):
    (max over ``omega`` of |K_chain - K_eq2| / |K_eq2|, the frequency in rad/s where it peaks).  K_chain by the
    network solve (route 1 of the engine); eq. (2) by its own closed form.  Zero node masses give round-off."""
    from ...engines.chains import solve_network

    undamped = {**p, "c_joint": 0.0, "c_O": 0.0}
    w = np.asarray(omega, dtype=float)
    k_chain = 1.0 / solve_network(model_b(undamped, variant, with_node_mass=True), w, 1.0).input_force
    k2, _, _ = eq2_mobility(undamped, w, variant)
    rel = np.abs(k_chain - k2) / np.abs(k2)
    i = int(np.nanargmax(rel))
    return float(rel[i]), float(w[i])


def build(model: str, p: Mapping[str, float], variant: str) -> Network:
    if model == "A":
        return model_a(p, variant)
    if model == "B":
        return model_b(p, variant)
    raise ValueError(f"unknown heald model {model!r}; expected one of {MODELS}")
