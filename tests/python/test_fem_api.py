# SPDX-License-Identifier: MIT
"""JointedRockModel input checks (clear errors naming what is available) and XDMF output."""
import os
import xml.etree.ElementTree as ET

import meshio
import numpy as np
import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

from mpi4py import MPI  # noqa: E402

import rockjoint  # noqa: E402
from rockjoint import meshes  # noqa: E402
from rockjoint.fem import JointedRockModel, NewtonOptions  # noqa: E402
from rockjoint.fem.mesh.distributed_mesh import distribute  # noqa: E402


@pytest.fixture(scope="module")
def dmesh():
    jm = meshes.column(1.0, 2.0, (1.0,), dim=2, mesh_size=0.5, comm=MPI.COMM_WORLD)
    return distribute(jm, MPI.COMM_WORLD)


LAW = rockjoint.BartonBandis(1e10, 1e-3)


def test_unknown_and_missing_names_are_listed(dmesh):
    with pytest.raises(ValueError, match=r"unknown block.*'granite'.*available blocks: \['block_1', 'block_2'\]"):
        JointedRockModel(dmesh, rock={"granite": (1e10, 0.2)}, joints={"joint_1": LAW})
    with pytest.raises(ValueError, match=r"no \(E, nu\) for block\(s\) \['block_2'\]"):
        JointedRockModel(dmesh, rock={"block_1": (1e10, 0.2)}, joints={"joint_1": LAW})
    with pytest.raises(ValueError, match=r"no closure law for joint\(s\) \['joint_1'\]"):
        JointedRockModel(dmesh, rock=(1e10, 0.2), joints={})
    with pytest.raises(ValueError, match=r"unknown joint.*'fault'.*available joints: \['joint_1'\]"):
        JointedRockModel(dmesh, rock=(1e10, 0.2), joints={"joint_1": LAW, "fault": LAW})
    model = JointedRockModel(dmesh, rock=(1e10, 0.2), joints={"joint_1": LAW})
    with pytest.raises(ValueError, match=r"unknown boundary 'roof'.*\['bottom', 'left', 'right', 'top'\]"):
        model.fix("roof", "y")
    with pytest.raises(ValueError, match="unknown boundary"):
        model.add_traction("roof", (0.0, 1.0))
    with pytest.raises(ValueError, match="unknown block"):
        model.fix("bottom", "y", block="block_9")


def test_bad_parameters_name_the_parameter(dmesh):
    with pytest.raises(ValueError, match="Young's modulus E = -1"):
        JointedRockModel(dmesh, rock=(-1.0, 0.2), joints={"joint_1": LAW})
    with pytest.raises(ValueError, match="Poisson's ratio nu = 0.5"):
        JointedRockModel(dmesh, rock=(1e10, 0.5), joints={"joint_1": LAW})
    with pytest.raises(ValueError, match="shear_stiffness"):
        JointedRockModel(dmesh, rock=(1e10, 0.2), joints={"joint_1": LAW}, shear_stiffness=-1.0)
    with pytest.raises(ValueError, match="closure law"):
        JointedRockModel(dmesh, rock=(1e10, 0.2), joints={"joint_1": 3.0})
    with pytest.raises(ValueError, match="plane"):
        JointedRockModel(dmesh, rock=(1e10, 0.2), joints={"joint_1": LAW}, plane="axisymmetric")
    model = JointedRockModel(dmesh, rock=(1e10, 0.2), joints={"joint_1": LAW})
    with pytest.raises(ValueError, match="traction must be 2 finite components"):
        model.add_traction("top", (0.0, np.nan))
    with pytest.raises(ValueError, match="support component 'z'"):
        model.fix("bottom", "z")


def test_write_xdmf_displacement_and_joint_points(dmesh, tmp_path):
    model = JointedRockModel(dmesh, rock=(1e10, 0.2), joints={"joint_1": LAW}, shear_stiffness=1e9,
                             newton=NewtonOptions(verbose=False))
    model.fix("bottom", "y")
    model.fix("left", "x")
    model.add_traction("top", (0.0, -2e6))
    with pytest.raises(RuntimeError, match="solve"):
        model.write_xdmf(str(tmp_path / "early.xdmf"))
    sol = model.solve()
    path = str(tmp_path / "column.xdmf")
    written = model.write_xdmf(path)
    assert written == [path, str(tmp_path / "column_joints.xdmf")]
    assert os.path.exists(path) and os.path.exists(str(tmp_path / "column.h5"))
    root = ET.parse(written[1]).getroot()
    grid = root.find("Domain/Grid")
    n = int(grid.find("Topology").get("NumberOfElements"))
    assert n == len(sol.gather_joints()["closure"]) > 0
    assert grid.find("Topology").get("TopologyType") == "Polyvertex"
    assert os.path.exists(str(tmp_path / "column_joints.h5"))  # heavy data in HDF5
    closure = meshio.read(written[1]).point_data["closure_m"]
    assert closure.shape == (n,)
    np.testing.assert_allclose(closure, LAW.closure_at_stress(2e6), rtol=1e-8)


def test_p2_column_matches_closed_form(dmesh):
    """P2 displacement with the nodal (Simpson) joint rule: exact for the uniform column."""
    model = JointedRockModel(dmesh, element_degree=2, rock=(10e9, 0.2), joints={"joint_1": LAW},
                             shear_stiffness=1e9, newton=NewtonOptions(verbose=False))
    model.fix("bottom", "y")
    model.fix("left", "x")
    p = 3e6
    model.add_traction("top", (0.0, -p))
    model.solve()
    ref = -(p * 2.0 * (1 - 0.2**2) / 10e9 + LAW.closure_at_stress(p))
    assert model.boundary_mean_displacement("top")[1] == pytest.approx(ref, rel=1e-8)


def test_p2_3d_column_matches_closed_form():
    """P2 in 3D: nodal rule on the 6-node facet (edge midpoints carry the joint, vertices weight 0)."""
    jm = meshes.column(1.0, 2.0, (1.0,), dim=3, mesh_size=0.5, comm=MPI.COMM_WORLD)
    model = JointedRockModel(distribute(jm, MPI.COMM_WORLD), element_degree=2, rock=(10e9, 0.2),
                             joints={"joint_1": LAW}, shear_stiffness=1e9, plane=None,
                             newton=NewtonOptions(verbose=False))
    model.fix("bottom", "z")
    model.fix("left", "x")
    model.fix("front", "y")
    p = 3e6
    model.add_traction("top", (0.0, 0.0, -p))
    sol = model.solve()
    ref = -(p * 2.0 / 10e9 + LAW.closure_at_stress(p))
    assert model.boundary_mean_displacement("top")[2] == pytest.approx(ref, rel=1e-8)
    assert sol.gather_joints()["closure"].shape[0] == 6 * MPI.COMM_WORLD.allreduce(model.interface.num_pairs)


def test_intact_block_solves_and_writes_xdmf_without_joint_file(tmp_path):
    """The intact specimen beside the jointed one (every demo has one): no joints, no joint
    file, and the top settlement is the elastic closed form σH(1-ν²)/E (plane strain)."""
    intact = distribute(meshes.jointed_block((1.0, 2.0), [], dim=2, mesh_size=0.5, comm=MPI.COMM_WORLD),
                        MPI.COMM_WORLD)
    model = JointedRockModel(intact, rock=(1e10, 0.2), joints={}, newton=NewtonOptions(verbose=False))
    model.fix("bottom", "y")
    model.fix("left", "x")
    model.add_traction("top", (0.0, -2e6))
    sol = model.solve()
    assert model.boundary_mean_displacement("top")[1] == pytest.approx(-2e6 * 2.0 * (1 - 0.2**2) / 1e10,
                                                                       rel=1e-8)
    assert sol.newton_iterations == 1   # a linear model: one solve meets the residual tolerance
    path = str(tmp_path / "intact.xdmf")
    assert model.write_xdmf(path) == [path]
    assert not os.path.exists(str(tmp_path / "intact_joints.xdmf"))


def test_intact_block_with_cg_needs_one_newton_iteration():
    """CG + GAMG stops on the true residual, so one linear solve of the (linear) intact model
    meets Newton's tolerance; the settlement is the plane-strain closed form σH(1-ν²)/E."""
    intact = distribute(meshes.jointed_block((1.0, 2.0), [], dim=2, mesh_size=0.1, comm=MPI.COMM_WORLD),
                        MPI.COMM_WORLD)
    model = JointedRockModel(intact, rock=(1e10, 0.2), joints={}, linear_solver="iterative",
                             newton=NewtonOptions(verbose=False))
    model.fix("bottom", "y")
    model.fix("left", "x")
    model.add_traction("top", (0.0, -2e6))
    sol = model.solve()
    assert sol.newton_iterations == 1
    assert model.boundary_mean_displacement("top")[1] == pytest.approx(-2e6 * 2.0 * (1 - 0.2**2) / 1e10,
                                                                       rel=1e-8)


def test_petsc_options_and_prefix_reach_the_linear_solver(dmesh):
    """DOLFINx convention: petsc_options without dashes override the defaults; the prefix is the
    user's. A GMRES + Jacobi solve gives the same closed-form answer as the default solver."""
    model = JointedRockModel(dmesh, rock=(1e10, 0.2), joints={"joint_1": LAW}, shear_stiffness=1e9,
                             linear_solver="iterative", options_prefix="column_",
                             petsc_options={"ksp_type": "gmres", "pc_type": "jacobi",
                                            "ksp_rtol": 1e-12, "ksp_max_it": 5000},
                             newton=NewtonOptions(verbose=False))
    model.fix("bottom", "y")
    model.fix("left", "x")
    p = 3e6
    model.add_traction("top", (0.0, -p))
    model.solve()
    ksp = model.linear_solver.ksp
    assert (ksp.getOptionsPrefix(), ksp.getType(), ksp.getPC().getType()) == ("column_", "gmres", "jacobi")
    ref = -(p * 2.0 * (1 - 0.2**2) / 1e10 + LAW.closure_at_stress(p))
    assert model.boundary_mean_displacement("top")[1] == pytest.approx(ref, rel=1e-8)
    for bad in ({"-ksp_type": "cg"}, ["ksp_type"]):
        with pytest.raises(ValueError, match="petsc_options"):
            JointedRockModel(dmesh, rock=(1e10, 0.2), joints={"joint_1": LAW}, petsc_options=bad)


def test_direct_solver_factorises_a_symmetric_jacobian_by_cholesky(dmesh):
    """Constant joint shear stiffness: J is symmetric, MUMPS Cholesky; k_s proportional to k_n:
    not symmetric, LU. Both give the column's closed-form settlement."""
    p = 3e6
    ref = -(p * 2.0 * (1 - 0.2**2) / 1e10 + LAW.closure_at_stress(p))
    for shear, factor in (({"shear_stiffness": 1e9}, "cholesky"),
                          ({"shear_stiffness_ratio": 0.1}, "lu")):
        model = JointedRockModel(dmesh, rock=(1e10, 0.2), joints={"joint_1": LAW},
                                 linear_solver="direct", newton=NewtonOptions(verbose=False), **shear)
        model.fix("bottom", "y")
        model.fix("left", "x")
        model.add_traction("top", (0.0, -p))
        model.solve()
        assert model.linear_solver.ksp.getPC().getType() == factor
        assert model.boundary_mean_displacement("top")[1] == pytest.approx(ref, rel=1e-8)
