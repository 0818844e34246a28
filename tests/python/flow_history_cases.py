# SPDX-License-Identifier: MIT
"""The column of joint_flow_cases.py with two joints, one hysteretic (NormalHysteresis over
Barton-Bandis), one plain Barton-Bandis, loaded to 4 MPa then unloaded to 1 MPa
(test_joint_flow_history*.py), and the closed forms it is checked against, written out here:
Barton-Bandis' inverse, the branch inverse Δ = r Δ_m + (1 - r) Δ_m (σ/σ_m)^(1/m), and (T2) over
the cubic law e_v = e0 - Δ."""
import numpy as np
from mpi4py import MPI

import rockjoint
from rockjoint import meshes
from rockjoint.fem import JointedRockModel, NewtonOptions
from rockjoint.fem.mesh.distributed_mesh import distribute
from joint_flow_cases import APERTURE, E, HEADS, HEIGHT, KNI, LOAD, NU, VM, WIDTH

R, M, LOSS = 0.25, 3.0, 0.35
UNLOADED = 0.25            # load factor of the second stage


def bb_closure(stress):
    """Barton-Bandis closure [m] at a stress [Pa] (its inverse)."""
    return stress * VM / (KNI * VM + stress)


def branch_transmissivity(closure, peak):
    """(T1-T2) over the cubic law e_v = e0 - Δ, independently of the library."""
    e_peak, e_now = APERTURE - peak, APERTURE - closure
    return (e_peak + (1 - LOSS) * (e_now - e_peak)) ** 3 / 12


def column_model(top_load: float, comm=MPI.COMM_WORLD):
    """(model, the top traction's handle): the column with its hysteretic joint_1 and plain
    joint_2, supported, `top_load` [Pa] on top (not solved)."""
    jm = meshes.column(WIDTH, HEIGHT, (1.0, 2.0), dim=2, mesh_size=0.5, comm=comm)
    joints = {"joint_1": rockjoint.NormalHysteresis(rockjoint.BartonBandis(KNI, VM), R, M),
              "joint_2": rockjoint.BartonBandis(KNI, VM)}
    model = JointedRockModel(distribute(jm, comm), rock=(E, NU), joints=joints,
                             newton=NewtonOptions(verbose=False), shear_stiffness=1e9, plane="strain")
    model.fix("bottom", "y")
    model.fix("left", "x")
    return model, model.add_traction("top", (0.0, -top_load))


def cycled_column(comm=MPI.COMM_WORLD):
    """The column solved at LOAD, then unloaded to UNLOADED x LOAD (two stages)."""
    model, _ = column_model(LOAD, comm)
    model.advance(1.0, load_steps=2)
    model.advance(UNLOADED, load_steps=2)
    return model


def unloaded_closures() -> dict:
    """{joint: closure [m]} after unloading to UNLOADED x LOAD (uniform along each joint)."""
    peak = bb_closure(LOAD)
    return {"joint_1": R * peak + (1 - R) * peak * UNLOADED ** (1 / M), "joint_2": bb_closure(UNLOADED * LOAD)}


def coupled_twice(comm=MPI.COMM_WORLD):
    """Two successive two-way coupled water solves of the column (issue 41 follow-up): solved dry
    at 1 MPa, then coupled with HEADS at LOAD (its first iterate is the dry column at LOAD, a
    closure no accepted state reaches: the water opens the joints), then coupled again unloaded
    to 2 MPa (below the peak: on the branch). Returns (model, network of the second solve, the
    accepted stages: the dry stage and the last iterate of each coupled solve)."""
    from rockjoint.flow import transmissivity_law
    from rockjoint.fem.water.coupled import coupled_steady
    model, top = column_model(1e6, comm)
    accepted = [model.solve(name="dry")]
    law = transmissivity_law("hydraulic_history", initial_aperture=APERTURE, hydraulic_loss=LOSS)
    laws = {"joint_1": law, "joint_2": law}
    top.value = (0.0, -LOAD)
    coupled_steady(model, laws, HEADS, name="first")
    accepted.append(model.solution)
    top.value = (0.0, -2e6)
    network = coupled_steady(model, laws, HEADS, name="second").network
    accepted.append(model.solution)
    return model, network, accepted


def check_coupled_twice(model, network, accepted):
    """Δ_m after two coupled solves is the largest closure of the accepted states only (the dry
    stage and the last iterate of each coupled solve), computed here from their closures; the
    first coupled solve's first iterate (dry at 4 MPa) closes the joints further, and counting it
    (the stages' maximum of before) would change Δ_m and T. Returns the overshoot [m]."""
    closures = [np.asarray(r.gather_joints()["closure"], dtype=float) for r in accepted]
    peak = np.maximum.reduce(closures)
    every = np.maximum.reduce([np.asarray(r.gather_joints()["closure"], dtype=float) for r in model.stages])
    overshoot = float(np.max(every - peak))
    assert overshoot > 1e-6            # the premise: an iterate reached more than any accepted state
    state = model.solution.gather_joints()
    closure = np.asarray(state["closure"], dtype=float)
    assert np.all(closure < peak)      # unloaded to 2 MPa: on the branch, where Δ_m matters
    np.testing.assert_allclose(state["maximum_closure"], peak, rtol=1e-12)   # no dilation here
    np.testing.assert_allclose(network.point_transmissivity, branch_transmissivity(closure, peak), rtol=1e-9)
    return overshoot

