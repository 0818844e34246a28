# SPDX-License-Identifier: MIT
"""Flow along n parallel joints between two heads (tests/python/test_joint_flow*.py): a column of
rock cut by horizontal joints, loaded on top (so the joints close), heads on its left and right
sides. Closed form: every joint carries Q_i = (ρ g / μ) T_i Δh W / L (W: the joint's width across
the flow, 1 m out of plane in 2D; L: the column's width along the flow) with T_i from its closure,
and the joints are the only path; written out here from the cubic law T = (e0 - Δ)³ / 12."""
import numpy as np
from mpi4py import MPI

import rockjoint
from rockjoint import meshes
from rockjoint.fem import JointedRockModel, NewtonOptions
from rockjoint.fem.mesh.distributed_mesh import distribute
from rockjoint.fem.water.joint_flow import Fluid

E, NU = 20e9, 0.25
KNI, VM = 1e10, 1e-3                 # Barton-Bandis K_ni [Pa/m], V_m [m]
APERTURE = 1.2e-3                    # e0: mechanical aperture of the open joint [m]
WIDTH, HEIGHT = 2.0, 3.0             # column [m]: flow along x over WIDTH
HEADS = {"left": 12.0, "right": 2.0}  # [m]
LOAD = 4e6                           # [Pa] on top


def cubic_law(closure):
    """T = e³/12 of the mechanical aperture e = e0 - Δ [m³]."""
    return (APERTURE - np.asarray(closure)) ** 3 / 12.0


def solved_column(dim: int, joint_heights=(1.0, 2.0), mesh_size=0.5, comm=MPI.COMM_WORLD):
    jm = meshes.column(WIDTH, HEIGHT, joint_heights, dim=dim, mesh_size=mesh_size, comm=comm)
    model = JointedRockModel(distribute(jm, comm), rock=(E, NU),
                             joints={f"joint_{i + 1}": rockjoint.BartonBandis(KNI, VM)
                                     for i in range(len(joint_heights))},
                             newton=NewtonOptions(verbose=False), shear_stiffness=1e9)
    model.fix("bottom", "z" if dim == 3 else "y")
    model.fix("left", "x")
    if dim == 3:
        model.fix("front", "y")
    model.add_traction("top", (0.0,) * (dim - 1) + (-LOAD,))
    model.solve()
    return model


def expected_rate(dim: int, joints: int) -> float:
    """Σ_i (ρ g / μ) T_i Δh W / L with every joint closed by Δ(LOAD) (uniform normal stress)."""
    closure = LOAD * VM / (KNI * VM + LOAD)            # Barton-Bandis inverse
    across = WIDTH if dim == 3 else 1.0                 # the box is WIDTH deep in 3D
    drop = HEADS["left"] - HEADS["right"]
    return joints * Fluid().conductivity_factor * cubic_law(closure) * drop * across / WIDTH
