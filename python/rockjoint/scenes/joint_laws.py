"""The scene's joint laws, through the law factory (rockjoint.laws), the topography chain, the
calibration (rockjoint.calibration) or a saved table, each tabulated over the plan's range."""
from __future__ import annotations

import logging

from . import defaults

log = logging.getLogger("rockjoint.scenes")


def source_law(scene, set_name: str, plan, reduced: bool = False):
    """The closure law of a joint set (before tabulation; a saved table is returned as it is)."""
    import rockjoint
    from rockjoint import calibration, law_registry, laws
    spec = scene.data["joints"][set_name]["law"]
    rock = scene.data["rock"]
    if "model" in spec and law_registry.get(spec["model"]).asperity:
        p = spec["parameters"]
        stats = rockjoint.AsperityParameters(
            composite_modulus=rockjoint.composite_modulus(rock["young"], rock["poisson"]),
            summit_density=p["summit_density"], summit_radius=p["summit_radius"],
            summit_height_std=p["summit_height_std"])
        return laws.make_law(spec["model"], stats)
    if "model" in spec:
        return laws.make_law(spec["model"], **spec["parameters"])
    if "table" in spec:
        return rockjoint.TabulatedLaw.load(spec["table"])
    if "curve" in spec:
        curve = calibration.read_closure_curve(spec["curve"], intact_length=spec.get("intact_length"),
                                               young_modulus=rock["young"] if "intact_length" in spec else None)
        fit = calibration.calibrate(curve, spec["fit"])
        log.info("joint set %s: %s calibrated to %s", set_name, spec["fit"], spec["curve"])
        return fit.law
    from rockjoint import topography as topo
    t = spec["topography"]
    n = scene.data["reduced"].get("topography_points", t["points"]) if reduced else t["points"]
    upper, lower = topo.mated_pair(topo.SelfAffineSpec(hurst_exponent=t["hurst"], rms_height=t["rms_height"]),
                                   (n, n), t["spacing"], t["matedness"], seed=t["seed"])
    analysis = topo.analyse(topo.composite_topography(upper, lower, offset=(0, 0)).composite)
    params = topo.closure_parameters(analysis, young=rock["young"], poisson=rock["poisson"])
    key = plan.laws[set_name]
    family = laws.laws_from_topography(params, summits=analysis, empirical=key.endswith("_empirical"))
    log.info("joint set %s: %s from a %dx%d topography at %.3g mm", set_name, key, n, n, t["spacing"] * 1e3)
    return family[key].law


def tables(scene, plan, reduced: bool = False) -> dict:
    """{joint set: tabulated law over the plan's normal-stress range}."""
    import rockjoint
    out = {}
    for name, spec in scene.data["joints"].items():
        law = source_law(scene, name, plan, reduced)
        if "table" in spec["law"]:
            out[name] = law
            continue
        tolerance = plan.table_tolerance
        if plan.laws.get(name, "").endswith("_empirical"):  # kinks: defaults.TABLE_TOLERANCE_EMPIRICAL
            tolerance = max(tolerance, defaults.TABLE_TOLERANCE_EMPIRICAL)
        out[name] = rockjoint.tabulate(law, max_stress=plan.table_max_stress, tolerance=tolerance)
        log.info("joint set %s: table of %d knots up to %.3g MPa", name, out[name].knot_count,
                 plan.table_max_stress * 1e-6)
    return out
