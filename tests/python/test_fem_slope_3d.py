# SPDX-License-Identifier: MIT
"""The extruded slope (issue 40, item 1: slopes in 2D and extruded 3D): the plane failure of
slope_cases.py extruded 3 m along the strike (meshes.slope_section(length=3), tetrahedra of 3 m,
1.5 m on the joints, the section meshed alike for the comparison; the
strike held at the front and back faces: plane strain), dry, φ = 40°, c = 0. Its factor of safety
by strength reduction must be the section's (within 1 %: two 1 % brackets, on one F) and Hoek & Bray's
limit equilibrium (3 %, as in 2D). On 2 ranks: test_fem_slope_mpi.py."""
import math

import pytest

from fe_stack import require_fe
require_fe()

from slope_cases import GEOMETRY, REFERENCE, plane_failure_joints, slope_mesh, trial_solver  # noqa: E402
from rockjoint.fem.mechanics.strength_reduction import factor_of_safety  # noqa: E402
from rockjoint.meshes.slope import slope_section  # noqa: E402

PHI = math.radians(40.0)
LENGTH = 3.0
SIZES = (3.0, 1.5)   # element size, and on the joints [m] (3.6k tetrahedra)


def test_the_extruded_slope_has_the_sections_groups_and_blocks():
    section = slope_section(GEOMETRY, plane_failure_joints(), mesh_size=3.0, joint_mesh_size=1.0)
    block = slope_section(GEOMETRY, plane_failure_joints(), mesh_size=3.0, joint_mesh_size=1.0, length=LENGTH)
    assert block.points.shape[1] == 3 and block.cells.shape[1] == 4
    groups = [*section.names["boundaries"].values(), "front", "back"]
    assert sorted(block.names["boundaries"].values()) == sorted(groups)
    assert sorted(block.names["joints"].values()) == ["crack", "plane"]
    assert len(block.names["blocks"]) == len(section.names["blocks"]) == 3
    with pytest.raises(ValueError, match="length"):
        slope_section(GEOMETRY, plane_failure_joints(), mesh_size=3.0, length=0.0)


def test_the_extruded_plane_failure_has_the_sections_factor_of_safety():
    section = factor_of_safety(trial_solver(slope_mesh(*SIZES), PHI, 0.0), tolerance=0.01)
    block = factor_of_safety(trial_solver(slope_mesh(*SIZES, length=LENGTH), PHI, 0.0), tolerance=0.01)
    expected = REFERENCE.factor_of_safety(PHI)
    print(f"plane failure, φ = 40°, dry: F = {block.factor:.4f} (3D, {len(block.trials)} trials), "
          f"{section.factor:.4f} (2D), limit equilibrium {expected:.4f}")
    assert block.decided_by_strength and section.decided_by_strength
    assert block.factor == pytest.approx(section.factor, rel=0.01)
    assert block.factor == pytest.approx(expected, rel=0.03)
    assert len(block.moving) == 1
