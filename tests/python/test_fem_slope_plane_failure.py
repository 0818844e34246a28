# SPDX-License-Identifier: MIT
"""Plane failure of a jointed rock slope by strength reduction against limit equilibrium (issue
40, item 4): the FE factor of safety of the slope of slope_cases.py against Hoek & Bray's
(rockjoint.reference.PlaneFailure), computed independently from the block's geometry, within 3 %:
dry and cohesionless (F = tan φ / tan ψ_p), dry with cohesion, the crack half full and full of
water (and the plane's water with it); a slope without a joint to fail says it has no factor."""
import math

import pytest

from fe_stack import require_fe
require_fe()

import numpy as np  # noqa: E402

from slope_cases import CRACK_X, GEOMETRY, H, REFERENCE, block_at, crack_foot_y, slope_mesh, trial_solver  # noqa: E402
from rockjoint.fem.mechanics.strength_reduction import factor_of_safety  # noqa: E402


def test_the_reference_block_is_hoek_and_brays():
    """The block's weight against the chart form of a crack in the upper surface (Hoek & Bray 1981,
    Fig. 6.6): W = ½ γ H² [(1 - (z/H)²) cot ψ_p - cot ψ_f]; dry and cohesionless F = tan φ / tan ψ_p."""
    z, psi_p, psi_f = REFERENCE.crack_depth, math.radians(35.0), math.radians(60.0)
    chart = 0.5 * REFERENCE.unit_weight * H ** 2 * ((1 - (z / H) ** 2) / math.tan(psi_p) - 1 / math.tan(psi_f))
    assert REFERENCE.weight == pytest.approx(chart, rel=1e-12)
    assert REFERENCE.factor_of_safety(math.radians(40.0)) == pytest.approx(math.tan(math.radians(40)) / math.tan(psi_p))


@pytest.mark.parametrize("phi_deg, cohesion, water_depth", [(40.0, 0.0, 0.0), (30.0, 60e3, 0.0),
                                                            (40.0, 60e3, "half"), (40.0, 100e3, "full")])
def test_strength_reduction_matches_limit_equilibrium(phi_deg, cohesion, water_depth):
    depth = {"half": 0.5 * REFERENCE.crack_depth, "full": REFERENCE.crack_depth}.get(water_depth, water_depth)
    phi = math.radians(phi_deg)
    expected = REFERENCE.factor_of_safety(phi, cohesion, depth)
    found = factor_of_safety(trial_solver(slope_mesh(), phi, cohesion, depth), tolerance=0.005)
    print(f"φ = {phi_deg}°, c = {cohesion * 1e-3:g} kPa, z_w = {depth:.3g} m: F = {found.factor:.4f} "
          f"(bracket {found.stable:.4f}-{found.failed:.4f}, {len(found.trials)} trials), LE {expected:.4f}, "
          f"{100 * (found.factor / expected - 1):+.2f} %")
    assert found.bounded
    assert found.factor == pytest.approx(expected, rel=0.03)
    # the mechanism: the block above the plane, toe to crack, and nothing else
    assert found.moving == [wedge_block()], found.block_motion


def wedge_block():
    """The name of the block holding the centroid of the limit-equilibrium block (toe, crest, the
    crack's top and foot)."""
    top = GEOMETRY.base + H
    corners = np.array([GEOMETRY.toe, GEOMETRY.crest, (CRACK_X, top), (CRACK_X, crack_foot_y())])
    return block_at(corners.mean(axis=0))


def test_a_slope_with_nothing_to_fail_says_so():
    """The intact slope (elastic rock, no joint) holds at every F: no factor, bounded False."""
    from mpi4py import MPI
    from rockjoint.fem import JointedRockModel, NewtonOptions, distribute
    from rockjoint.meshes.slope import slope_section
    from slope_cases import DENSITY
    dmesh = distribute(slope_section(GEOMETRY, [], mesh_size=5.0, comm=MPI.COMM_WORLD), MPI.COMM_WORLD)

    def trial(factor):
        model = JointedRockModel(dmesh, rock=(10e9, 0.25), density=DENSITY, plane="strain",
                                 newton=NewtonOptions(verbose=False))
        model.fix("bottom", "x")
        model.fix("bottom", "y")
        model.solve(name="gravity")
    found = factor_of_safety(trial, largest=8.0)
    assert not found.bounded and found.failed is None and found.factor == 8.0
    assert [f for f, held, _ in found.trials] == [1.0, 2.0, 4.0, 8.0]


def test_reduced_strength_divides_tan_phi_c_and_t():
    from rockjoint.fem.mechanics.strength_reduction import reduced_strength
    from rockjoint.joint import JointStrength, StrengthModel
    s = JointStrength(StrengthModel.coulomb, friction_angle=math.radians(40), cohesion=1e5, tensile_strength=5e4,
                      dilation_angle=math.radians(10))
    r = reduced_strength(s, 2.0)
    assert math.tan(r.friction_angle) == pytest.approx(math.tan(math.radians(40)) / 2.0, rel=1e-14)
    assert (r.cohesion, r.tensile_strength, r.dilation_angle) == (5e4, 2.5e4, pytest.approx(math.radians(10)))
    assert reduced_strength(s, 10.0).dilation_angle == pytest.approx(math.atan(math.tan(math.radians(40)) / 10))
    with pytest.raises(ValueError, match="factor"):
        reduced_strength(s, 0.0)
    # F < 1 raises the strength, but T stays within the apex c / tan φ (the same for every F)
    apex = 1e5 / math.tan(math.radians(40))
    assert reduced_strength(s, 0.5).tensile_strength == pytest.approx(1e5)           # 5e4 / 0.5, below the apex
    assert reduced_strength(s, 0.25).tensile_strength == pytest.approx(apex, rel=1e-14)  # 2e5 capped at 1.19e5
    # Barton's is reduced in C++ at every normal stress (test_fem_barton_reduction.py)
    barton = reduced_strength(JointStrength(StrengthModel.barton, friction_angle=0.5, jrc=10.0, jcs=50e6), 1.5)
    assert barton.reduction_factor == 1.5 and barton.friction_angle == 0.5
