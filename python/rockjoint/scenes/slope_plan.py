# SPDX-License-Identifier: MIT
"""The planner's rules for a slope (docs/slopes.md, "Slope scenes"): its weight as the stress
bound, slip on every set when a factor of safety is searched, the prescribed water, and the cost
and error of the strength-reduction search.

The search's cost in trial solves follows from its rule (strength_reduction.factor_of_safety):
from F = 1 the trial factor is multiplied (F >= 1) or divided (F < 1) by the growth g = 2 until a
trial fails / holds, which brackets F in [g^k, g^(k+1)) after |k| + 2 trials (k >= 0) or |k| + 1
(k < 0); then the bracket, of width g^k (g - 1), is halved until it is within the tolerance t of
its stable end: ceil(log2(g^k (g - 1) / (t F))) more trials.
"""
from __future__ import annotations

import math

import numpy as np

from . import defaults, rules, slope_keys
from .rules import Choice

#: the search's growth factor (strength_reduction.factor_of_safety's default)
GROWTH = 2.0
#: the factors of safety the planner quotes the search's cost for (before the search, F is unknown)
QUOTED = (0.5, 4.0)


def searched(scene) -> bool:
    """True if the scene asks for a slope's factor of safety."""
    return "factor_of_safety" in scene.data


def trial_count(factor: float, tolerance: float, growth: float = GROWTH) -> int:
    """Trial solves of a search that finds `factor` to `tolerance` (module docstring)."""
    k = math.floor(math.log(factor, growth) + 1e-12)
    bracket = k + 2 if k >= 0 else -k + 1
    width = growth ** k * (growth - 1.0)
    return bracket + max(0, math.ceil(math.log2(width / (tolerance * factor)) - 1e-12))


def slip(ctx, dim: int):
    """rules.slip; with a factor of safety searched, every set with a strength slips."""
    values, choices = rules.slip(ctx, dim)
    if not searched(ctx.scene):
        return values, choices
    for s in ctx.sets:
        if ctx.scene.strengths[s["name"]] is not None:
            values[s["name"]] = True
    why = "the factor of safety divides every set's strength by F until a block slides"
    return values, [Choice(c.topic, "joint strength and slip", why=why, cost="a non-symmetric Jacobian (LU) "
                           "and small load steps", error="path-dependent slip resolved per load step")
                    for c in choices]


def water(ctx):
    """(coupling or None, [Choice]) of a slope's water: the prescribed hydrostatic table, or the flow
    between heads and pressures coupled both ways (the scenes' water, rules.water)."""
    w = ctx.scene.data.get("water")
    if w is None:
        return None, []
    if "table" not in w:   # computed: the coupled steady state after every stage (rules.water says its cost)
        return rules.water(ctx)
    return None, [Choice(
        "water", f"prescribed: the water table at z = {w['table']:g} m behind the crest, drawn down straight to "
                 "the toe; "
                 "p = ρ_w g (z_w - z) in every joint below it (cracks and sliding planes), set after the stages",
        why="the distribution of limit-equilibrium practice (Hoek & Bray 1981): the face drains",
        cost="one more stage per solve (per trial of the factor-of-safety search)",
        error="no flow: the pressures are prescribed, not computed from the joints' transmissivity")]


def factor_of_safety(ctx, dofs: float, steps: int):
    """({tolerance, largest}, [Choice]) of the strength-reduction search: its trial solves for F
    in QUOTED (trial_count), each the scene's stages, and its error, the tolerance."""
    spec = ctx.scene.data.get("factor_of_safety")
    if spec is None:
        return None, []
    t = spec["tolerance"]
    grid = np.exp(np.linspace(math.log(QUOTED[0]), math.log(QUOTED[1]), 200))
    counts = [trial_count(f, t) for f in grid]
    stages = len(ctx.scene.data["stages"]) + (1 if "water" in ctx.scene.data else 0)
    per_trial = dofs * defaults.SECONDS_PER_DOF * steps * stages * 6
    return spec, [Choice(
        "factor of safety",
        f"strength reduction to {100 * t:.3g} % (bracketing x{GROWTH:g} from F = 1, then bisection)",
        why="the scene asks for it (factor_of_safety); the intact rock is elastic and never fails: it is solved "
            "once, not searched",
        cost=f"{min(counts)}-{max(counts)} trial solves for F between {QUOTED[0]:g} and {QUOTED[1]:g} "
             f"({trial_count(1.5, t)} at F = 1.5), each the {stages} stage(s) at ~{per_trial:.2g} s "
             "(~6 Newton iterations per load step at the mesh's rate)",
        error=f"F to within {100 * t:.3g} % (the final bracket's width; F is its middle), "
              "besides the mesh's error on the failure load")]
