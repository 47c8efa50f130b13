"""Planar multibody dynamics of a four-bar with clearance joints (paper ``clearance``).

kernels: compiled building blocks (constraints, forces, contact laws, film forces).
model: parameters, the generated right-hand side of a scene, integrators, the ideal scene.
"""

import os

# Compile for a generic x86-64 CPU (no host-specific instructions such as FMA): the compiled scenes then round
# the same on every machine, so the chaotic contact dynamics, and every result built on it, reproduce exactly
# on another computer.  Set NUMBA_CPU_NAME yourself to override (e.g. "host" for a little more speed).
os.environ.setdefault("NUMBA_CPU_NAME", "generic")
