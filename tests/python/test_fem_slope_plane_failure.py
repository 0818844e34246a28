# SPDX-License-Identifier: MIT
"""Plane failure of a jointed rock slope by strength reduction against limit equilibrium (issue
40, item 4): the FE factor of safety of the slope of slope_cases.py against Hoek & Bray's
(rockjoint.reference.PlaneFailure), computed independently from the block's geometry, within 3 %:
dry and cohesionless (F = tan φ / tan ψ_p), dry with cohesion, the crack half full of water."""
import math

import pytest

from fe_stack import require_fe
require_fe()

from slope_cases import GEOMETRY, H, REFERENCE, slope_mesh, trial_solver  # noqa: E402
from rockjoint.fem.mechanics.strength_reduction import factor_of_safety  # noqa: E402


def test_the_reference_block_is_hoek_and_brays():
    """The block's weight against the chart form of a crack in the upper surface (Hoek & Bray 1981,
    Fig. 6.6): W = ½ γ H² [(1 - (z/H)²) cot ψ_p - cot ψ_f]; dry and cohesionless F = tan φ / tan ψ_p."""
    z, psi_p, psi_f = REFERENCE.crack_depth, math.radians(35.0), math.radians(60.0)
    chart = 0.5 * REFERENCE.unit_weight * H ** 2 * ((1 - (z / H) ** 2) / math.tan(psi_p) - 1 / math.tan(psi_f))
    assert REFERENCE.weight == pytest.approx(chart, rel=1e-12)
    assert REFERENCE.factor_of_safety(math.radians(40.0)) == pytest.approx(math.tan(math.radians(40)) / math.tan(psi_p))


@pytest.mark.parametrize("phi_deg, cohesion, water_depth", [(40.0, 0.0, 0.0), (30.0, 60e3, 0.0),
                                                            (40.0, 60e3, "half")])
def test_strength_reduction_matches_limit_equilibrium(phi_deg, cohesion, water_depth):
    depth = 0.5 * REFERENCE.crack_depth if water_depth == "half" else water_depth
    phi = math.radians(phi_deg)
    expected = REFERENCE.factor_of_safety(phi, cohesion, depth)
    found = factor_of_safety(trial_solver(slope_mesh(), phi, cohesion, depth), tolerance=0.005)
    print(f"φ = {phi_deg}°, c = {cohesion * 1e-3:g} kPa, z_w = {depth:.3g} m: F = {found.factor:.4f} "
          f"(bracket {found.stable:.4f}-{found.failed:.4f}, {len(found.trials)} trials), LE {expected:.4f}, "
          f"{100 * (found.factor / expected - 1):+.2f} %")
    assert found.bounded
    assert found.factor == pytest.approx(expected, rel=0.03)
