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
- mesh: refined only near joints and openings; the intact model on the same mesh (glued nodes).
Any choice can be overridden in the scene's `plan:` section; the plan then says so.
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np

from . import defaults, geometry, ladder, statics
from .stresses import FACE_AXIS, mobilised_friction, stage_stresses, wall_mobilised_friction



@dataclasses.dataclass
class Choice:
    topic: str
    choice: str
    cost: str
    error: str
    why: str


@dataclasses.dataclass
class Plan:
    dimension: int
    element_degree: int
    quadrature: str
    mesh_size: float
    joint_size: float | None
    opening_size: float | None
    normal_stress_bound: float          # [Pa]
    table_max_stress: float             # [Pa]
    table_tolerance: float
    laws: dict                          # joint set -> ladder key / "given"
    slip: dict                          # joint set -> bool
    load_steps: int
    intact: bool
    choices: list
    reduced: bool = False               # the scene's reduced size (coarse mesh, small scans)
    smeared: tuple = ()                 # joint sets smeared in the rock (equivalent continuum)

    def text(self) -> str:
        rows = [f"{c.topic}: {c.choice}\n    why: {c.why}\n    cost: {c.cost}\n    error: {c.error}"
                for c in self.choices]
        return "\n".join(rows)


def concentration(scene) -> tuple:
    """(factor, words): the stress-concentration bound of the scene's geometry: Kirsch's 3 at an
    opening, block corners where joint sets of different orientation cross, else 1."""
    g = scene.data["geometry"]
    if "opening" in g:
        return defaults.OPENING_CONCENTRATION, "x 3 Kirsch concentration at the opening"
    orientations = {(round(s["dip"], 6), round(s["dip_direction"], 6)) for s in g.get("joint_sets", [])}
    if len(orientations) > 1:
        return (defaults.BLOCK_CORNER_CONCENTRATION,
                f"x {defaults.BLOCK_CORNER_CONCENTRATION:g} at block corners where joint sets cross")
    return 1.0, "no concentration: a homogeneous field"


def bending(scene) -> list:
    """Per stage, the bending stress [Pa] a shear traction on a face adds on a joint section:
    the moment τ W H of a shear τ on a face of width W at lever arm H, over the section modulus
    W²/6 (beam theory: 6 τ H/W), H the scene's extent normal to the face, W the smallest along it."""
    g = scene.data["geometry"]
    ext, dim = geometry.extent(g), g["dimension"]
    out, loads = [], {}
    for stage in scene.data["stages"]:
        loads.update(stage["loads"])
        extra = 0.0
        for face, load in loads.items():
            if "traction" not in load or face not in FACE_AXIS:
                continue
            axis = dim - 1 if face in ("bottom", "top") else (0 if face in ("left", "right") else 1)
            t = np.asarray(load["traction"], float)
            tau = float(np.linalg.norm(np.delete(t, axis)))
            along = np.delete(ext, axis).min()
            extra += 6.0 * tau * ext[axis] / along
        out.append(extra)
    return out


def normal_stress_bound(scene) -> float:
    """Upper bound [Pa] of any joint's normal stress over the stages."""
    factor = concentration(scene)[0]
    bound = 0.0
    for (_, s, pressure), extra in zip(stage_stresses(scene), bending(scene)):
        compression = max(0.0, -float(np.linalg.eigvalsh(s).min()))
        bound = max(bound, compression * factor + pressure + extra)
    return bound


def _largest_stress(scene) -> float:
    """The largest principal stress magnitude [Pa] of any stage (pressures included); 1 MPa if
    nothing loads the scene (a table needs a range)."""
    top = max((max(float(np.abs(np.linalg.eigvalsh(s)).max(initial=0.0)), p)
               for _, s, p in stage_stresses(scene)), default=0.0)
    return top if top > 0 else 1e6


def _ratio(r: float) -> str:
    return f"{r:.2f}" if r < 10 else "more than 10 (no cohesion: planes nearly along the wall)"


def _joint_spacing(scene) -> float:
    """Smallest distance between parallel joints of the scene (a column's: between its joints and
    ends), the length the report's joint mesh size is relative to."""
    g = scene.data["geometry"]
    if g["kind"] == "column":
        z = sorted([0.0, g["height"]] + list(g["joint_heights"]))
        return min(b - a for a, b in zip(z, z[1:]) if b > a)
    return min((s["spacing"] for s in g.get("joint_sets", [])), default=float(max(geometry.extent(g))))


def _estimate_dofs(scene, dim, h, hj, ho) -> float:
    extent = geometry.extent(scene.data["geometry"])
    # triangles ~ 2 A/h², tetrahedra ~ 6 V/h³; vertices ~ cells/2 (2D), cells/5 (3D); the refined
    # bands near joints and openings roughly double that at h/4 - h/8.
    cells = (2.0 if dim == 2 else 6.0) * float(np.prod(extent / h))
    refine = 1.0 + (1.0 if hj else 0.0) + (1.0 if ho else 0.0)
    return dim * cells * refine / (2.0 if dim == 2 else 5.0)


def make_plan(scene, reduced: bool = False) -> Plan:
    statics.check(scene)  # supports and excavations that leave no equilibrium: a bad scene
    d = scene.data
    over = d["plan"]
    g = d["geometry"]
    budget = d["error_budget"]
    choices = []

    def choose(topic, key, value, auto, **words):
        if key in over:
            words["why"] = f"set in the scene's plan ({key}); the planner would choose {auto}"
            value = over[key]
        choices.append(Choice(topic, words.pop("text")(value), **words))
        return value

    dim = choose("dimension", "dimension", g["dimension"], g["dimension"],
                 text=lambda v: "2D plane strain" if v == 2 else "3D",
                 why="the scene is a " + ("2D section: plane strain, no 3D solve"
                                          if g["dimension"] == 2 else "3D block"),
                 cost="2D: ~1/20 of a 3D model's dofs at the same element size" if g["dimension"] == 2
                 else "3D: the full cost", error="exact for a long opening / plane section (plane strain)")
    if dim != g["dimension"]:
        scene.fail(("plan", "dimension"), f"a {g['dimension']}D geometry cannot be solved in {dim}D")

    bound = normal_stress_bound(scene)
    opening = "opening" in g
    sets = geometry.joint_sets(scene)
    # No compression anywhere (a scene pulled in tension): the joints open and the table is never
    # read past 0, but it must exist; it covers the largest stress magnitude instead of 0.
    cover = bound if bound > 0 else _largest_stress(scene)
    table_top = choose("table range", "table_max_stress", defaults.TABLE_MARGIN * cover,
                       f"{defaults.TABLE_MARGIN * cover * 1e-6:.3g} MPa",
                       text=lambda v: f"normal stress 0 - {v * 1e-6:.3g} MPa",
                       why=((f"upper bound of joint normal stress {bound * 1e-6:.3g} MPa (largest "
                             "compressive principal stress of in-situ + all loads"
                             + (" + bending 6 τ H/W of shear tractions" if max(bending(scene)) > 0 else "")
                             + ", " + concentration(scene)[1] + ")") if bound > 0 else
                            ("no load compresses the joints (every principal stress is tensile or 0): "
                             f"they open; the table covers the largest stress magnitude, {cover * 1e-6:.3g} MPa")
                            ) + f", x {defaults.TABLE_MARGIN} margin",
                       cost="knots grow with log(range); a table evaluation costs ~0.05 µs whatever the law",
                       error="the loads cannot take a joint outside it (checked after the run)")
    fe, met = defaults.fe_settings(budget)
    measured = (f"the report's tunnels got {fe.measured_error:.2g} and {fe.measured_error_second_scene:.2g} "
                f"with these settings (bench/results/fe_speed_vs_error.md §8, budget {fe.error_budget:.0%})")
    if not met:
        measured += f"; no mesh of its sweep met {budget:.0%}: an error that small is not demonstrated"
    tol = choose("table tolerance", "table_tolerance", fe.table_tolerance, f"{fe.table_tolerance:g}",
                 text=lambda v: f"{v:g} relative on σ and k",
                 why=(f"the largest tolerance whose FE error stays below a tenth of a {fe.error_budget:.0%} "
                      "budget on the report's column and tunnel"),
                 cost="tens to hundreds of knots, built in well under a second",
                 error="the table's share of the answer: 1.2e-4 on the report's tunnel at 0.01, "
                       "1e-8 at 1e-6 (fe_speed_vs_error.md §5)")

    laws = {}
    for s in sets:
        law = d["joints"][s["name"]]["law"]
        if "topography" in law:
            points = law["topography"]["points"]
            if reduced:
                points = d["reduced"].get("topography_points", points)
            rung, met = ladder.cheapest_within(budget, points, tol)
            auto = rung.key
            key = over.get("law", auto)
            rungs = ladder.by_key()
            if key not in rungs:
                scene.fail(("plan", "law"), f"{key!r} is not on the accuracy ladder; one of "
                           f"{', '.join(rungs)}")
            r = rungs[key]
            why = ("set in the scene's plan (law)" if "law" in over else
                   f"least total cost within the {budget:.0%} budget of every way to the joint's curve" if met else
                   f"no rung meets the {budget:.0%} budget: the most accurate one")
            seconds = r.seconds(points, tol)
            what = ("the BEM solve of the exact contact" if key == ladder.EXACT_CONTACT else
                    f"the scan's analysis and the law's table ({r.evaluation * 1e6:.2f} µs per evaluation "
                    "while tabulating)")
            errors = ", ".join(f"{e:.1%} {f}" for f, e in r.errors.items())
            at = ladder.evidence_spacing()
            spacing = law["topography"]["spacing"]
            choices.append(Choice(
                f"law of {s['name']}", f"{key} ({r.label.replace('**', '')})", why=why,
                cost=f"~{seconds:.2g} s on the {points}² scan: {what} (bench/results/accuracy_ladder.json)",
                error=(f"closure vs the walls' exact contact at half the scan's spacing, "
                       f"{ladder.PREDICTION_LEVEL:.0%} upper prediction limit for a joint from the bench's joints "
                       f"scanned at {at * 1e3:g} mm: {errors} ("
                       + ("the BEM's resolution error + its table's" if key == ladder.EXACT_CONTACT else
                          "the law vs the scan's BEM + the BEM's resolution error")
                       + "; bench/results/accuracy_ladder.json)"
                       + ("" if spacing <= at * (1 + 1e-9) else
                          f"; this scan is coarser ({spacing * 1e3:g} mm): its resolution error is not measured"))))
            laws[s["name"]] = key
        else:
            how = next(k for k in ("model", "curve", "cycles", "table") if k in law)
            laws[s["name"]] = "given"
            choices.append(Choice(f"law of {s['name']}", f"the scene's {how}",
                                  why="a law given by the user is kept", cost="tabulated once",
                                  error="the law's own (not on the ladder); table error above"))

    slip = {}
    tensors = stage_stresses(scene)
    for s in sets:
        strength = d["joints"][s["name"]].get("strength")
        if strength is None:
            slip[s["name"]] = False
            continue
        if opening:
            hoop = max(defaults.OPENING_CONCENTRATION * max(0.0, -float(np.linalg.eigvalsh(t).min()))
                       for _, t, _ in tensors)
            ratio, where = wall_mobilised_friction(strength, hoop), "at the opening's wall (σ_r = 0)"
        else:
            n = geometry.set_normal(s, dim)
            ratio, where = max(mobilised_friction(strength, n, t) for _, t, _ in tensors), "on its plane"
        auto = ratio >= defaults.SLIP_MARGIN
        value = over.get("slip", auto)
        slip[s["name"]] = value
        choices.append(Choice(
            f"slip of {s['name']}", "joint strength and slip" if value else "elastic joints (no slip)",
            why=("set in the scene's plan (slip)" if "slip" in over else
                 f"mobilised friction τ/τ_max up to {_ratio(ratio)} {where} under the stress bound "
                 f"({'>=' if auto else '<'} {defaults.SLIP_MARGIN})"),
            cost=("a non-symmetric Jacobian (LU/GMRES) and small load steps" if value
                  else "none: symmetric Jacobian, one load step"),
            error=("path-dependent slip resolved per load step" if value else
                   f"joints stay below {defaults.SLIP_MARGIN:.0%} of their strength: slip cannot occur "
                   "unless stresses concentrate beyond the bound")))

    h = d["mesh"]["size"]
    if reduced and "mesh_size" in d["reduced"]:
        h = d["reduced"]["mesh_size"]
    refine = over.get("refine", True)
    spacing = _joint_spacing(scene)
    radius = g["opening"]["radius"] if opening else None
    hj = d["mesh"].get("joint_size", min(h, fe.joint_size_over_spacing * spacing)) \
        if (refine and sets) else None
    ho = d["mesh"].get("opening_size", min(h, fe.opening_size_over_radius * radius)) \
        if (refine and opening) else None
    degree = over.get("element_degree", fe.element_degree)
    quadrature = over.get("quadrature", fe.quadrature)
    dofs = _estimate_dofs(scene, dim, h, hj, ho)
    sizes = ", ".join(f for f in (
        f"{fe.joint_size_over_spacing:.3g} x joint spacing on joints" if hj else "",
        f"{fe.opening_size_over_radius:.3g} x radius on the opening" if ho else "") if f)
    choices.append(Choice(
        "mesh", f"P{degree}, {h:g} m far" + (f", {hj:g} m on joints" if hj else "")
        + (f", {ho:g} m on the opening" if ho else "") + f", {quadrature} joint rule",
        why=(f"the cheapest settings of the FE speed-vs-error report within {fe.error_budget:.0%}"
             + (f" ({sizes}; never coarser than the scene's size)" if sizes else "")
             + "; refined only near joints and openings"
             + ("; refinement switched off in the scene's plan" if not refine else "")),
        cost=f"~{dofs:.2g} dofs, ~{dofs * defaults.SECONDS_PER_DOF:.2g} s per Newton load step "
             "(fe_speed_vs_error.md §3 rate)",
        error=measured + "; uniform stress fields are exact with P1 (§1)"))
    any_slip = any(slip.values())
    steps = over.get("load_steps", defaults.LOAD_STEPS_SLIP if any_slip else fe.load_steps)
    if reduced and "load_steps" in d["reduced"]:
        steps = d["reduced"]["load_steps"]
    choices.append(Choice("load steps", f"{steps} per stage (unless the stage sets its own)",
                          why="slip is path dependent" if any_slip else "elastic joints: Newton from one step",
                          cost=f"~6 Newton iterations per step", error="none for elastic joints"))
    intact = over.get("intact", True)
    choices.append(Choice("intact model", "on the same mesh (split nodes glued)" if intact else "left out",
                          why="the joints' share of every answer is jointed minus intact",
                          cost="one linear solve per load step", error="none: same mesh, same solver"))
    smeared = _smeared_sets(scene, sets, budget, choices, dominance(scene, sets, dim))
    return Plan(dim, degree, quadrature, h, hj, ho, bound, table_top, tol, laws, slip, steps,
                intact, choices, reduced, smeared)


def dominance(scene, sets, dim) -> dict:
    """{set: mobilised friction τ/τ_max where the set is loaded hardest}: with an opening, on the
    set's plane under the uniaxial wall stress where the hoop stress peaks (Kirsch: 3 σ1 - σ3
    along the major compression σ1); otherwise on its plane under the stage stresses. 0 for a set
    without a strength. The largest is the dominant set, the one kept discrete in a mixed model."""
    d = scene.data
    opening = "opening" in d["geometry"]
    out = {}
    for s in sets:
        strength = d["joints"][s["name"]].get("strength")
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


def _smeared_sets(scene, sets, budget, choices, mobilised) -> tuple:
    """Discrete or smeared, set by set (defaults.SMEARED_EVIDENCE, the nearest measured spacing
    ratio at or above the set's: spacing over the opening radius, or half the section's smaller
    side). The dominant set (largest mobilised friction, `dominance`) is smeared only where the
    all-smeared model is within the budget and cheaper than the discrete one; any other set where
    the mixed model (dominant set discrete, the rest smeared) or the all-smeared one is. Error of
    a model: the larger of its crown and sidewall gaps to the discrete model. The scene's
    plan.smeared overrides."""
    g = scene.data["geometry"]
    over = scene.data["plan"].get("smeared")
    names = [s["name"] for s in sets]
    if over is not None:
        if g["kind"] == "column":
            scene.fail(("plan", "smeared"), "a column's joints are given one by one; only joint sets can be smeared")
        for name in over:
            if name not in names:
                scene.fail(("plan", "smeared"), f"no joint set '{name}'; joint sets: {', '.join(names)}")
    if g["kind"] == "column":
        return ()
    if "flow" in scene.data["outputs"]:   # the flow runs along the joint network (docs/flow.md)
        if over:
            scene.fail(("plan", "smeared"), "the scene asks for flow, which runs along the joint network: "
                       "flow through smeared sets and the rock around them is not modelled; keep the sets discrete")
        for s in sets:
            choices.append(Choice(f"joints of {s['name']}", "discrete (joint elements)",
                                  why="the scene asks for flow, which runs along the joint network",
                                  cost="joint elements on every joint of the set",
                                  error="none from the choice: the joints are meshed"))
        return ()
    size = g["opening"]["radius"] if "opening" in g else 0.5 * float(min(geometry.extent(g)))
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
                 + f"s/a = {ratio:.2g}; the {role} set (mobilised friction {_ratio(mobilised[s['name']])}); "
                 + f"{evidence} (bench/results/continuum.md)"
                 + ("" if value or over is not None else
                    "; smearing it is not both within the budget and cheaper")),
            cost="smeared: no joint elements, a quadrature-point material with a local Newton per point"
                 if value else "joint elements on every joint of the set",
            error=error))
    return tuple(chosen)
