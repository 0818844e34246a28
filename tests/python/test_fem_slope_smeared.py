# SPDX-License-Identifier: MIT
"""Smeared sets reduce their strength as discrete joints do (issue 40, item 2;
strength_reduction.reduced_continuum): a block of rock carrying one horizontal smeared
Barton-Bandis set with a Coulomb strength (φ = 35°, c = 0.2 MPa), its base fixed, loaded on its
other faces by the tractions of the uniform stress

    σ_xx = -p ν/(1 - ν),   σ_yy = -p,   σ_xy = τ     (p = 2 MPa, τ = 0.8 MPa).

That stress is the exact solution for every cell, slipping or not: its elastic strain has ε_xx = 0
in plane strain (the fixed base needs no lateral strain), and the set (normal y) adds only ε_yy
and γ_xy, both compatible with u = (γ y, ε_yy y). The set carries σ_n = p and τ; with its strength
divided by F it holds while τ <= (c + p tan φ)/F, and beyond that nothing bounds its slip under
the applied tractions. So the factor of safety is, in closed form,

    F = (c + p tan φ) / τ   (= tan φ / tan φ_mobilised for c = 0),

and the strength reduction of the smeared block must find it (to its 0.5 % bracket, 1 % asserted)."""
import math

import pytest

from fe_stack import require_fe
require_fe()

from mpi4py import MPI  # noqa: E402

from continuum_cases import E, NU, behaviour  # noqa: E402
from rockjoint import continuum as rj_continuum, meshes  # noqa: E402
from rockjoint.fem import JointedRockModel, NewtonOptions, distribute  # noqa: E402
from rockjoint.fem.mechanics.strength_reduction import factor_of_safety, reduced_continuum  # noqa: E402
from rockjoint.joint import JointStrength, StrengthModel  # noqa: E402

P, TAU = 2e6, 0.8e6
PHI, C = math.radians(35.0), 0.2e6


def test_a_smeared_set_under_uniform_stress_fails_at_its_closed_form_factor():
    strength = JointStrength(StrengthModel.coulomb, friction_angle=PHI, cohesion=C)
    material = rj_continuum.EquivalentContinuum(2, E, NU, [rj_continuum.JointSet([0.0, 1.0], 0.5, behaviour(strength),
                                                                                  label="bedding")])
    dmesh = distribute(meshes.column(1.0, 2.0, (), dim=2, mesh_size=0.5, comm=MPI.COMM_WORLD), MPI.COMM_WORLD)
    sxx = -P * NU / (1 - NU)

    def trial(factor):
        model = JointedRockModel(dmesh, rock=(E, NU), plane="strain",
                                 continuum={"block_1": reduced_continuum(material, factor)},
                                 newton=NewtonOptions(verbose=False, relaxation_max_steps=40))
        model.fix("bottom", "x")
        model.fix("bottom", "y")
        model.add_traction("top", (TAU, -P))
        model.add_traction("right", (sxx, TAU))
        model.add_traction("left", (-sxx, -TAU))
        model.solve(load_steps=2, name="load")
        return model
    found = factor_of_safety(trial, tolerance=0.005)
    expected = (C + P * math.tan(PHI)) / TAU
    print(f"smeared set: F = {found.factor:.4f} ({len(found.trials)} trials), closed form {expected:.4f}")
    assert found.decided_by_strength, found.reason
    assert found.factor == pytest.approx(expected, rel=0.01)


def test_reduced_continuum_divides_every_sets_strength_and_keeps_the_rest():
    strength = JointStrength(StrengthModel.coulomb, friction_angle=PHI, cohesion=C, tensile_strength=1e5)
    sets = [rj_continuum.JointSet([0.0, 1.0], 0.5, behaviour(strength), label="a"),
            rj_continuum.JointSet([1.0, 0.0], 2.0, behaviour(), label="b")]
    reduced = reduced_continuum(rj_continuum.EquivalentContinuum(2, E, NU, sets), 2.0)
    a, b = reduced.sets
    assert (reduced.young, reduced.poisson, a.label, a.spacing, b.label, b.spacing) == (E, NU, "a", 0.5, "b", 2.0)
    assert math.tan(a.behaviour.strength.friction_angle) == pytest.approx(math.tan(PHI) / 2.0, rel=1e-14)
    assert (a.behaviour.strength.cohesion, a.behaviour.strength.tensile_strength) == (C / 2.0, 5e4)
    assert a.behaviour.shear_stiffness == sets[0].behaviour.shear_stiffness
    assert b.behaviour.strength.model == StrengthModel.none
    with pytest.raises(ValueError, match="factor"):
        reduced_continuum(rj_continuum.EquivalentContinuum(2, E, NU, sets), -1.0)
