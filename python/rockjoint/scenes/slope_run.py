# SPDX-License-Identifier: MIT
"""A slope scene's factor of safety (its `factor_of_safety:` request; docs/slopes.md): strength
reduction (rockjoint.fem.mechanics.strength_reduction) where each trial is the scene's jointed
model with every joint set's strength divided by F, run through the scene's stages (its weight,
the loads, then the prescribed water) exactly as `rockjoint run` runs it.

What the trials share: the distributed mesh (built once), the law tables (tabulated once by
joint_laws.tables), the compiled forms (DOLFINx's JIT cache: the first trial compiles, the others
load them); each trial builds its own model and solver (a new strength per joint point, and the
PETSc solver set up on its own Jacobian). The intact rock is elastic and never fails: it is solved
once, not searched.
"""
from __future__ import annotations

import dataclasses
import logging
import time

from ..fem.mechanics.strength_reduction import factor_of_safety, reduced_strength

log = logging.getLogger("rockjoint.scenes")


@dataclasses.dataclass
class SlopeSafety:
    """The search's answer: the SafetyFactor (F, bracket, trials, block motion), its wall-clock
    time [s], and the two largest stable trials' models, {F: model} (the mechanism's picture)."""

    found: object
    seconds: float
    stable_models: dict

    @property
    def moving(self) -> list:
        """The blocks that fail (SafetyFactor.moving)."""
        return self.found.moving


def search(scene, plan, dmesh, tables: dict, build_model, run_stages, transmissivity=None):
    """(the jointed model at the largest stable F, its StageRows, SlopeSafety); the model and
    rows are None when no F down to the search's smallest holds. `build_model` and `run_stages`
    are runner's (one way to build and run a scene's model); `transmissivity`: {set: law} of a
    slope whose water flows (coupled both ways in every trial)."""
    spec = scene.data["factor_of_safety"]
    kept = {}

    def trial(factor):
        reduced = dataclasses.replace(scene, strengths={k: None if v is None else reduced_strength(v, factor)
                                                        for k, v in scene.strengths.items()})
        model = build_model(reduced, plan, dmesh, tables)
        rows = run_stages(reduced, plan, model, "jointed", transmissivity=transmissivity)
        kept[factor] = (model, rows)
        for old in sorted(kept)[:-2]:   # the two largest stable trials only
            del kept[old]
        return model

    t0 = time.perf_counter()
    found = factor_of_safety(trial, tolerance=spec["tolerance"], largest=spec["largest"])
    seconds = time.perf_counter() - t0
    log.info("factor of safety: F = %.4g (%s), %d trials in %.1f s", found.factor,
             f"stable {found.stable}, no equilibrium at {found.failed}" if found.bounded else "not bounded",
             len(found.trials), seconds)
    safety = SlopeSafety(found, seconds, {f: m for f, (m, _) in kept.items()})
    if found.stable is None:
        return None, None, safety
    model, rows = kept[found.stable]
    return model, rows, safety


def no_equilibrium_words(safety) -> str:
    """Why a slope without any stable trial is refused, in words: the model's own reason at F = 1
    (e.g. the joints the water jacks open) and at the smallest F tried."""
    f = safety.found
    reasons = [f"at F = {t[0]:g}: {t[2]}" for t in (f.trials[0], f.trials[-1])] if f.trials else []
    return (f"the slope has no equilibrium even with its joints' strength multiplied by {1 / f.failed:g} "
            f"(F = {f.failed:g}): a block is free whatever the strength; "
            + "; ".join(dict.fromkeys(reasons)))
