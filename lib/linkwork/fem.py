"""Planar frame finite elements (Euler-Bernoulli, 3 dof per node: u, v, theta).

Small, pure functions: an element stiffness in global coordinates, assembly of
a rigid-jointed frame, and a static solve with fixed degrees of freedom.  SI
units throughout.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]


def frame_element_stiffness(
    youngs_modulus: float, area: float, second_moment: float, start: Sequence[float], end: Sequence[float]
) -> FloatArray:
    """6x6 stiffness of a 2-node planar frame element in global coordinates.

    Parameters: E (Pa), A (m^2), I (m^4), end coordinates (m).  Dof order
    (u1, v1, theta1, u2, v2, theta2); units N/m, N, N m.
    """
    dx, dy = end[0] - start[0], end[1] - start[1]
    length = float(np.hypot(dx, dy))
    if length <= 0.0:
        raise ValueError("frame element has zero length")
    c, s = dx / length, dy / length
    ea, ei = youngs_modulus * area / length, youngs_modulus * second_moment
    l2, l3 = length**2, length**3
    local = np.array(
        [
            [ea, 0, 0, -ea, 0, 0],
            [0, 12 * ei / l3, 6 * ei / l2, 0, -12 * ei / l3, 6 * ei / l2],
            [0, 6 * ei / l2, 4 * ei / length, 0, -6 * ei / l2, 2 * ei / length],
            [-ea, 0, 0, ea, 0, 0],
            [0, -12 * ei / l3, -6 * ei / l2, 0, 12 * ei / l3, -6 * ei / l2],
            [0, 6 * ei / l2, 2 * ei / length, 0, -6 * ei / l2, 4 * ei / length],
        ]
    )
    rot = np.array([[c, s, 0], [-s, c, 0], [0, 0, 1.0]])
    t = np.zeros((6, 6))
    t[:3, :3] = rot
    t[3:, 3:] = rot
    return t.T @ local @ t


def assemble_frame(
    nodes: FloatArray, elements: Sequence[tuple[int, int]], sections: Sequence[tuple[float, float, float]]
) -> FloatArray:
    """Global stiffness of a rigid-jointed frame.

    nodes: (n, 2) coordinates (m); elements: node index pairs; sections:
    (E, A, I) per element.
    """
    n = len(nodes)
    k = np.zeros((3 * n, 3 * n))
    for (i, j), (e, a, inertia) in zip(elements, sections, strict=True):
        ke = frame_element_stiffness(e, a, inertia, nodes[i], nodes[j])
        dofs = np.r_[3 * i : 3 * i + 3, 3 * j : 3 * j + 3]
        k[np.ix_(dofs, dofs)] += ke
    return k


def solve_static(stiffness: FloatArray, load: FloatArray, fixed: Sequence[int]) -> FloatArray:
    """Displacements for K u = f with the listed dofs held at zero."""
    free = np.setdiff1d(np.arange(len(load)), np.asarray(fixed, dtype=int))
    u = np.zeros(len(load))
    u[free] = np.linalg.solve(stiffness[np.ix_(free, free)], load[free])
    return u
