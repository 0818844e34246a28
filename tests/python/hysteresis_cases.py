# SPDX-License-Identifier: MIT
"""The FE column with a hysteretic joint, loaded, unloaded and reloaded (test_fem_hysteresis*.py),
and the closed forms it is checked against: Barton-Bandis inverse on first loading, the branch
inverse Δ = Δ_p + (Δ_m - Δ_p)(σ/σ_m)^(1/m) with Δ_p = r Δ_m below the largest stress reached
(docs/hysteresis.md, H1-H2), written out here independently of the library."""
import numpy as np
import pytest
from mpi4py import MPI

import rockjoint
from rockjoint import meshes
from rockjoint.fem import JointedRockModel, NewtonOptions
from rockjoint.fem.mesh.distributed_mesh import distribute

E, NU = 20e9, 0.25
KNI, VM = 1e10, 1e-3                 # Barton-Bandis K_ni [Pa/m], V_m [m]
R, M = 0.25, 3.0                     # permanent fraction, unloading exponent
PEAK = 8e6                           # [Pa]
FACTORS = (0.5, 1.0, 0.5, 0.01, 0.75, 1.0, 1.25, 0.25)  # load, unload, reload, load further, unload
# (not to exactly 0: there the joint is open at any Δ <= Δ_p with zero stress and zero tangent, an
#  equilibrium that is not unique; at 1 % of the peak the branch fixes the closure near Δ_p)


def virgin_closure(stress):
    return stress * VM / (KNI * VM + stress)


def expected_closures(stresses):
    """Closure after each stress of the path, by (H1-H2) with the virgin inverse above the peak."""
    out, dm, top = [], 0.0, 0.0
    for s in stresses:
        if s >= top:
            d = virgin_closure(s)
            dm, top = max(dm, d), s
        else:
            dp = R * dm
            d = dp + (dm - dp) * (s / top) ** (1.0 / M)
        out.append(d)
    return np.array(out)


def hysteretic_column(comm=MPI.COMM_WORLD, mesh_size=0.25, top_traction=True, **shear):
    """shear: the joint's shear model (default k_s = 1e9 Pa/m; shear_stiffness_ratio=... for k_s ∝ k_n)."""
    jm = meshes.column(1.0, 2.0, (1.0,), dim=2, mesh_size=mesh_size, comm=comm)
    law = rockjoint.NormalHysteresis(rockjoint.BartonBandis(KNI, VM), R, M)
    shear = shear or {"shear_stiffness": 1e9}
    model = JointedRockModel(distribute(jm, comm), rock=(E, NU), joints={"joint_1": law},
                             plane="strain", newton=NewtonOptions(verbose=False), **shear)
    model.fix("bottom", "y")
    model.fix("left", "x")
    if top_traction:
        model.add_traction("top", (0.0, -PEAK))
    return model


def run_cycle(model):
    """(closures [points, steps], top settlement per step) along FACTORS."""
    closures, tops = [], []
    for f in FACTORS:
        res = model.advance(f, load_steps=2)
        joints = res.gather_joints()
        closures.append(joints["closure"] if joints is not None else None)
        tops.append(model.boundary_mean_displacement("top")[1])
    return closures, tops


def check_cycle(closures, tops):
    expected = expected_closures([f * PEAK for f in FACTORS])
    for c, e, f in zip(closures, expected, FACTORS):
        if c is not None:
            np.testing.assert_allclose(c, e, rtol=1e-8, err_msg=f"load factor {f}")
    # nearly unloaded: the top has settled by the plane-strain strain of the rock and the branch
    # closure, which is within 25 % of the permanent closure r Δ_m (x = 0.01^(1/m) of the way up)
    i = FACTORS.index(0.01)
    rock = 0.01 * PEAK * 2.0 * (1 - NU**2) / E
    assert tops[i] == pytest.approx(-(rock + expected[i]), rel=1e-8)
    assert expected[i] - R * virgin_closure(PEAK) < 0.25 * (1 - R) * virgin_closure(PEAK)
