# SPDX-License-Identifier: MIT
"""The `slope` scene kind (docs/slopes.md, "Slope scenes"): its geometry keys, its water and its
factor-of-safety request, in SI, and the section and joints they make. No FE stack: `rockjoint
plan` reads it too.

    geometry:
      kind: slope
      height: 30 m            # the face's height H
      face_angle: 65 deg      # ψ_f, from the horizontal
      base: 15 m              # rock below the toe (default H / 2)
      toe_distance: 20 m      # floor in front of the toe (default H)
      crest_distance: 40 m    # ground behind the crest (default H)
      joint_sets: [...]       # as every kind writes them, in the section's (x, y)
      benches: [{elevation: 15 m, width: 4 m}]               # optional: horizontal benches up the face
      tension_crack: {behind_crest: 8 m, ends_on: bedding}   # a vertical joint down to the set's highest joint
    water: {table: 40 m}      # the water table behind the crest, drawn down straight to the toe, or
    # water: {heads: {top: 45 m}, pressures: {face: 0 MPa}, coupling: two_way}: the flow, coupled
    factor_of_safety: {tolerance: 1 %}

A bench is a horizontal floor `width` wide at `elevation` above the toe; the faces between the
benches rise at face_angle (the overall slope is flatter: the crest moves back by the widths).
"""
from __future__ import annotations

import math

import numpy as np

from .. import meshes
from ..joint import JointStrength, StrengthModel
from ..meshes.slope import SlopeGeometry, slope_traces
from .fields import ListOf, Mapping, Quantity, Text

CRACK = "tension_crack"
FACES = ("bottom", "top", "left", "right", "face", "toe")
_LENGTH = dict(low=0.0, open_low=True)
#: the geometry keys only a slope has (GEOMETRY in schema.py takes them)
FIELDS = {
    "face_angle": Quantity("angle", low=0.0, high=math.pi / 2 + 1e-12, open_low=True, required=False),
    "base": Quantity("length", required=False, **_LENGTH),
    "toe_distance": Quantity("length", required=False, **_LENGTH),
    "crest_distance": Quantity("length", required=False, **_LENGTH),
    "benches": ListOf(Mapping({"elevation": Quantity("length", **_LENGTH), "width": Quantity("length", **_LENGTH)}),
                      required=False, min_length=1),
    CRACK: Mapping({"behind_crest": Quantity("length", **_LENGTH), "ends_on": Text()}, required=False)}

FACTOR_OF_SAFETY = Mapping({
    "tolerance": Quantity("fraction", low=0.0, high=0.5, open_low=True, required=False, default=0.01),
    "largest": Quantity("number", low=1.0, required=False, default=50.0)}, required=False)


def geometry_rule(g: dict, path: tuple, c) -> None:
    """The slope's keys on a slope only; its defaults (base H/2, toe and crest distances H)."""
    if g["kind"] != "slope":
        for key in FIELDS:
            if key in g:
                c.fail(path + (key,), f"not used by kind {g['kind']} (a slope's key)")
        return
    h = g["height"]
    below = 0.0
    for k, bench in enumerate(g.get("benches", [])):
        if not below < bench["elevation"] < h:
            c.fail(path + ("benches", k, "elevation"), f"{bench['elevation']:g} m must lie above the toe and the "
                   f"bench below ({below:g} m) and below the crest ({h:g} m)")
        below = bench["elevation"]
    g.setdefault("base", 0.5 * h)
    g.setdefault("toe_distance", h)
    g.setdefault("crest_distance", h)
    if CRACK in g and g[CRACK]["behind_crest"] >= g["crest_distance"]:
        c.fail(path + (CRACK, "behind_crest"), f"{g[CRACK]['behind_crest']:g} m is beyond the section "
               f"(crest_distance {g['crest_distance']:g} m)")


def section(g: dict) -> SlopeGeometry:
    """The SlopeGeometry of a checked slope geometry section."""
    return SlopeGeometry(g["height"], math.degrees(g["face_angle"]), g["base"], g["toe_distance"],
                         g["crest_distance"], tuple((b["elevation"], b["width"]) for b in g.get("benches", [])))


def set_joints(s: dict) -> list:
    """One joint set of the scene as meshes.Joint objects of the section (names <set>_<i>): a 3D
    slope is its section extruded along y, so a 3D set (which runs along y, the schema checks it)
    is the section's joint through (x, z)."""
    point = (s["point"][0], s["point"][-1])
    dip_direction = 90.0 if s["dip"] == 0.0 else math.degrees(s["dip_direction"])
    return meshes.joint_set(s["spacing"], math.degrees(s["dip"]), dip_direction, origin=point, count=s["count"],
                            name=s["name"])


def crack_joint(g: dict, joints: list):
    """The tension crack: a vertical joint `behind_crest` behind the crest, from the ground down to
    the highest joint of the set it `ends_on` there (that joint bounds it); ValueError if none of
    the set's joints passes below that point."""
    geo, spec = section(g), g[CRACK]
    x = geo.crest[0] + spec["behind_crest"]
    top = geo.base + geo.height
    best = None
    for joint, segments in zip(joints, slope_traces(geo, joints)):
        if joint.joint_set != spec["ends_on"]:
            continue
        for (x0, y0), (x1, y1) in segments:
            if min(x0, x1) < x < max(x0, x1):
                y = y0 + (x - x0) * (y1 - y0) / (x1 - x0)
                if y < top and (best is None or y > best[1]):
                    best = (joint.name, y)
    if best is None:
        raise ValueError(f"no joint of set {spec['ends_on']!r} passes below the crack {spec['behind_crest']:g} m "
                         "behind the crest: it would end inside a block")
    return meshes.Joint(point=(x, 0.5 * (top + best[1])), dip=90.0, dip_direction=90.0, name=CRACK,
                        bounded_by=(best[0],), joint_set=CRACK)


def joints(g: dict, exclude=()) -> list:
    """Every joint of the slope: its sets (without those in `exclude`) and its tension crack."""
    out = [j for s in g.get("joint_sets", []) if s["name"] not in exclude for j in set_joints(s)]
    if CRACK in g and g[CRACK]["ends_on"] in exclude:
        raise ValueError(f"the tension crack ends on set {g[CRACK]['ends_on']!r}, which the plan smears (an "
                         "equivalent continuum, `rockjoint plan` says why): a crack ends on discrete joints; "
                         "give that set a spacing the planner keeps discrete, or end the crack on another set")
    if CRACK in g:
        out.append(crack_joint(g, [j for s in g.get("joint_sets", []) for j in set_joints(s)]))
    return out


def check(d: dict, c) -> None:
    """The slope's relations: 2D sets that cross the section, a crack that ends on a set, the
    rock's weight (its density: the slope's only load besides the water), no uniform in-situ
    stress, the water a prescribed table or coupled flow; and a factor of safety asked of slopes only."""
    g = d["geometry"]
    if g["kind"] != "slope":
        if "factor_of_safety" in d:
            c.fail(("factor_of_safety",), f"the factor of safety is searched for slopes only, not a {g['kind']}")
        return
    names = [s["name"] for s in g.get("joint_sets", [])]
    if CRACK in names:
        c.fail(("geometry", "joint_sets"), f"{CRACK!r} is the tension crack's name: give the set another")
    geo = section(g)
    for i, s in enumerate(g.get("joint_sets", [])):
        inside = geo.contains(np.array([[s["point"][0], s["point"][-1]]]))[0]
        if not inside or (len(s["point"]) == 3 and not 0.0 < s["point"][1] < g["length"]):
            c.fail(("geometry", "joint_sets", i, "point"), "the point is not inside the slope section")
        for joint in set_joints(s):
            try:
                slope_traces(geo, [joint])
            except ValueError:
                c.fail(("geometry", "joint_sets", i), f"joint {joint.name} of set {s['name']} (point "
                       f"{joint.point[0]:.4g}, {joint.point[1]:.4g} m) misses the slope section: lower its count "
                       "or spacing")
    if CRACK in g:
        if g[CRACK]["ends_on"] not in names:
            c.fail(("geometry", CRACK, "ends_on"),
                   f"no joint set {g[CRACK]['ends_on']!r} (sets: {', '.join(names) or 'none'})")
        try:
            crack_joint(g, [j for s in g.get("joint_sets", []) for j in set_joints(s)])
        except ValueError as err:
            c.fail(("geometry", CRACK), str(err))
    if "density" not in d["rock"]:
        c.fail(("rock",), "missing key 'density': a slope is loaded by its own weight")
    if "in_situ" in d:
        c.fail(("in_situ",), "a slope's initial stress is its own weight (rock.density), not a uniform in-situ stress")
    w = d.get("water")
    if w is not None:   # prescribed (a table) or computed (flow between heads/pressures, coupled both ways)
        flowing = bool(w.get("heads") or w.get("pressures"))
        if flowing and "table" in w:
            c.fail(("water", "table"), "a slope's water is either the prescribed table (water.table) or the flow "
                                       "between heads and pressures (coupling: two_way), not both")
        elif flowing and w["coupling"] != "two_way":
            c.fail(("water", "coupling"), "a slope's flowing water must act on its joints: coupling: two_way "
                                          "(one way, the flow would not load the slope)")
        elif not flowing and w["coupling"] != "one_way":
            c.fail(("water", "coupling"), "a slope's prescribed table (water.table) is not coupled: coupling is "
                                          "for the flow between heads and pressures")
        elif not flowing and "table" not in w:
            c.fail(("water",), "missing key 'table' (the water table's elevation behind the crest), or the flow's "
                               "heads and pressures with coupling: two_way")


def sets(g: dict) -> list:
    """The slope's joint sets (as the planner and the statics read them), its crack a vertical one."""
    crack = [{"name": CRACK, "dip": math.pi / 2, "dip_direction": math.pi / 2,
              "spacing": section(g).width, "count": 1}] if CRACK in g else []
    return list(g.get("joint_sets", [])) + crack


def weight_stress(d: dict) -> np.ndarray:
    """The slope's largest homogeneous stress [Pa] (tension positive): its weight at the bottom,
    σ_v = ρ g (H + base), σ_h = ν/(1 - ν) σ_v (laterally confined elastic rock; 3D: both
    horizontal axes, the vertical is z)."""
    rock, g = d["rock"], d["geometry"]
    sv = rock["density"] * 9.80665 * (g["height"] + g["base"])
    k = rock["poisson"] / (1.0 - rock["poisson"])
    return -np.diag([k * sv] * (g["dimension"] - 1) + [sv])


def free_crack(d: dict, strengths: dict) -> None:
    """A tension crack given without a strength is open ground: no cohesion, no friction (it
    neither pulls nor holds the block behind it), the limit-equilibrium crack."""
    if _has_crack(d) and strengths.get(CRACK) is None:
        strengths[CRACK] = JointStrength(StrengthModel.coulomb, friction_angle=0.0, cohesion=0.0)


def _has_crack(d: dict) -> bool:
    return d["geometry"]["kind"] == "slope" and CRACK in d["geometry"]


def phreatic(g: dict, table: float):
    """p(x) [Pa] at joint points x (2, n): ρ_w g (z_w(x) - z) below the phreatic line z_w, 0 above:
    z_w = `table` behind the crest, drawn down straight to the toe under the face (which drains,
    as limit-equilibrium practice assumes: Hoek & Bray 1981); a crack below the line fills to it."""
    from ..fem import Fluid   # the FE stack is optional: this runs only when a slope is solved
    geo, fluid = section(g), Fluid()
    (x0, y0), x1 = geo.toe, geo.crest[0]

    def pressure(x):   # x: (gdim, n); the vertical is the last coordinate (3D: z, the section's y)
        z_w = y0 + (table - y0) * np.clip((np.asarray(x)[0] - x0) / max(x1 - x0, 1e-12), 0.0, 1.0)
        return fluid.density * fluid.gravity * np.maximum(z_w - np.asarray(x)[-1], 0.0)
    return pressure
