"""Planar multibody dynamics of a four-bar with clearance joints (paper ``clearance``).

kernels: compiled building blocks (constraints, forces, contact laws, film forces).
model: parameters, the generated right-hand side of a scene, integrators, the ideal scene.
"""
