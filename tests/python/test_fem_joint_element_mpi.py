# SPDX-License-Identifier: MIT
"""The joint element's DOLFINx-side checks on 2 ranks (ghosted pair dofs, the joint's reference
direction reduced over ranks, the pre-closure force balance summed over ranks)."""
import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

import test_fem_joint_element as element  # noqa: E402  (tests/python is on sys.path under pytest)
from mpi_ranks import two_ranks  # noqa: E402


@pytest.mark.mpi
@pytest.mark.parametrize("dim,degree", [(2, 2), (3, 1), (3, 2)])
def test_pair_dofs_on_two_ranks(dim, degree):
    two_ranks()
    element.test_pair_dofs_come_from_the_dofmap_and_pair_coincident_nodes(dim, degree)


@pytest.mark.mpi
@pytest.mark.parametrize("dim", [2, 3])
def test_one_frame_per_joint_on_two_ranks(dim):
    two_ranks()
    element.test_one_tangent_frame_per_joint_on_every_rank(dim)


@pytest.mark.mpi
@pytest.mark.parametrize("dim", [2, 3])
def test_pre_closure_on_two_ranks(dim):
    two_ranks()
    element.test_initial_jump_from_an_in_situ_stress_preloads_the_joint(dim)
