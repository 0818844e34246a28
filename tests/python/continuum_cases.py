# SPDX-License-Identifier: MIT
"""Small models shared by the equivalent-continuum tests (test_fem_continuum*.py): Barton-Bandis
sets smeared in a column or a block, the matching discrete columns, and the closed forms."""
from mpi4py import MPI

import rockjoint
from rockjoint import continuum as rj_continuum, joint as rj_joint, meshes
from rockjoint.fem import JointedRockModel, NewtonOptions, distribute

E, NU = 20e9, 0.25
E_PLANE = E / (1 - NU**2)  # plane-strain modulus
KNI, VM = 1e10, 1e-3       # Barton-Bandis K_ni [Pa/m], V_m [m]
KS = 1e9                   # shear stiffness [Pa/m]
WIDTH, HEIGHT = 1.0, 3.0
QUIET = NewtonOptions(verbose=False, rtol=1e-11)


def bb_closure(stress):
    """Barton-Bandis closure Δ(σ) = σ V_m / (K_ni V_m + σ) (Bandis et al. 1983, closed form)."""
    return stress * VM / (KNI * VM + stress)


def behaviour(strength=None):
    return rj_joint.JointBehaviour(rockjoint.BartonBandis(KNI, VM), shear_stiffness=KS,
                                           strength=strength)


def material(dim, sets):
    """sets: [(normal, spacing)] of Barton-Bandis sets in the rock (E, ν)."""
    c = rj_continuum
    return c.EquivalentContinuum(dim, E, NU, [c.JointSet(list(n), s, behaviour(), label=f"set_{i}")
                                              for i, (n, s) in enumerate(sets)])


def vertical(dim):
    return (0.0, 1.0) if dim == 2 else (0.0, 0.0, 1.0)


def column(dim, joint_heights=(), smeared=None, comm=MPI.COMM_WORLD, mesh_size=0.5, **kw):
    """Column WIDTH × HEIGHT (rollers bottom, left[, front]), Barton-Bandis discrete joints at
    `joint_heights`; smeared: {block name: EquivalentContinuum}."""
    jm = meshes.column(WIDTH, HEIGHT, joint_heights, dim=dim, mesh_size=mesh_size, comm=comm)
    law = rockjoint.BartonBandis(KNI, VM)
    joints = {f"joint_{i + 1}": law for i in range(len(joint_heights))}
    kw.setdefault("newton", QUIET)
    model = JointedRockModel(distribute(jm, comm), rock=(E, NU), joints=joints, shear_stiffness=KS,
                             plane="strain" if dim == 2 else None, continuum=smeared, **kw)
    model.fix("bottom", "y" if dim == 2 else "z")
    model.fix("left", "x")
    if dim == 3:
        model.fix("front", "y")
    return model


def top_load(model, dim, stress):
    t = [0.0] * dim
    t[-1] = -stress
    return model.add_traction("top", t)


def rock_strain(dim, stress):
    """|ε| of the rock under uniaxial stress: plane strain σ/E', 3D σ/E."""
    return stress / (E_PLANE if dim == 2 else E)


def sliding_column(comm=MPI.COMM_WORLD, **newton):
    """A set at 35° with φ = 20° smeared in the column (rollers bottom and left), 2 MPa on top and
    0.5 MPa on the right: the set slides (one slip system, slip monotone). newton: NewtonOptions
    fields over QUIET's."""
    import dataclasses
    import numpy as np
    th = np.radians(35.0)
    strength = rj_joint.JointStrength(rj_joint.StrengthModel.coulomb,
                                              friction_angle=np.radians(20.0))
    c = rj_continuum
    mat = c.EquivalentContinuum(2, E, NU, [c.JointSet([-np.sin(th), np.cos(th)], 0.5, behaviour(strength))])
    model = column(2, smeared={"block_1": mat}, comm=comm, newton=dataclasses.replace(QUIET, **newton))
    top_load(model, 2, 2e6)
    model.add_traction("right", (-0.5e6, 0.0))
    return model


def sliding_answer(model):
    """(top and right faces' mean displacements [m], largest slip [m]) of a sliding_column."""
    import numpy as np
    slip = model.smeared.points[1].set_state(0)["slip"]
    return (model.boundary_mean_displacement("top"), model.boundary_mean_displacement("right"),
            model.comm.allreduce(float(np.abs(slip).max(initial=0.0)), op=MPI.MAX))


def fail_first_newton(monkeypatch):
    """Make the first Newton of the next load step report failure without touching the model, so
    that pseudo-transient continuation solves it; returns the switch ({"first": bool})."""
    from rockjoint.fem.solvers import pseudo_transient
    from rockjoint.fem.solvers.newton import StepReport
    real = pseudo_transient.newton
    calls = {"first": True}

    def newton(problem, load_factor, options, step=1, start=None):
        if calls["first"]:
            calls["first"] = False
            return StepReport(load_factor, reason="failed on purpose")
        return real(problem, load_factor, options, step=step, start=start)
    monkeypatch.setattr(pseudo_transient, "newton", newton)
    return calls
