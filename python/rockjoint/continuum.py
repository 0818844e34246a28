# SPDX-License-Identifier: MIT
"""Joint sets smeared into the rock, without the FE stack: the equivalent-continuum material
(C++ `continuum/`, bound as `rockjoint._rockjoint.continuum`; needs neither PETSc nor DOLFINx).
Each set is a unit normal, a spacing and a per-point joint behaviour (`rockjoint.joint`); the
material adds the sets' compliances to the rock's (docs/equivalent-continuum.md). The FE side,
`rockjoint.fem` (`JointedRockModel(continuum=...)`), evaluates it at every quadrature
point; a point driver can call it directly.

    from rockjoint import BartonBandis
    from rockjoint.joint import JointBehaviour
    from rockjoint.continuum import EquivalentContinuum, JointSet
    b = JointBehaviour(BartonBandis(1e10, 1e-3), shear_stiffness=1e9)
    material = EquivalentContinuum(2, 30e9, 0.25, [JointSet([0.0, 1.0], 0.5, b, label="bedding")])
"""
from __future__ import annotations

from ._rockjoint import continuum as _cpp

#: a joint set smeared in the rock: unit normal [-], spacing [m] (> 0), joint.JointBehaviour, label
JointSet = _cpp.JointSet
#: rock elasticity (gdim, E [Pa], ν) + smeared joint sets; Voigt strains with engineering shear
EquivalentContinuum = _cpp.EquivalentContinuum
#: the path-dependent state of an EquivalentContinuum at n material points (commit / revert)
ContinuumPoints = _cpp.ContinuumPoints

__all__ = ["ContinuumPoints", "EquivalentContinuum", "JointSet"]
