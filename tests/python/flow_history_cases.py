# SPDX-License-Identifier: MIT
"""The column of joint_flow_cases.py with two joints, one hysteretic (NormalHysteresis over
Barton-Bandis), one plain Barton-Bandis, loaded to 4 MPa then unloaded to 1 MPa
(test_joint_flow_history*.py), and the closed forms it is checked against, written out here:
Barton-Bandis' inverse, the branch inverse Δ = r Δ_m + (1 - r) Δ_m (σ/σ_m)^(1/m), and (T2) over
the cubic law e_v = e0 - Δ."""
from mpi4py import MPI

import rockjoint
from rockjoint import meshes
from rockjoint.fem import JointedRockModel, NewtonOptions
from rockjoint.fem.mesh.distributed_mesh import distribute
from joint_flow_cases import APERTURE, E, HEIGHT, KNI, LOAD, NU, VM, WIDTH

R, M, LOSS = 0.25, 3.0, 0.35
UNLOADED = 0.25            # load factor of the second stage


def bb_closure(stress):
    """Barton-Bandis closure [m] at a stress [Pa] (its inverse)."""
    return stress * VM / (KNI * VM + stress)


def branch_transmissivity(closure, peak):
    """(T1-T2) over the cubic law e_v = e0 - Δ, independently of the library."""
    e_peak, e_now = APERTURE - peak, APERTURE - closure
    return (e_peak + (1 - LOSS) * (e_now - e_peak)) ** 3 / 12


def cycled_column(comm=MPI.COMM_WORLD):
    """The column solved at LOAD, then unloaded to UNLOADED x LOAD (two stages)."""
    jm = meshes.column(WIDTH, HEIGHT, (1.0, 2.0), dim=2, mesh_size=0.5, comm=comm)
    joints = {"joint_1": rockjoint.NormalHysteresis(rockjoint.BartonBandis(KNI, VM), R, M),
              "joint_2": rockjoint.BartonBandis(KNI, VM)}
    model = JointedRockModel(distribute(jm, comm), rock=(E, NU), joints=joints,
                             newton=NewtonOptions(verbose=False), shear_stiffness=1e9, plane="strain")
    model.fix("bottom", "y")
    model.fix("left", "x")
    model.add_traction("top", (0.0, -LOAD))
    model.advance(1.0, load_steps=2)
    model.advance(UNLOADED, load_steps=2)
    return model


def unloaded_closures() -> dict:
    """{joint: closure [m]} after unloading to UNLOADED x LOAD (uniform along each joint)."""
    peak = bb_closure(LOAD)
    return {"joint_1": R * peak + (1 - R) * peak * UNLOADED ** (1 / M), "joint_2": bb_closure(UNLOADED * LOAD)}
