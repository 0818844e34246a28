# SPDX-License-Identifier: MIT
"""Barton's JRC-JCS strength reduced by F (issue 40; joint/joint_strength.hpp): the peak angle's
tangent divided by F at every effective normal stress, tan(φ_r + JRC log10(JCS/σ'_n)) / F.

The block: the unit square cut by a joint dipping θ = 30° through its centre (test_fem_inclined.py),
rollers under the lower block only, a vertical traction p on top: the exact solution is the uniform
uniaxial stress, so every joint point carries σ'_n = p cos²θ and |τ| = p sin θ cos θ, and the
upper block, held by the joint alone, slides when tan φ_F(σ'_n) < tan θ. Its factor of safety in
closed form is F = tan(φ_r + JRC log10(JCS/σ'_n)) / tan θ; the FE search brackets it."""
import math

import pytest

from fe_stack import require_fe
require_fe()

from mpi4py import MPI  # noqa: E402

import rockjoint  # noqa: E402
from rockjoint import meshes  # noqa: E402
from rockjoint.fem import JointedRockModel, NewtonOptions  # noqa: E402
from rockjoint.fem.mechanics.strength_reduction import factor_of_safety, reduced_strength  # noqa: E402
from rockjoint.fem.mesh.distributed_mesh import distribute  # noqa: E402
from rockjoint.joint import JointStrength, StrengthModel  # noqa: E402

THETA, P = math.radians(30.0), 4e6
BARTON = JointStrength(StrengthModel.barton, friction_angle=math.radians(20.0), jrc=12.0, jcs=100e6,
                       dilation_angle=math.radians(5.0))


def peak_angle(sigma):
    """Barton & Choubey's peak angle [rad] at σ'_n [Pa] (below the 70° cap here)."""
    return BARTON.friction_angle + math.radians(BARTON.jrc * math.log10(BARTON.jcs / sigma))


def test_reduced_barton_strength_is_the_peak_divided_by_f_at_every_stress():
    reduced = reduced_strength(BARTON, 1.7)
    assert (reduced.model, reduced.reduction_factor, reduced.jrc, reduced.jcs) == (StrengthModel.barton, 1.7, 12.0, 100e6)
    for sigma in (0.2e6, 1e6, 3e6, 20e6, 90e6):
        assert reduced.shear_strength(sigma) == pytest.approx(sigma * math.tan(peak_angle(sigma)) / 1.7, rel=1e-12)
    # past JCS the roughness term is gone: φ_r alone, reduced
    assert reduced.shear_strength(150e6) == pytest.approx(150e6 * math.tan(BARTON.friction_angle) / 1.7, rel=1e-12)
    # a reduced strength reduced again: the factors multiply
    assert reduced_strength(reduced, 2.0).reduction_factor == pytest.approx(3.4, rel=1e-15)
    with pytest.raises(ValueError, match="reduction_factor"):
        JointStrength(StrengthModel.barton, friction_angle=0.3, jrc=5.0, jcs=50e6, reduction_factor=0.0)


def block_trials(comm):
    """trial(F): the block of the module docstring with the joint's Barton strength reduced by F."""
    jm = meshes.jointed_block((1.0, 1.0), [meshes.Joint((0.5, 0.5), 30.0, 90.0, "j")], dim=2, mesh_size=0.25,
                              comm=comm)
    dmesh = distribute(jm, comm)

    def trial(factor):
        model = JointedRockModel(dmesh, rock=(30e9, 0.2), joints={"j": rockjoint.BartonBandis(1e10, 1e-3)},
                                 shear_stiffness=5e9, strength={"j": reduced_strength(BARTON, factor)},
                                 plane="stress", newton=NewtonOptions(verbose=False))
        model.fix("bottom", "y")
        model.fix("left", "x", block="block_1")
        model.add_traction("top", (0.0, -P))
        model.solve(load_steps=2)
        return model
    return trial


def check_block_factor(comm):
    sigma = P * math.cos(THETA) ** 2                      # 3 MPa on the joint
    expected = math.tan(peak_angle(sigma)) / math.tan(THETA)
    found = factor_of_safety(block_trials(comm), tolerance=0.01)
    assert found.bounded
    assert found.stable <= expected <= found.failed, (found.stable, expected, found.failed)
    assert found.factor == pytest.approx(expected, rel=0.01)
    return found, expected


def test_block_on_a_barton_joint_fails_at_the_closed_form_factor():
    found, expected = check_block_factor(MPI.COMM_WORLD)
    print(f"Barton block: F = {found.factor:.4f} (bracket {found.stable:.4f}-{found.failed:.4f}, "
          f"{len(found.trials)} trials), closed form {expected:.4f}")

