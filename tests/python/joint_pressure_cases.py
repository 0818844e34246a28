# SPDX-License-Identifier: MIT
"""A column of rock with one horizontal Barton-Bandis joint under a vertical stress σ, water at
pressure p in the joint (rockjoint.fem.water.joint_pressure), shared by the serial and MPI tests.
The closed forms it is checked against (independent of the code under test):

- closed joint: σ_BB(Δ) + k_r Δ = σ - α p, σ_BB = K_ni Δ / (1 - Δ/V_m) (theory §6); with k_r = 0
  Δ = s V_m / (K_ni V_m + s), s = σ - α p; with k_r > 0 the root of a quadratic;
- open joint (α p > σ, hydraulic jacking): the law carries nothing, k_r Δ = σ - α p (Δ < 0).
"""
import math

from mpi4py import MPI

import rockjoint
from rockjoint import meshes
from rockjoint.fem import JointedRockModel, NewtonOptions, distribute
from rockjoint.fem.water.joint_pressure import set_joint_pressure

E, NU = 20e9, 0.25
KNI, VM = 1e10, 1e-3          # 10 MPa/mm, 1 mm
SIGMA = 5e6                   # the vertical stress on the column [Pa]


def closure(s: float, kr: float = 0.0) -> float:
    """Δ with σ_BB(Δ) + k_r Δ = s: closed forms (see the module docstring)."""
    if s <= 0.0:
        return s / kr                                # open: only the residual spring
    if kr == 0.0:
        return s * VM / (KNI * VM + s)
    # K Δ/(1 - Δ/V) + k Δ = s  ⇔  (k/V) Δ² - (K + k + s/V) Δ + s = 0, the root in (0, V)
    a, b, c = kr / VM, -(KNI + kr + s / VM), s
    return (-b - math.sqrt(b * b - 4 * a * c)) / (2 * a)


def loaded_column(dim: int, comm=MPI.COMM_WORLD, *, rock=(E, NU), shear_stiffness: float = 1e9,
                  mesh_size: float = 0.5, joint_mesh_size=None, residual_stiffness: float = 0.0,
                  alpha: float = 1.0, loaded: bool = True):
    """The 1 m wide, 2 m high column, its joint at z = 1 m, rollers at the bottom and sides, σ on
    top unless not `loaded` (not solved): returns the model."""
    jm = meshes.column(1.0, 2.0, [1.0], dim=dim, mesh_size=mesh_size, joint_mesh_size=joint_mesh_size, comm=comm)
    model = JointedRockModel(distribute(jm, comm), rock=rock, joints={"joint_1": rockjoint.BartonBandis(KNI, VM)},
                             shear_stiffness=shear_stiffness, residual_stiffness=residual_stiffness,
                             effective_stress_coefficient=alpha, plane="strain" if dim == 2 else None,
                             newton=NewtonOptions(verbose=False))
    model.fix("bottom", "y" if dim == 2 else "z")
    model.fix("left", "x")
    if dim == 3:
        model.fix("front", "y")
    if loaded:
        model.add_traction("top", (0.0,) * (dim - 1) + (-SIGMA,))
    return model


def column(dim: int, comm=MPI.COMM_WORLD, residual_stiffness: float = 0.0, alpha: float = 1.0):
    """The loaded column (first stage solved, dry): returns the model."""
    model = loaded_column(dim, comm, residual_stiffness=residual_stiffness, alpha=alpha)
    model.solve(name="load")
    return model


def with_water(model, pressure: float, load_steps: int = 1):
    """The next stage: water at `pressure` [Pa] in the joint; returns the gathered joint state."""
    set_joint_pressure(model, pressure)
    return model.solve(load_steps, name=f"water {pressure * 1e-6:g} MPa").gather_joints()
