# SPDX-License-Identifier: MIT
"""The planner's rules: one function per decision, each returning its value and the Choice that
explains it (what was chosen, why, what it costs, what error it buys). make_plan (planner.py)
calls them in order; docs/scenes.md §planner states them in words.

Every override of the scene's `plan:` section goes through Context.setting, the one path: the
rule computes what it would choose, the scene's value replaces it, and the explanation says so.
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np

from . import defaults, geometry, ladder
from .stresses import (bending, concentration, largest_stress, mobilised_friction, normal_stress_bound,
                       stage_stresses, wall_mobilised_friction)


@dataclasses.dataclass
class Choice:
    """One decision of the planner: its topic, the choice, its cost, its error and why it was made."""

    topic: str
    choice: str
    cost: str
    error: str
    why: str


@dataclasses.dataclass
class Context:
    """What every rule reads: the scene (already at its reduced size when it is to be run so),
    its error budget, its joint sets, and the FE settings of the budget (defaults.fe_settings)."""

    scene: object
    budget: float
    sets: list
    fe: object
    fe_met: bool

    @classmethod
    def of(cls, scene) -> "Context":
        """The Context of `scene`: its error budget, its joint sets and the FE settings that meet the budget."""
        budget = scene.data["error_budget"]
        fe, met = defaults.fe_settings(budget)
        return cls(scene, budget, geometry.joint_sets(scene), fe, met)

    @property
    def geometry(self) -> dict:
        """The scene's checked `geometry:` section."""
        return self.scene.data["geometry"]

    def setting(self, key: str, auto):
        """(value, overridden): the scene's plan.<key> where it gives one, else the rule's own."""
        over = self.scene.data["plan"]
        return (over[key], True) if key in over else (auto, False)

    def chosen(self, key, auto, auto_words: str, text, **words):
        """The value of a setting with one Choice: `text(value)` names it; an override replaces
        the rule's reason by the scene's, with what the planner would have chosen."""
        value, overridden = self.setting(key, auto)
        if overridden:
            words["why"] = f"set in the scene's plan ({key}); the planner would choose {auto_words}"
        return value, [Choice(words.pop("topic"), text(value), **words)]


def friction_words(r: float) -> str:
    """The mobilised friction `r` [-] in words for a plan: two decimals, or "more than 10" (no cohesion)."""
    return f"{r:.2f}" if r < 10 else "more than 10 (no cohesion: planes nearly along the wall)"


def dimension(ctx: Context):
    """The scene's own dimension: a 2D section is solved in plane strain, never in 3D."""
    own = ctx.geometry["dimension"]
    value, choices = ctx.chosen(
        "dimension", own, own, text=lambda v: "2D plane strain" if v == 2 else "3D", topic="dimension",
        why="the scene is a " + ("2D section: plane strain, no 3D solve" if own == 2 else "3D block"),
        cost="2D: ~1/20 of a 3D model's dofs at the same element size" if own == 2 else "3D: the full cost",
        error="exact for a long opening / plane section (plane strain)")
    if value != own:
        ctx.scene.fail(("plan", "dimension"), f"a {own}D geometry cannot be solved in {value}D")
    return value, choices


def table_range(ctx: Context):
    """((normal-stress bound, table top) [Pa]): the tables cover the bound with a margin; with no
    compression anywhere (a scene pulled in tension) the joints open and the table is never read
    past 0, but it must exist: it covers the largest stress magnitude instead."""
    bound = normal_stress_bound(ctx.scene)
    cover = bound if bound > 0 else largest_stress(ctx.scene)
    auto = defaults.TABLE_MARGIN * cover
    why = ((f"upper bound of joint normal stress {bound * 1e-6:.3g} MPa (largest compressive principal "
            "stress of in-situ + all loads"
            + (" + bending 6 τ H/W of shear tractions" if max(bending(ctx.scene)) > 0 else "")
            + ", " + concentration(ctx.scene)[1] + ")") if bound > 0 else
           ("no load compresses the joints (every principal stress is tensile or 0): they open; the "
            f"table covers the largest stress magnitude, {cover * 1e-6:.3g} MPa"))
    top, choices = ctx.chosen(
        "table_max_stress", auto, f"{auto * 1e-6:.3g} MPa", text=lambda v: f"normal stress 0 - {v * 1e-6:.3g} MPa",
        topic="table range", why=why + f", x {defaults.TABLE_MARGIN} margin",
        cost="knots grow with log(range); a table evaluation costs ~0.05 µs whatever the law",
        error="the loads cannot take a joint outside it (checked after the run)")
    return (bound, top), choices


def table_tolerance(ctx: Context):
    """The largest table tolerance whose FE error stays below a tenth of the budget (the FE
    speed-vs-error report's row for the budget)."""
    fe = ctx.fe
    return ctx.chosen(
        "table_tolerance", fe.table_tolerance, f"{fe.table_tolerance:g}", text=lambda v: f"{v:g} relative on σ and k",
        topic="table tolerance",
        why=(f"the largest tolerance whose FE error stays below a tenth of a {fe.error_budget:.0%} "
             "budget on the report's column and tunnel"),
        cost="tens to hundreds of knots, built in well under a second",
        error="the table's share of the answer: 1.2e-4 on the report's tunnel at 0.01, "
              "1e-8 at 1e-6 (fe_speed_vs_error.md §5)")


def _ladder_law(ctx: Context, name: str, topography: dict, tolerance: float):
    """(ladder key, Choice) of a joint given by its walls: the rung of least total cost within
    the budget (ladder.cheapest_within), or the scene's plan.law."""
    points = topography["points"]
    rung, met = ladder.cheapest_within(ctx.budget, points, tolerance)
    key, overridden = ctx.setting("law", rung.key)
    rungs = ladder.by_key()
    if key not in rungs:
        ctx.scene.fail(("plan", "law"), f"{key!r} is not on the accuracy ladder; one of {', '.join(rungs)}")
    r = rungs[key]
    why = ("set in the scene's plan (law)" if overridden else
           f"least total cost within the {ctx.budget:.0%} budget of every way to the joint's curve" if met else
           f"no rung meets the {ctx.budget:.0%} budget: the most accurate one")
    exact = key == ladder.EXACT_CONTACT
    what = ("the BEM solve of the exact contact" if exact else
            f"the scan's analysis and the law's table ({r.evaluation * 1e6:.2f} µs per evaluation while tabulating)")
    errors = ", ".join(f"{e:.1%} {f}" for f, e in r.errors.items())
    at = ladder.evidence_spacing()
    return key, Choice(
        f"law of {name}", f"{key} ({r.label.replace('**', '')})", why=why,
        cost=f"~{r.seconds(points, tolerance):.2g} s on the {points}² scan: {what} (bench/results/accuracy_ladder.json)",
        error=(f"closure vs the walls' exact contact at half the scan's spacing, "
               f"{ladder.PREDICTION_LEVEL:.0%} upper prediction limit for a joint from the bench's joints "
               f"scanned at {at * 1e3:g} mm: {errors} ("
               + ("the BEM's resolution error + its table's" if exact else
                  "the law vs the scan's BEM + the BEM's resolution error")
               + "; bench/results/accuracy_ladder.json)"
               + ("" if topography["spacing"] <= at * (1 + 1e-9) else
                  f"; this scan is coarser ({topography['spacing'] * 1e3:g} mm): its resolution error is not measured")))


def laws(ctx: Context, tolerance: float):
    """{set: ladder key} of the sets whose law the planner chooses (those given by their walls);
    a law the scene gives by model, curve, cycles or table is kept and has no key here."""
    keys, choices = {}, []
    for s in ctx.sets:
        law = ctx.scene.data["joints"][s["name"]]["law"]
        if "topography" in law:
            keys[s["name"]], choice = _ladder_law(ctx, s["name"], law["topography"], tolerance)
        else:
            how = next(k for k in ("model", "curve", "cycles", "table") if k in law)
            choice = Choice(f"law of {s['name']}", f"the scene's {how}", why="a law given by the user is kept",
                            cost="tabulated once", error="the law's own (not on the ladder); table error above")
        choices.append(choice)
    return keys, choices


def slip(ctx: Context, dim: int):
    """{set: bool}: slip is modelled only for sets with a strength whose mobilised friction
    τ/τ_max can reach defaults.SLIP_MARGIN under the bound (at an opening: the wall's uniaxial
    state, every plane)."""
    values, choices = {}, []
    tensors = stage_stresses(ctx.scene)
    opening = "opening" in ctx.geometry
    for s in ctx.sets:
        strength = ctx.scene.strengths[s["name"]]
        if strength is None:
            values[s["name"]] = False
            continue
        if opening:
            hoop = max(defaults.OPENING_CONCENTRATION * max(0.0, -float(np.linalg.eigvalsh(t).min()))
                       for _, t, _ in tensors)
            ratio, where = wall_mobilised_friction(strength, hoop), "at the opening's wall (σ_r = 0)"
        else:
            n = geometry.set_normal(s, dim)
            ratio, where = max(mobilised_friction(strength, n, t) for _, t, _ in tensors), "on its plane"
        auto = ratio >= defaults.SLIP_MARGIN
        value, overridden = ctx.setting("slip", auto)
        values[s["name"]] = value
        choices.append(Choice(
            f"slip of {s['name']}", "joint strength and slip" if value else "elastic joints (no slip)",
            why=("set in the scene's plan (slip)" if overridden else
                 f"mobilised friction τ/τ_max up to {friction_words(ratio)} {where} under the stress bound "
                 f"({'>=' if auto else '<'} {defaults.SLIP_MARGIN})"),
            cost=("a non-symmetric Jacobian (LU/GMRES) and small load steps" if value
                  else "none: symmetric Jacobian, one load step"),
            error=("path-dependent slip resolved per load step" if value else
                   f"joints stay below {defaults.SLIP_MARGIN:.0%} of their strength: slip cannot occur "
                   "unless stresses concentrate beyond the bound")))
    return values, choices


def _joint_spacing(scene) -> float:
    """Smallest distance between parallel joints of the scene (a column's: between its joints and
    ends), the length the report's joint mesh size is relative to."""
    g = scene.data["geometry"]
    if g["kind"] == "column":
        z = sorted([0.0, g["height"]] + list(g["joint_heights"]))
        return min(b - a for a, b in zip(z, z[1:]) if b > a)
    return min((s["spacing"] for s in g.get("joint_sets", [])), default=float(max(geometry.extent(g))))


def estimate_dofs(scene, dim, h, hj, ho) -> float:
    """The displacement dofs a mesh of the scene's geometry would have at element size h (hj on
    the joints, ho at an opening; None: h), from cell and vertex counts (below): the planner's cost."""
    extent = geometry.extent(scene.data["geometry"])
    # triangles ~ 2 A/h², tetrahedra ~ 6 V/h³; vertices ~ cells/2 (2D), cells/5 (3D); the refined
    # bands near joints and openings roughly double that at h/4 - h/8.
    cells = (2.0 if dim == 2 else 6.0) * float(np.prod(extent / h))
    refine = 1.0 + (1.0 if hj else 0.0) + (1.0 if ho else 0.0)
    return dim * cells * refine / (2.0 if dim == 2 else 5.0)


def mesh(ctx: Context, dim: int):
    """((far size, joint size, opening size, degree, joint rule)): the cheapest settings of the FE
    speed-vs-error report within the budget, refined only near joints and openings."""
    fe, g, d = ctx.fe, ctx.geometry, ctx.scene.data
    h = d["mesh"]["size"]
    refine, _ = ctx.setting("refine", True)
    opening = "opening" in g
    hj = d["mesh"].get("joint_size", min(h, fe.joint_size_over_spacing * _joint_spacing(ctx.scene))) \
        if (refine and ctx.sets) else None
    ho = d["mesh"].get("opening_size", min(h, fe.opening_size_over_radius * geometry.opening_half_size(g))) \
        if (refine and opening) else None
    degree, _ = ctx.setting("element_degree", fe.element_degree)
    quadrature, _ = ctx.setting("quadrature", fe.quadrature)
    dofs = estimate_dofs(ctx.scene, dim, h, hj, ho)
    sizes = ", ".join(f for f in (
        f"{fe.joint_size_over_spacing:.3g} x joint spacing on joints" if hj else "",
        f"{fe.opening_size_over_radius:.3g} x radius on the opening"
        + ("" if g["opening"]["shape"] == "circle" else " (its half-size)") if ho else "") if f)
    measured = (f"the report's tunnels got {fe.measured_error:.2g} and {fe.measured_error_second_scene:.2g} "
                f"with these settings (bench/results/fe_speed_vs_error.md §8, budget {fe.error_budget:.0%})")
    if not ctx.fe_met:
        measured += f"; no mesh of its sweep met {ctx.budget:.0%}: an error that small is not demonstrated"
    choice = Choice(
        "mesh", f"P{degree}, {h:g} m far" + (f", {hj:g} m on joints" if hj else "")
        + (f", {ho:g} m on the opening" if ho else "") + f", {quadrature} joint rule",
        why=(f"the cheapest settings of the FE speed-vs-error report within {fe.error_budget:.0%}"
             + (f" ({sizes}; never coarser than the scene's size)" if sizes else "")
             + "; refined only near joints and openings"
             + ("; refinement switched off in the scene's plan" if not refine else "")),
        cost=f"~{dofs:.2g} dofs, ~{dofs * defaults.SECONDS_PER_DOF:.2g} s per Newton load step "
             "(fe_speed_vs_error.md §3 rate)",
        error=measured + "; uniform stress fields are exact with P1 (§1)")
    return (h, hj, ho, degree, quadrature), [choice]


def load_steps(ctx: Context, any_slip: bool):
    """Load steps per stage: one Newton from one step for elastic joints, small steps for slip
    (path dependent)."""
    steps, _ = ctx.setting("load_steps", defaults.LOAD_STEPS_SLIP if any_slip else ctx.fe.load_steps)
    return steps, [Choice("load steps", f"{steps} per stage (unless the stage sets its own)",
                          why="slip is path dependent" if any_slip else "elastic joints: Newton from one step",
                          cost="~6 Newton iterations per step", error="none for elastic joints")]


def intact(ctx: Context):
    """The intact model on the same mesh, always unless the plan leaves it out."""
    value, _ = ctx.setting("intact", True)
    return value, [Choice("intact model", "on the same mesh (split nodes glued)" if value else "left out",
                          why="the joints' share of every answer is jointed minus intact",
                          cost="one linear solve per load step", error="none: same mesh, same solver")]


def water(ctx: Context):
    """The scene's water (`water:`, or `outputs: {flow}`) and what its coupling costs: one way, a
    network solve per stage; two ways, the coupled steady state after every stage, about
    defaults.COUPLED_ITERATIONS mechanical solves each (the measured count)."""
    d = ctx.scene.data
    w = d.get("water")
    if w is None and "flow" not in d["outputs"]:
        return None, []
    coupling = w["coupling"] if w is not None else "one_way"
    table = (f"; the table at z = {w['table']:g} m: hydrostatic water in the joints from the in-situ "
             "stage on, joints pre-closed at the effective stress") if w is not None and "table" in w else ""
    timed = [(s["name"], s["water"]) for s in d["stages"] if "water" in s]
    if timed:
        per = (f"about {defaults.TRANSIENT_ITERATIONS} mechanical stage solves (+ one network solve each) per "
               "time step, the fixed-stress iterations measured on the erfc column (bench/results/coupled_water.md)"
               if coupling == "two_way" else "one network solve per time step (the mechanics held)")
        table += "; transient water in stage(s) " + ", ".join(
            f"{n} ({t['duration'] / 86400:g} d in {t['steps']} implicit steps: {per})" for n, t in timed)
    if coupling == "two_way":
        return coupling, [Choice(
            "water", "two way: the water's pressure acts on the joints, coupled to the equilibrium" + table,
            why="set in the scene (water.coupling: two_way)",
            cost=(f"after every stage the coupled steady state: about {defaults.COUPLED_ITERATIONS} mechanical "
                  "stage solves (+ one network solve each) per stage, the staggered iterations measured on the "
                  "verification column and the drained tunnel (bench/results/coupled_water*.md)"),
            error="the coupling converged to 1e-8 of the pressures; the network's P1 error on the joints")]
    return coupling, [Choice(
        "water", "one way: the flow along the joints at each stage's closures" + table,
        why=("the scene's default (water.coupling: one_way)" if w is not None else "outputs.flow: the flow only")
            + (": the joints see only the table's water" if table else ""),
        cost="one network solve per stage (a sparse direct solve on the joint points)",
        error="the water's pressure does not act back on the joints: they keep the table's water (or none)")]
