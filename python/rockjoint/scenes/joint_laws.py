# SPDX-License-Identifier: MIT
"""The scene's joint laws, through the law factory (rockjoint.laws), the topography chain, the
calibration to a closure curve (rockjoint.calibration) or to load cycles (a law with history,
rockjoint.cycle_calibration) or a saved table, each tabulated over the plan's range."""
from __future__ import annotations

import logging

import rockjoint
from rockjoint import calibration, cycle_calibration, law_registry, laws
from rockjoint import topography as topo

from . import ladder

log = logging.getLogger("rockjoint.scenes")


def source_law(scene, set_name: str, plan):
    """The closure law of a joint set (before tabulation; a saved table is returned as it is)."""
    spec = scene.data["joints"][set_name]["law"]
    rock = scene.data["rock"]
    if "model" in spec:
        record, params, history = law_registry.get(spec["model"]), dict(spec["parameters"]), {}
        if record.history:   # the history's own parameters, and the virgin law it is built over
            history = {q.name: params.pop(q.name) for q in record.parameters}
            history["virgin"] = spec["virgin"]
            record = law_registry.get(spec["virgin"])
        if record.asperity:
            stats = rockjoint.AsperityParameters(
                composite_modulus=rockjoint.composite_modulus(rock["young"], rock["poisson"]), **params)
            return laws.make_law(spec["model"], stats, **history)
        return laws.make_law(spec["model"], **params, **history)
    if "table" in spec:
        return rockjoint.TabulatedLaw.load(spec["table"])
    if "curve" in spec:
        curve = calibration.read_closure_curve(spec["curve"], intact_length=spec.get("intact_length"),
                                               young_modulus=rock["young"] if "intact_length" in spec else None)
        fit = calibration.calibrate(curve, spec["fit"])
        log.info("joint set %s: %s calibrated to %s", set_name, spec["fit"], spec["curve"])
        return fit.law
    if "cycles" in spec:   # a law with history: the virgin law `fit` and its branches
        fit = cycle_calibration.calibrate_cycles(cycle_calibration.read_load_cycles(spec["cycles"]), spec["fit"])
        log.info("joint set %s: %s with unloading branches calibrated to the cycles of %s", set_name,
                 spec["fit"], spec["cycles"])
        return fit.law
    t = spec["topography"]
    n = t["points"]
    key = plan.laws[set_name]
    log.info("joint set %s: %s from a %dx%d topography at %.3g mm", set_name, key, n, n, t["spacing"] * 1e3)
    return topography_law(key, t, n, rock["young"], rock["poisson"], plan.table_max_stress)


def topography_law(key: str, topography: dict, points: int, young: float, poisson: float,
                   top_stress: float):
    """The law of rung `key` (scenes.ladder) for the synthetic mated pair `topography` (the scene's
    {hurst, rms_height, spacing, matedness, seed}) on a points² scan: the exact contact curve
    (BEM) up to `top_stress` [Pa], or a law of rockjoint.laws.laws_from_topography."""
    upper, lower = scan(topography, points)
    return law_of_walls(key, upper, lower, young, poisson, top_stress)


def scan(topography: dict, points: int) -> tuple:
    """(upper, lower) walls of the scene's synthetic mated pair on a points² scan."""
    t = topography
    return topo.mated_pair(topo.SelfAffineSpec(hurst_exponent=t["hurst"], rms_height=t["rms_height"]),
                           (points, points), t["spacing"], t["matedness"], seed=t["seed"])


def law_of_walls(key: str, upper, lower, young: float, poisson: float, top_stress: float):
    """The law of rung `key` for two scanned walls (topography.Surface, mated, no offset): what
    the planner's cost of that rung counts (scenes.ladder)."""
    joint = topo.composite_topography(upper, lower, offset=(0, 0))
    if law_registry.topography_laws()[key].needs == "walls":   # the walls' own contact: no statistics
        inputs = law_registry.TopographyInputs(None, {}, aperture=joint.aperture,
                                               composite_modulus=rockjoint.composite_modulus(young, poisson),
                                               stresses=ladder.contact_stresses(top_stress))
        return inputs.law(key)
    analysis = topo.analyse(joint.composite)
    params = topo.closure_parameters(analysis, young=young, poisson=poisson)
    return laws.laws_from_topography(params, summits=analysis, keys=(key,))[key].law


def tables(scene, plan) -> dict:
    """{joint set: tabulated law over the plan's normal-stress range} (a saved table and the
    exact contact curve are tables already)."""
    rungs = ladder.by_key()
    out = {}
    for name, spec in scene.data["joints"].items():
        law = source_law(scene, name, plan)
        rung = rungs.get(plan.laws.get(name))
        if "table" in spec["law"] or (rung is not None and not rung.tabulation):
            out[name] = law
            continue
        # laws over measured summits: a kink per summit, tabulated no tighter than the bench could
        tolerance = max(plan.table_tolerance, rung.tightest_tolerance if rung else 0.0)
        # A factor-of-safety search finds a mechanism by its singular system: the table's default
        # opening stiffness (1e-6 σ_max/Δ_max) would hold a freed block at a large displacement
        # instead (a cohesive plane failure held to F = 1.371 against 1.284 by limit equilibrium,
        # tests/python/test_fem_slope_scene_cohesive.py); open joints carry nothing there (k_res = 0)
        opening = 0.0 if "factor_of_safety" in scene.data else None
        out[name] = rockjoint.tabulate(law, max_stress=plan.table_max_stress, tolerance=tolerance,
                                       residual_stiffness=opening)
        log.info("joint set %s: table of %d knots up to %.3g MPa", name, rockjoint.curve_table(out[name]).knot_count,
                 plan.table_max_stress * 1e-6)
    return out
