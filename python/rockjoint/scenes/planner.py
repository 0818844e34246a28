# SPDX-License-Identifier: MIT
"""`rockjoint plan`: decide what a scene needs to model, each choice with its cost and error.

Rules (docs/scenes.md §planner):

- dimension: the scene's own (a 2D section is solved in 2D plane strain, never in 3D);
- joint normal-stress bound: the largest compressive principal stress of in-situ + loads (every
  load added in full: an upper bound), times the Kirsch concentration 3 at an opening; the tables
  cover it with a margin (defaults.TABLE_MARGIN);
- law: from a topography, the rung of least total cost (ladder.py: each law of the accuracy
  ladder, or the exact contact curve of the walls) whose error is within the error budget; a
  law given by name, curve or table is kept;
- slip: only for joint sets with a strength whose mobilised friction τ/τ_max can reach
  defaults.SLIP_MARGIN under the bound (at an opening: the wall's uniaxial state, every plane);
- mesh: refined only near joints and openings; the intact model on the same mesh (glued nodes);
- water: one way (a network solve per stage) or two ways (the coupled steady state after every
  stage: about defaults.COUPLED_ITERATIONS mechanical solves per stage, measured).

Any choice can be overridden in the scene's `plan:` section; the plan then says so.
"""
from __future__ import annotations

import dataclasses

from . import rules, slope_plan, smearing, statics
from .rules import Choice  # noqa: F401  (re-exported: the planner's explained choice)


@dataclasses.dataclass
class Plan:
    """What the planner chose for a scene, with a Choice (what, why, cost, error) for each decision.

    Sizes in m, stresses in Pa; laws maps each joint set given by its walls to a ladder key, slip
    each joint set to whether it may slip.
    """

    dimension: int
    element_degree: int
    quadrature: str
    mesh_size: float
    joint_size: float | None
    opening_size: float | None
    normal_stress_bound: float          # [Pa]
    table_max_stress: float             # [Pa]
    table_tolerance: float
    laws: dict                          # joint set given by its walls -> ladder key
    slip: dict                          # joint set -> bool
    load_steps: int
    intact: bool
    choices: list
    reduced: bool = False               # planned at the scene's reduced size (Scene.at_reduced_size)
    smeared: tuple = ()                 # joint sets smeared in the rock (equivalent continuum)
    water: str | None = None            # the water's coupling (one_way, two_way), None: dry
    safety: dict | None = None          # a slope's factor-of-safety search {tolerance, largest}, None: none

    def text(self) -> str:
        """The plan's choices in words, one block per choice (topic, choice, why, cost, error)."""
        rows = [f"{c.topic}: {c.choice}\n    why: {c.why}\n    cost: {c.cost}\n    error: {c.error}"
                for c in self.choices]
        return "\n".join(rows)


def make_plan(scene) -> Plan:
    """What to model for `scene` (at its reduced size: plan `scene.at_reduced_size()`): the
    decisions of rules.py and smearing.py in order, each with its explained Choice."""
    statics.check(scene)  # supports and excavations that leave no equilibrium: a bad scene
    ctx = rules.Context.of(scene)
    choices = []

    def decide(rule, *args):
        value, explained = rule(ctx, *args)
        choices.extend(explained)
        return value

    dim = decide(rules.dimension)
    bound, table_top = decide(rules.table_range)
    tolerance = decide(rules.table_tolerance)
    laws = decide(rules.laws, tolerance)
    slope = ctx.geometry["kind"] == "slope"
    slip = decide(slope_plan.slip if slope else rules.slip, dim)
    h, hj, ho, degree, quadrature = decide(rules.mesh, dim)
    steps = decide(rules.load_steps, any(slip.values()))
    intact = decide(rules.intact)
    smeared = decide(smearing.smeared_sets, dim)
    water = decide(slope_plan.water if slope else rules.water)
    safety = decide(slope_plan.factor_of_safety, rules.estimate_dofs(scene, dim, h, hj, ho), steps)
    return Plan(dim, degree, quadrature, h, hj, ho, bound, table_top, tolerance, laws, slip, steps,
                intact, choices, scene.reduced, smeared, water, safety)
