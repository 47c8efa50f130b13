"""Planar multibody dynamics of any linkage with ideal and clearance revolute joints.

linkage: the description (bodies, ground points, joints with their clearances and effects, driver) and the contact laws.
describe: the description read from config and checked, with the key of any problem named.
assembly: configurations (assembly on a branch, the driven turn, kinematics) and the ideal inverse dynamics.
kernels: compiled building blocks (constraints, forces, contact laws, film forces, small solves).
model: the generated right-hand side of a scene (topology and effects as code, the rest as data).
integrators: the compiled integrators, compiled once and given a scene's right-hand side as a first-class function.
simulate: continuable runs of a compiled scene.  exudyn_route: the same description in Exudyn.
"""

import os

# Compile for a generic x86-64 CPU (no host-specific instructions such as FMA): the compiled scenes then round
# the same on every machine, so the chaotic contact dynamics, and every result built on it, reproduce exactly
# on another computer.  Set NUMBA_CPU_NAME yourself to override (e.g. "host" for a little more speed).
os.environ.setdefault("NUMBA_CPU_NAME", "generic")
