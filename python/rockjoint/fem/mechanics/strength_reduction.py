# SPDX-License-Identifier: MIT
"""Factor of safety by strength reduction (issue 40; Dawson, Roth & Drescher 1999 for continua,
the discontinuum form of UDEC/3DEC): every joint's strength divided by a trial F,

    tan φ_F = tan φ / F,   c_F = c / F,   T_F = T / F   (and ψ_F = min(ψ, φ_F)),

the model built and solved through its stages at each trial; a trial fails when its solve finds
no equilibrium (Newton's load stepping gives up, ConvergenceError, or the linear solve of a
mechanism fails, LinearSolveError). F is found by bracketing from F = 1 (×/÷ `growth` until a
trial fails / holds) and bisection until the bracket is within `tolerance` (relative) of its
stable end. The intact rock stays elastic (the joints are what fails). Barton's strength is
reduced through its peak angle, tan(φ_r + JRC log10(JCS/σ'_n)) / F at every σ'_n, by the C++
strength's reduction factor (joint/joint_strength.hpp).

The mechanism: where `trial` returns its model, the displacement the last reduction before
failure adds (the two largest stable factors, both close to F) is mostly the motion of the
blocks that fail, which grows without bound as F nears its critical value; each block's mean
``|Δu|`` is kept (SafetyFactor.block_motion), and the blocks moving at least half as much as the
fastest one are named (SafetyFactor.moving).

A factor the strength does not decide is not reported as one (SafetyFactor.reason, docs/slopes.md,
"Mesh dependence"): no equilibrium at any F down to `smallest`, or every failed trial stopping at
the same load factor whatever F; the reason gives the failure, which names the joints and the
blocks where Newton's iterates cycle (contact_cycling.py). What stopped the trial at the bracket's
unstable end is kept (SafetyFactor.failure): near a real mechanism the iterates cycle too (the
plane failure's toe), so only the user can tell from it whether that F is a strength's.
"""
from __future__ import annotations

import logging
import math
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from ...continuum import EquivalentContinuum, JointSet
from ...joint import JointBehaviour, JointStrength, StrengthModel
from ..solvers.linear_solver import LinearSolveError
from ..solvers.newton import ConvergenceError

log = logging.getLogger(__name__)


def reduced_strength(strength: JointStrength, factor: float) -> JointStrength:
    """The strength with tan φ, c and T divided by `factor` (> 0); no strength stays none. Barton's
    is reduced at every normal stress in C++, tan(φ_r + JRC log10(JCS/σ'_n)) / F (the strength's
    ``reduction_factor``, joint/joint_strength.hpp), its dilation kept within the reduced cap."""
    if not (math.isfinite(factor) and factor > 0.0):
        raise ValueError(f"strength reduction factor = {factor!r} must be finite and > 0")
    if strength.model == StrengthModel.none:
        return strength
    if strength.model == StrengthModel.barton:
        return JointStrength(StrengthModel.barton, friction_angle=strength.friction_angle,
                             cohesion=strength.cohesion, tensile_strength=strength.tensile_strength,
                             dilation_angle=strength.dilation_angle, dilation_limit=strength.dilation_limit,
                             jrc=strength.jrc, jcs=strength.jcs,
                             maximum_friction_angle=strength.maximum_friction_angle,
                             reduction_factor=strength.reduction_factor * factor)
    phi = math.atan(math.tan(strength.friction_angle) / factor)
    # T/F, but never past the reduced line's apex c_F / tan φ_F = c / tan φ (F < 1 raises T above it)
    # (computed from the reduced c and φ as the C++ check computes it: equal to the last bit)
    apex = (strength.cohesion / factor) / math.tan(phi) if phi > 0.0 else math.inf
    return JointStrength(StrengthModel.coulomb, friction_angle=phi, cohesion=strength.cohesion / factor,
                         tensile_strength=min(strength.tensile_strength / factor, apex),
                         dilation_angle=min(strength.dilation_angle, phi), dilation_limit=strength.dilation_limit,
                         reduction_factor=strength.reduction_factor)


def reduced_behaviour(behaviour: JointBehaviour, factor: float) -> JointBehaviour:
    """The joint behaviour with its strength reduced by `factor` (reduced_strength); the law and
    the stiffnesses unchanged."""
    return JointBehaviour(behaviour.law, behaviour.shear_model, shear_stiffness=behaviour.shear_stiffness,
                          shear_stiffness_ratio=behaviour.shear_stiffness_ratio,
                          residual_stiffness=behaviour.residual_stiffness,
                          strength=reduced_strength(behaviour.strength, factor),
                          effective_stress_coefficient=behaviour.effective_stress_coefficient)


def reduced_continuum(material: EquivalentContinuum, factor: float) -> EquivalentContinuum:
    """The equivalent-continuum material with every smeared set's strength reduced by `factor`,
    as the discrete joints' (issue 40: the smeared sets reduce their strength the same way); the
    rock, the sets' normals, spacings and stiffnesses unchanged. For a trial's
    JointedRockModel(continuum={block: reduced_continuum(material, F)})."""
    gdim = material.gdim
    sets = [JointSet(list(js.normal)[:gdim], js.spacing, reduced_behaviour(js.behaviour, factor), label=js.label)
            for js in material.sets]
    return EquivalentContinuum(gdim, material.young, material.poisson, sets)


@dataclass
class SafetyFactor:
    """The strength-reduction factor of safety: F (the middle of the last bracket), the bracket
    (largest F with equilibrium, smallest without; None where none was found), and every trial
    (F, held, why it failed)."""

    factor: float
    stable: float | None
    failed: float | None
    tolerance: float
    trials: list = field(default_factory=list)
    #: {block name: mean ``|u(F_stable) - u(F_before)|`` [m]} over the block's nodes (module docstring)
    block_motion: dict = field(default_factory=dict)
    #: why `factor` is not the joints' strength's factor of safety ("" if it is): the module docstring
    reason: str = ""
    #: what stopped the trial at `failed` (its error's first line; "" if none failed)
    failure: str = ""

    @property
    def decided_by_strength(self) -> bool:
        """True if F is a factor of safety: bounded, and the failure is the strength's (no reason)."""
        return self.bounded and not self.reason

    @property
    def moving(self) -> list:
        """The blocks that move at least half as much as the fastest near failure (sorted)."""
        top = max(self.block_motion.values(), default=0.0)
        return sorted(b for b, v in self.block_motion.items() if top > 0.0 and v >= 0.5 * top)

    @property
    def bounded(self) -> bool:
        """True if both ends of the bracket were found (a real factor, not a search limit)."""
        return self.stable is not None and self.failed is not None


def factor_of_safety(trial: Callable[[float], object], *, tolerance: float = 0.01, growth: float = 2.0,
                     smallest: float = 0.05, largest: float = 50.0) -> SafetyFactor:
    """F of the model that `trial(F)` builds with every joint strength reduced by F
    (reduced_strength) and solves through its stages (raising ConvergenceError or LinearSolveError
    when it finds no equilibrium). `tolerance`: relative width of the final bracket (default 0.01,
    issue 40). A scene stable at `largest` (or failing at `smallest`) returns that limit with
    bounded False, and says so in the log."""
    if not 0.0 < tolerance < 1.0:
        raise ValueError(f"factor_of_safety: tolerance = {tolerance!r} must be in (0, 1)")
    if not growth > 1.0:
        raise ValueError(f"factor_of_safety: growth = {growth!r} must be > 1")
    trials, held, errors = [], {}, {}

    def holds(f: float) -> bool:
        try:
            model = trial(f)
        except (ConvergenceError, LinearSolveError) as e:
            errors[f] = e
            trials.append((f, False, str(e).splitlines()[0]))
            log.info("strength reduction F = %.4g: no equilibrium (%s)", f, trials[-1][2][:120])
            return False
        trials.append((f, True, ""))
        if model is not None:
            held[f] = model
            for old in sorted(held)[:-2]:   # keep the two largest stable models only
                del held[old]
        log.info("strength reduction F = %.4g: equilibrium", f)
        return True

    stable = failed = None
    f = 1.0
    if holds(f):
        stable = f
        while failed is None and stable < largest:
            f = min(stable * growth, largest)
            if holds(f):
                stable = f
            else:
                failed = f
    else:
        failed = f
        while stable is None and failed > smallest:
            f = max(failed / growth, smallest)
            if holds(f):
                stable = f
            else:
                failed = f
    if stable is None or failed is None:
        limit = largest if failed is None else smallest
        log.info("strength reduction: %s at every F tried up to %g: no factor of safety in [%g, %g]",
                    "equilibrium" if failed is None else "no equilibrium", limit, smallest, largest)
        return SafetyFactor(limit, stable, failed, tolerance, trials, reason=_not_the_strength(errors, stable),
                            failure=str(errors[failed]).splitlines()[0] if failed is not None else "")
    while failed - stable > tolerance * stable:
        f = 0.5 * (stable + failed)
        if holds(f):
            stable = f
        else:
            failed = f
    motion = block_motion(*(held[k] for k in sorted(held))) if len(held) == 2 else {}
    reason = _not_the_strength(errors, stable)
    if reason:
        log.warning("strength reduction: F = %.4g is not a factor of safety: %s", 0.5 * (stable + failed), reason)
    failure = str(errors[failed]).splitlines()[0]
    if getattr(errors[failed], "hint", ""):
        log.warning("strength reduction: the trial at F = %.4g failed where %s", failed, errors[failed].hint)
    return SafetyFactor(0.5 * (stable + failed), stable, failed, tolerance, trials, motion, reason, failure)


def _not_the_strength(errors: dict, stable: float | None) -> str:
    """Why the failures of the trials ({F: error}) do not make a factor of safety, or "" if they
    may (module docstring): none held, or all stopped at one load factor."""
    if not errors:
        return ""
    if stable is None:
        f = min(errors)
        return (f"no equilibrium at any F down to {f:g}: the model fails whatever its joints' strength (not a "
                f"factor of safety). At F = {f:g}: {str(errors[f]).splitlines()[0]}")
    stops = {getattr(e, "load_factor", None) for e in errors.values()}
    if len(errors) > 1 and len(stops) == 1 and None not in stops:
        f = min(errors)
        return (f"every failed trial ({len(errors)}, F = {min(errors):g} to {max(errors):g}) stopped at the same load "
                f"factor {stops.pop():.6g}: the failure does not depend on the strength. At F = {f:g}: "
                f"{str(errors[f]).splitlines()[0]}")
    return ""


def block_motion(before, after) -> dict:
    """{block name: mean ``|u_after - u_before|`` [m]} over each block's displacement nodes, two models
    on one mesh (P1: the nodes are the cells' vertices; each node counted once per block).
    Collective; the same on every rank."""
    du = (after.u.x.array - before.u.x.array).reshape(-1, after.gdim)
    tags = after.dmesh.cell_blocks
    dofmap = after.V.dofmap
    owned = after.V.dofmap.index_map.size_local
    comm = after.comm
    out = {}
    for tag, name in sorted(after.dmesh.names["blocks"].items()):
        cells = tags.indices[tags.values == tag]
        nodes = np.unique(np.concatenate([dofmap.cell_dofs(c) for c in cells])) if cells.size else np.zeros(0, int)
        nodes = nodes[nodes < owned]                      # owned nodes: each counted on one rank
        total = comm.allreduce(float(np.linalg.norm(du[nodes], axis=1).sum()))
        count = comm.allreduce(int(nodes.size))
        out[name] = total / count if count else 0.0
    return out
