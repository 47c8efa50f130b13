"""Kineto-elastodynamics (KED) of the crank-rocker rice transplanter (paper ``transplanter``, Li & Xu 2001).

The rigid motion comes from the shared chain solver: crank AB about A, dyad B-C-D, and the
planting arm BE welded to the coupler at B at a fixed angle to BC.  Each member is then a
chain of beam elements (``frame6`` or the paper's 8-coordinate ``quintic8``) loaded by the
inertia of its own rigid-body motion, F = -M (U''_rigid - g):

* quasi-static: U = K^-1 F at every crank angle (the particular solution of eq. 7);
* dynamic: M U'' + C U' + K U = F integrated by Newmark's average-acceleration rule over
  several revolutions (Rayleigh damping), the last revolution kept as the steady state.

Joints: pins share translations and keep their own slopes; the arm is welded to the coupler
(shared slope); the fixed pivots A, D hold their translations; the drive holds the crank's
slope at A.  With quintic elements the curvature (moment) is zero at the pins and at the free
tip, which with 9 elements on 10 nodes leaves exactly the paper's 35 coordinates.
Stress, eq. (8): sigma = E (h |v''| + |u'|), h = d / 2.  SI units, radians.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ...engines.fem import (
    BeamMesh, assemble, cholesky_solve_batch, element_strain_extremes, gather, local_matrices,
    local_to_global, newmark_history, rotate, scatter_vectors, scatter_weighted, shape_integrals,
)
from ...engines.kinematics import Chain, Dyad, solve_chain

FloatArray = NDArray[np.float64]
MEMBERS = ("crank", "coupler", "rocker", "arm")  # AB, BC, DC, BE (start -> end)
JOINTS = ("A", "B", "C", "D", "E")


@dataclass(frozen=True)
class Transplanter:
    """Geometry and speed: lengths (m), pivot D (m), arm angle between BC and BE (rad), crank speed (rad/s)."""

    crank: float
    coupler: float
    rocker: float
    arm: float
    pivot_d: tuple[float, float]
    arm_angle: float
    arm_side: int = 1
    branch: int = 1
    crank_speed: float = 10 * np.pi

    def __post_init__(self) -> None:
        for name in ("crank", "coupler", "rocker", "arm"):
            value = getattr(self, name)
            if not np.isfinite(value) or value <= 0:
                raise ValueError(f"transplanter {name} length must be positive, got {value!r}")
        for name in ("arm_side", "branch"):
            if getattr(self, name) not in (1, -1):
                raise ValueError(f"transplanter {name} must be +1 or -1, got {getattr(self, name)!r}")

    def chain(self) -> Chain:
        return Chain(
            ground={"A": (0.0, 0.0), "D": tuple(map(float, self.pivot_d))},
            crank_pivot="A",
            crank_tip="B",
            crank_length=self.crank,
            dyads=(Dyad("C", "B", "D", self.coupler, self.rocker, self.branch),),
        )


@dataclass(frozen=True)
class RigidMotion:
    """Joint positions/accelerations (n, 5, 2) in A..E order; member angles, angular velocities and
    accelerations (n, 4) in MEMBERS order; time derivatives for the crank speed of the mechanism."""

    theta: FloatArray
    pos: FloatArray
    acc: FloatArray
    angle: FloatArray
    omega: FloatArray
    alpha: FloatArray


def rigid_motion(mech: Transplanter, theta: ArrayLike) -> RigidMotion:
    """Rigid-body kinematics over crank angles (rad) at the mechanism's constant crank speed."""
    w = mech.crank_speed
    m = solve_chain(mech.chain(), theta)
    crank, coupler, rocker = m.links["A-B"], m.links["B-C"], m.links["D-C"]
    arm_angle = coupler.angle + mech.arm_side * mech.arm_angle
    r = mech.arm * np.stack([np.cos(arm_angle), np.sin(arm_angle)], axis=-1)
    perp = np.stack([-r[..., 1], r[..., 0]], axis=-1)
    b = m.points["B"]
    e_pos = b.pos + r
    e_acc = b.acc * w**2 + (coupler.accel * w**2)[..., None] * perp - ((coupler.rate * w) ** 2)[..., None] * r
    pos = np.stack([m.points["A"].pos, b.pos, m.points["C"].pos, m.points["D"].pos, e_pos], axis=-2)
    acc = np.stack(
        [m.points["A"].acc * w**2, b.acc * w**2, m.points["C"].acc * w**2, m.points["D"].acc * w**2, e_acc], axis=-2
    )
    angle = np.stack([crank.angle, coupler.angle, rocker.angle, arm_angle], axis=-1)
    omega = np.stack([crank.rate, coupler.rate, rocker.rate, coupler.rate], axis=-1) * w
    alpha = np.stack([crank.accel, coupler.accel, rocker.accel, coupler.accel], axis=-1) * w**2
    return RigidMotion(np.asarray(theta, dtype=float), pos, acc, angle, omega, alpha)


MEMBER_ENDS = {"crank": (0, 1), "coupler": (1, 2), "rocker": (3, 2), "arm": (1, 4)}


@dataclass(frozen=True)
class Discretisation:
    """A mesh of the four members: element counts per member and the element kind."""

    mesh: BeamMesh
    member_of: tuple[int, ...]  # member index of every element
    fraction: FloatArray  # (n_nodes, ) position of each node along its member, 0..1
    node_member: tuple[int, ...]  # member carrying each node (joints: any member through it)
    node_ends: tuple[tuple[int, int], ...]  # (start joint, end joint) of the member carrying the node


def discretise(elements_per_member: tuple[int, int, int, int], kind: str = "quintic8") -> Discretisation:
    """Nodes A..E first (0-4), interior nodes after; dof keys as described in the module docstring."""
    curv = kind == "quintic8"
    elements, extra, member_of = [], [], []
    fraction = [0.0, 1.0, 1.0, 0.0, 1.0]
    node_member = [0, 0, 1, 2, 3]
    node_ends = [
        MEMBER_ENDS["crank"], MEMBER_ENDS["crank"], MEMBER_ENDS["coupler"], MEMBER_ENDS["rocker"], MEMBER_ENDS["arm"],
    ]
    next_node = 5
    end_keys = {  # (slope key, curvature key) at the member's start and end joint
        "crank": (("s-drive", "k-crank-A"), ("s-crank-B", None)),
        "coupler": (("s-weld-B", "k-coupler-B"), ("s-coupler-C", None)),
        "rocker": (("s-rocker-D", None), ("s-rocker-C", None)),
        "arm": (("s-weld-B", "k-arm-B"), ("s-arm-E", None)),
    }
    for mi, (name, n_el) in enumerate(zip(MEMBERS, elements_per_member, strict=True)):
        if n_el < 1:
            raise ValueError(f"member {name} needs at least one element, got {n_el}")
        start, end = MEMBER_ENDS[name]
        chain_nodes = [start]
        for k in range(1, n_el):
            chain_nodes.append(next_node)
            fraction.append(k / n_el)
            node_member.append(mi)
            node_ends.append((start, end))
            next_node += 1
        chain_nodes.append(end)
        (s0, k0), (s1, k1) = end_keys[name]
        for k in range(n_el):
            first = (s0, k0) if k == 0 else (f"s-{name}-{k}", f"k-{name}-{k}")
            last = (s1, k1) if k == n_el - 1 else (f"s-{name}-{k + 1}", f"k-{name}-{k + 1}")
            if first[0] == "s-drive":
                first = (None, first[1])  # the drive holds the crank's slope at A
            elements.append((chain_nodes[k], chain_nodes[k + 1]))
            extra.append((first if curv else first[:1], last if curv else last[:1]))
            member_of.append(mi)
    mesh = BeamMesh(kind, next_node, tuple(elements), tuple(extra), frozenset({0, 3}))
    return Discretisation(mesh, tuple(member_of), np.array(fraction), tuple(node_member), tuple(node_ends))


@dataclass(frozen=True)
class Material:
    """Young's modulus (Pa) and density (kg/m^3) of the links."""

    youngs_modulus: float
    density: float


def bar_mass(lengths_m, diameters_m, density_kg_m3: float) -> float:
    """Mass (kg) of solid round bars of the given lengths and diameters (m): rho pi/4 sum(l d^2)."""
    lengths, d = np.asarray(lengths_m, dtype=float), np.asarray(diameters_m, dtype=float)
    return float(density_kg_m3 * np.pi / 4.0 * np.sum(lengths * d**2))


def circle(d: float) -> tuple[float, float]:
    """(area, second moment) of a solid circular section of diameter d (m)."""
    return np.pi * d**2 / 4.0, np.pi * d**4 / 64.0


@dataclass(frozen=True)
class KedResult:
    """Elastic response over crank angles: tip displacement (n, 2) global m; member stress (n, 4) Pa;
    all dofs (n, n_dof); natural frequencies of the first configuration (rad/s)."""

    theta: FloatArray
    tip: FloatArray
    tip_axial: FloatArray
    tip_transverse: FloatArray
    stress: FloatArray
    dofs: FloatArray
    first_frequencies: FloatArray
    periodicity: float
    rayleigh: tuple[float, float] = (0.0, 0.0)  # dynamic: C = alpha M + beta K, (alpha in s^-1, beta in s)


def _element_geometry(mech, disc, motion):
    """Per-element lengths, section properties, directions and nodal rigid accelerations."""
    lengths = np.array([mech.crank, mech.coupler, mech.rocker, mech.arm])
    n_el = len(disc.member_of)
    counts = np.bincount(np.array(disc.member_of), minlength=4)
    el_len = np.array([lengths[m] / counts[m] for m in disc.member_of])
    # node positions and rigid accelerations: affine along each (rigid) member
    start = np.array([e[0] for e in disc.node_ends])
    end = np.array([e[1] for e in disc.node_ends])
    f = disc.fraction[None, :, None]
    node_pos = motion.pos[:, start] * (1 - f) + motion.pos[:, end] * f
    node_acc = motion.acc[:, start] * (1 - f) + motion.acc[:, end] * f
    el_dir = np.stack([motion.angle[:, disc.member_of[e]] for e in range(n_el)], axis=1)
    return el_len, node_pos, node_acc, el_dir


def element_frames(mech, disc, theta) -> tuple[FloatArray, FloatArray, RigidMotion]:
    """(element lengths (m), element directions (n, elements; rad), the rigid motion) over crank angles ``theta``
    (rad): what the stresses and tip displacements are read in, without assembling any matrix."""
    motion = rigid_motion(mech, theta)
    el_len, _, _, el_dir = _element_geometry(mech, disc, motion)
    return el_len, el_dir, motion


def tip_dofs(disc: Discretisation) -> list[int]:
    """Global indices of the x and y translations of the arm tip E (node 4)."""
    _, table = disc.mesh.dof_indices()
    last = table[[k for k, (a, b) in enumerate(disc.mesh.elements) if b == 4][0]]
    return [int(i) for i in last[-(4 if disc.mesh.kind == "quintic8" else 3):][:2]]


@dataclass(frozen=True)
class Frames:
    """What a KED solution reads that depends on the geometry, the mesh and the crank angles only, not on the
    diameters or the material: the rigid motion, element lengths (m) and directions (rad), and each element's matrices
    per unit section property rotated into the global frame at every angle (stiffness per unit E A and per unit E I,
    mass per unit rho A) with its inertia loads per unit rho A (from the rigid accelerations, and per m/s^2 of
    gravity).  Computed once per (mechanism, mesh, angles): every diameter and material a search or an optimiser
    tries reuses it."""

    el_len: FloatArray
    el_dir: FloatArray
    motion: RigidMotion
    stiffness_bases: FloatArray  # (elements, 2, angles, size, size): per unit E A, per unit E I
    mass_bases: FloatArray  # (elements, 1, angles, size, size): per unit rho A
    acceleration_loads: FloatArray  # (elements, angles, size): -M_e U''_rigid per unit rho A (N per kg/m: m^2/s^2)
    gravity_loads: FloatArray  # (elements, angles, size): -M_e (0, 1) per unit rho A and per m/s^2 of gravity (m)


#: Frames of the latest (mechanism, mesh, angles): a job evaluates one or two angle grids many times.
_FRAMES: dict[tuple, tuple[Frames, int]] = {}  # key -> (frames, bytes)
#: Memory bounds (bytes): frames larger than FRAMES_ENTRY_BYTES are not built (the matrices are assembled element by
#: element instead: a fine mesh or angle grid of an accuracy study is solved a few times, and its bases would take a
#: few hundred MB); the cache keeps at most FRAMES_BYTES, the oldest entries going first.  The paper's mesh on 360
#: angles takes about 21 MB.
FRAMES_ENTRY_BYTES = 32 * 2**20
FRAMES_BYTES = 64 * 2**20


def frames_bytes(disc: Discretisation, n_angles: int) -> int:
    """What the ``Frames`` of the mesh ``disc`` on ``n_angles`` crank angles take (bytes): three bases and two loads
    per element and angle."""
    size = 2 * (3 if disc.mesh.kind == "frame6" else 4)
    return 8 * len(disc.member_of) * n_angles * (3 * size * size + 2 * size)


def frames(mech: Transplanter, disc: Discretisation, theta) -> Frames:
    """The ``Frames`` of a mechanism, mesh and crank angles ``theta`` (rad), cached within ``FRAMES_BYTES``."""
    theta = np.asarray(theta, dtype=float)
    key = (mech, disc.mesh, disc.member_of, disc.fraction.tobytes(), disc.node_ends, theta.tobytes())
    if key not in _FRAMES:
        need = frames_bytes(disc, theta.size)
        while _FRAMES and sum(size for _, size in _FRAMES.values()) + need > FRAMES_BYTES:
            _FRAMES.pop(next(iter(_FRAMES)))
        _FRAMES[key] = (_frames(mech, disc, theta), need)
    return _FRAMES[key][0]


def _frames(mech: Transplanter, disc: Discretisation, theta: FloatArray) -> Frames:
    motion = rigid_motion(mech, theta)
    el_len, _, node_acc, el_dir = _element_geometry(mech, disc, motion)
    kind = disc.mesh.kind
    per_end = 3 if kind == "frame6" else 4
    k_bases, m_bases, acc_loads, g_loads = [], [], [], []
    for e, ((i, j), member) in enumerate(zip(disc.mesh.elements, disc.member_of, strict=True)):
        axial_k, axial_m, bend_k, bend_m = shape_integrals(kind, float(el_len[e]))
        t = local_to_global(kind, el_dir[:, e])
        mass = rotate(t, axial_m + bend_m)
        k_bases.append([rotate(t, axial_k), rotate(t, bend_k)])
        m_bases.append([mass])
        rig, down = np.zeros((len(theta), 2 * per_end)), np.zeros(2 * per_end)
        for end, node in enumerate((i, j)):
            o = end * per_end
            rig[:, o], rig[:, o + 1] = node_acc[:, node, 0], node_acc[:, node, 1]
            rig[:, o + 2] = motion.alpha[:, member]
            down[o + 1] = 1.0  # F = -M (U'' - g), g = (0, -gravity): gravity's share is -M (0, 1) gravity
        acc_loads.append(-(mass @ rig[..., None])[..., 0])
        g_loads.append(-(mass @ down))
    return Frames(el_len, el_dir, motion, np.array(k_bases), np.array(m_bases), np.array(acc_loads),
                  np.array(g_loads))


def system_matrices(
    mech: Transplanter,
    disc: Discretisation,
    diameters,
    material: Material,
    theta,
    gravity: float = 0.0,
    mass: str = "all",
    tip_force=(0.0, 0.0),
):
    """(K, M, F, element data) over crank angles: F = -M (U''_rigid - g) assembled element by element, plus an
    external force ``tip_force`` (N, global x and y, the same at every crank angle) at the arm tip E.

    Each element's matrices are its section properties times the cached bases (``frames``), scattered by the dof table
    (``fem.scatter_weighted``; tests/test_transplanter.py checks them against rotating and assembling each element's
    own matrices).  ``mass``: "all" returns the global M at every crank angle, "first" only at the first (the
    quasi-static solution needs it only for the natural frequencies).  Frames above ``FRAMES_ENTRY_BYTES`` (the
    accuracy studies' fine meshes and angle grids) are not built: those matrices come element by element."""
    if frames_bytes(disc, np.size(theta)) > FRAMES_ENTRY_BYTES:
        return system_matrices_by_element(mech, disc, diameters, material, theta, gravity, mass, tip_force)
    fr = frames(mech, disc, theta)
    sections = np.array([circle(diameters[member]) for member in disc.member_of])  # (elements, (A, I))
    n_dof, table = disc.mesh.dof_indices()
    k = scatter_weighted(table, fr.stiffness_bases, material.youngs_modulus * sections, n_dof)
    rho_a = material.density * sections[:, 0]
    m_bases = fr.mass_bases if mass == "all" else fr.mass_bases[:, :, :1]
    m = scatter_weighted(table, m_bases, rho_a[:, None], n_dof)
    loads = rho_a[:, None, None] * (fr.acceleration_loads + gravity * fr.gravity_loads)
    f = scatter_vectors(table, loads, n_dof)
    f[:, tip_dofs(disc)] += np.asarray(tip_force, dtype=float)
    return k, m, f, (fr.el_len, fr.el_dir, fr.motion)


def system_matrices_by_element(
    mech: Transplanter, disc: Discretisation, diameters, material: Material, theta, gravity: float = 0.0,
    mass: str = "all", tip_force=(0.0, 0.0),
):
    """(K, M, F, element data) over crank angles by the direct route: each element's own local matrices
    (``fem.local_matrices``) rotated and assembled (``fem.assemble``), its loads -M_e (U''_rigid - g) added at its
    dofs (``mass`` as in ``system_matrices``).  The independent route the cached bases are tested against, and the
    route of meshes too fine to cache."""
    motion = rigid_motion(mech, np.asarray(theta, dtype=float))
    el_len, _, node_acc, el_dir = _element_geometry(mech, disc, motion)
    kind = disc.mesh.kind
    per_end = 3 if kind == "frame6" else 4
    local = [local_matrices(kind, material.youngs_modulus, *circle(diameters[member]), material.density, el_len[e])
             for e, member in enumerate(disc.member_of)]
    k = assemble(disc.mesh, [kl for kl, _ in local], el_dir)
    m = assemble(disc.mesh, [ml for _, ml in local], el_dir if mass == "all" else el_dir[:1])
    n_dof, table = disc.mesh.dof_indices()
    f = np.zeros((len(motion.theta), n_dof))
    for e, ((i, j), member) in enumerate(zip(disc.mesh.elements, disc.member_of, strict=True)):
        rig = np.zeros((len(motion.theta), 2 * per_end))
        for end, node in enumerate((i, j)):
            o = end * per_end
            rig[:, o], rig[:, o + 1] = node_acc[:, node, 0], node_acc[:, node, 1] + gravity
            rig[:, o + 2] = motion.alpha[:, member]
        m_e = rotate(local_to_global(kind, el_dir[:, e]), local[e][1])
        f_e = -(m_e @ rig[..., None])[..., 0]
        keep = np.flatnonzero(table[e] >= 0)
        np.add.at(f, (slice(None), table[e][keep]), f_e[:, keep])
    f[:, tip_dofs(disc)] += np.asarray(tip_force, dtype=float)
    return k, m, f, (el_len, el_dir, motion)


def _postprocess(mech, disc, diameters, material, u, el_len, el_dir, motion):
    elem = gather(disc.mesh, u)
    t = local_to_global(disc.mesh.kind, el_dir)
    local = np.einsum("cekl,cel->cek", t, elem)
    stress = np.zeros((u.shape[0], 4))
    for e, member in enumerate(disc.member_of):
        strain = element_strain_extremes(disc.mesh.kind, el_len[e], diameters[member] / 2.0, local[:, e])
        stress[:, member] = np.maximum(stress[:, member], material.youngs_modulus * strain)
    tip = u[:, tip_dofs(disc)]
    arm_dir = motion.angle[:, 3]
    tip_axial = tip[:, 0] * np.cos(arm_dir) + tip[:, 1] * np.sin(arm_dir)
    tip_transverse = -tip[:, 0] * np.sin(arm_dir) + tip[:, 1] * np.cos(arm_dir)
    return tip, tip_axial, tip_transverse, stress


def natural_frequencies(k: FloatArray, m: FloatArray, count: int = 4) -> FloatArray:
    """Lowest natural frequencies (rad/s) of one configuration."""
    from scipy.linalg import eigh

    lam = eigh(k, m, eigvals_only=True, subset_by_index=[0, count - 1])
    return np.sqrt(np.clip(lam, 0.0, None))


def ked(
    mech: Transplanter,
    disc: Discretisation,
    diameters,
    material: Material,
    theta: ArrayLike,
    solution: str = "quasi-static",
    gravity: float = 0.0,
    damping_ratio: float = 0.02,
    revolutions: int = 4,
    substeps: int = 1,
    tip_force=(0.0, 0.0),
) -> KedResult:
    """Elastic response of the mechanism over one revolution sampled at ``theta`` (rad, uniform from 0).

    quasi-static: U = K^-1 F at each angle.  dynamic: Newmark (average acceleration) with
    time-varying K, M and Rayleigh damping fitted to ``damping_ratio`` at the first two
    natural frequencies; ``substeps`` steps per grid interval; the last of ``revolutions``
    is returned, and ``periodicity`` is the largest change of the tip displacement between
    the last two revolutions relative to its range.  ``tip_force`` (N, global x, y): an external
    load at the arm tip E, constant over the turn (the paper prints none; zero by default).
    """
    theta = np.asarray(theta, dtype=float)
    if solution == "quasi-static":
        k, m, f, (el_len, el_dir, motion) = system_matrices(
            mech, disc, diameters, material, theta, gravity, mass="first", tip_force=tip_force
        )
        u = cholesky_solve_batch(np.linalg.cholesky(k), f)
        freqs = natural_frequencies(k[0], m[0])
        periodicity, rayleigh = 0.0, (0.0, 0.0)
    elif solution == "dynamic":
        n = theta.size * substeps
        fine = theta[0] + np.arange(n) * (2 * np.pi / n)
        k, m, f, _ = system_matrices(mech, disc, diameters, material, fine, gravity, tip_force=tip_force)
        freqs = natural_frequencies(k[0], m[0])
        w1, w2 = freqs[0], freqs[1]
        a0, a1 = rayleigh_coefficients(damping_ratio, w1, w2)
        rayleigh = (a0, a1)
        c = a0 * m + a1 * k
        dt = (2 * np.pi / n) / mech.crank_speed
        beta, gamma = 0.25, 0.5
        # the step matrix of every angle, factorised once and reused in every revolution
        step_factor = np.linalg.cholesky(m + gamma * dt * c + beta * dt**2 * k)
        ud = np.linalg.solve(k[0], f[0])
        vd = np.zeros_like(ud)
        ad = np.linalg.solve(m[0], f[0] - k[0] @ ud)
        history = newmark_history(step_factor, k, c, f, ud, vd, ad, dt, revolutions * n, beta, gamma)
        # the step that lands on angle index s is history[step] with s = (step + 1) % n
        last = np.roll(history[-n:], 1, axis=0)[::substeps]
        prev = np.roll(history[-2 * n : -n], 1, axis=0)[::substeps]
        u = last
        el_len, el_dir, motion = element_frames(mech, disc, theta)
        tip_l, *_ = _postprocess(mech, disc, diameters, material, last, el_len, el_dir, motion)
        tip_p, *_ = _postprocess(mech, disc, diameters, material, prev, el_len, el_dir, motion)
        scale = max(np.ptp(tip_l, axis=0).max(), 1e-30)
        periodicity = float(np.abs(tip_l - tip_p).max() / scale)
    else:
        raise ValueError(f"unknown solution {solution!r}; expected 'quasi-static' or 'dynamic'")
    tip, tip_axial, tip_transverse, stress = _postprocess(mech, disc, diameters, material, u, el_len, el_dir, motion)
    return KedResult(theta, tip, tip_axial, tip_transverse, stress, u, freqs, periodicity, rayleigh)


def rayleigh_coefficients(damping_ratio: float, w1: float, w2: float) -> tuple[float, float]:
    """(alpha, beta) of C = alpha M + beta K giving the damping ratio ``damping_ratio`` at the natural
    frequencies w1 and w2 (rad/s): zeta(w) = alpha / (2 w) + beta w / 2."""
    return 2 * damping_ratio * w1 * w2 / (w1 + w2), 2 * damping_ratio / (w1 + w2)


def signed_extreme(values: FloatArray) -> float:
    """The value of largest magnitude, with its sign (the paper's 'maximum deformation' -0.0004)."""
    v = np.asarray(values, dtype=float)
    return float(v[np.argmax(np.abs(v))])


def with_speed(mech: Transplanter, crank_speed: float) -> Transplanter:
    return replace(mech, crank_speed=crank_speed)


def modal_quasi_static(k: FloatArray, m: FloatArray, f: FloatArray, modes: int) -> FloatArray:
    """U ~ sum over the lowest ``modes`` mass-normalised modes of phi phi^T F / w^2, per configuration.

    The paper's mode-superposition route to K^-1 F; all modes recover it exactly.
    """
    from scipy.linalg import eigh

    out = np.empty_like(f)
    for c in range(f.shape[0]):
        lam, phi = eigh(k[c], m[c], subset_by_index=[0, modes - 1])
        out[c] = phi @ ((phi.T @ f[c]) / lam)
    return out


def ked_modal(mech, disc, diameters, material, theta, modes: int, gravity: float = 0.0):
    """Quasi-static KED by truncated mode superposition: (tip (n, 2), stress (n, 4))."""
    k, m, f, (el_len, el_dir, motion) = system_matrices(
        mech, disc, diameters, material, np.asarray(theta, dtype=float), gravity
    )
    u = modal_quasi_static(k, m, f, modes)
    tip, _, _, stress = _postprocess(mech, disc, diameters, material, u, el_len, el_dir, motion)
    return tip, stress
