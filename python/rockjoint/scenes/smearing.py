# SPDX-License-Identifier: MIT
"""The planner's rule for joint sets: discrete (joint elements) or smeared into the rock as an
equivalent continuum, set by set, on the continuum bench's evidence (defaults.SMEARED_EVIDENCE,
docs/equivalent-continuum.md); one of the rules make_plan calls (rules.py has the others)."""
from __future__ import annotations

import math

import numpy as np

from . import defaults, geometry, water_keys
from .rules import Choice, friction_words
from .stresses import mobilised_friction, stage_stresses


def dominance(scene, sets, dim) -> dict:
    """{set: mobilised friction τ/τ_max where the set is loaded hardest}: with an opening, on the
    set's plane under the uniaxial wall stress where the hoop stress peaks (Kirsch: 3 σ1 - σ3
    along the major compression σ1); otherwise on its plane under the stage stresses. 0 for a set
    without a strength. The largest is the dominant set, the one kept discrete in a mixed model."""
    d = scene.data
    opening = "opening" in d["geometry"]
    out = {}
    for s in sets:
        strength = scene.strengths[s["name"]]
        if strength is None:
            out[s["name"]] = 0.0
            continue
        n = geometry.set_normal(s, dim)
        ratios = []
        for _, t, _ in stage_stresses(scene):
            if opening:
                values, vectors = np.linalg.eigh(t)  # ascending: values[0] the major compression
                hoop = max(0.0, -3.0 * values[0] + values[-1])
                t = -hoop * np.outer(vectors[:, 0], vectors[:, 0])
            ratios.append(mobilised_friction(strength, n, t))
        out[s["name"]] = max(ratios, default=0.0)
    return out


def smeared_sets(ctx, dim: int):
    """Discrete or smeared, set by set (defaults.SMEARED_EVIDENCE, the nearest measured spacing
    ratio at or above the set's: spacing over the opening radius (half-size), or half the section's smaller
    side). The dominant set (largest mobilised friction, `dominance`) is smeared only where the
    all-smeared model is within the budget and cheaper than the discrete one; any other set where
    the mixed model (dominant set discrete, the rest smeared) or the all-smeared one is. Error of
    a model: the larger of its crown and sidewall gaps to the discrete model. The scene's
    plan.smeared overrides. Returns (the smeared sets, their Choices)."""
    scene, sets, budget, choices = ctx.scene, ctx.sets, ctx.budget, []
    g = scene.data["geometry"]
    over, _ = ctx.setting("smeared", None)
    mobilised = dominance(scene, sets, dim)
    names = [s["name"] for s in sets]
    if over is not None:
        if g["kind"] == "column":
            scene.fail(("plan", "smeared"), "a column's joints are given one by one; only joint sets can be smeared")
        for name in over:
            if name not in names:
                scene.fail(("plan", "smeared"), f"no joint set '{name}'; joint sets: {', '.join(names)}")
    if g["kind"] == "column":
        return (), choices
    if water_keys.flows(scene.data) or "water" in scene.data:   # water runs along the joint network (docs/flow.md)
        if over:
            scene.fail(("plan", "smeared"), "the scene asks for flow, which runs along the joint network: "
                       "flow through smeared sets and the rock around them is not modelled; keep the sets discrete")
        for s in sets:
            choices.append(Choice(f"joints of {s['name']}", "discrete (joint elements)",
                                  why="the scene asks for flow, which runs along the joint network",
                                  cost="joint elements on every joint of the set",
                                  error="none from the choice: the joints are meshed"))
        return (), choices
    size = geometry.opening_half_size(g) if "opening" in g else 0.5 * float(min(geometry.extent(g)))
    dominant = max(names, key=lambda name: mobilised[name]) if names else None
    chosen = []
    for s in sets:
        ratio = s["spacing"] / size
        rows = [r for r in defaults.SMEARED_EVIDENCE if r[0] >= ratio]
        measured = min(rows, key=lambda r: r[0]) if rows else None
        role = "dominant" if s["name"] == dominant else "other"
        all_ok = bool(measured) and measured[1] <= budget and measured[2] > 1.0
        mixed_ok = bool(measured) and measured[3] <= budget and measured[4] > 1.0
        auto = all_ok or (role == "other" and mixed_ok)
        value = (s["name"] in over) if over is not None else auto
        if value:
            chosen.append(s["name"])
        if measured:
            def off(e):  # an infinite error: the model failed or did not hold on a finer mesh
                return f"{e:.0%} off" if math.isfinite(e) else "not validated (failed or mesh-dependent)"
            evidence = (f"the continuum bench at s/a = {measured[0]:g}: all sets smeared {off(measured[1])} "
                        f"at {measured[2]:.2g}x the discrete model's speed, the dominant set discrete and the "
                        f"rest smeared {off(measured[3])} at {measured[4]:.2g}x")
        else:
            evidence = "no continuum bench row at so large a spacing ratio"
        error = ("none from the choice: the joints are meshed" if not value else
                 f"the bench's gap {measured[1] if (all_ok or not mixed_ok) else measured[3]:.0%} (wall convergence)"
                 if measured else "unmeasured: the scene's plan asks for it")
        choices.append(Choice(
            f"joints of {s['name']}", "smeared (equivalent continuum)" if value else "discrete (joint elements)",
            why=(("set in the scene's plan (smeared); " if over is not None else "")
                 + f"s/a = {ratio:.2g}; the {role} set (mobilised friction {friction_words(mobilised[s['name']])}); "
                 + f"{evidence} (bench/results/continuum.md)"
                 + ("" if value or over is not None else
                    "; smearing it is not both within the budget and cheaper")),
            cost="smeared: no joint elements, a quadrature-point material with a local Newton per point"
                 if value else "joint elements on every joint of the set",
            error=error))
    return tuple(chosen), choices
