# SPDX-License-Identifier: MIT
"""The scene's water (docs/flow.md, "Water in scenes"): the schema of its `water:` section and the
relations it has with the rest of the scene, in SI. No FE stack: `rockjoint plan` reads it too.

    water:
      table: 140 m              # elevation (the last coordinate) of the initial water table
      coupling: two_way         # one_way (default) | two_way
      heads: {left: 140 m}      # hydraulic heads h [m] on named boundaries
      pressures: {top: 0 MPa}   # water pressures p [Pa] on named boundaries (h = z + p / (ρ g))
      opening: drained          # a tunnel's opening once excavated: drained (p = 0) | lined (no flow)

A stage may let the water flow for a given time instead of to its steady state (transient flow
with storage, rockjoint.fem.water.transient): ``stages: [{name: ..., water: {duration: 30 d,
steps: 10}}]``, implicit time steps after the stage's mechanics, one way or two way as the
scene's coupling says.

The older `outputs: {flow: {heads}}` (one way, the joints dry) stays; a scene gives one or the
other.
"""
from __future__ import annotations

from .. import flow
from .fields import Integer, Mapping, NamedMapping, Quantity, Text

COUPLINGS = ("one_way", "two_way")


def _water_rule(w, path, c):
    if w["coupling"] == "two_way" and not (w.get("heads") or w.get("pressures") or w.get("opening") == "drained"):
        c.fail(path + ("coupling",), "two_way needs the flow's boundaries: heads, pressures or opening: drained")


WATER = Mapping({
    "table": Quantity("length", required=False),
    "coupling": Text(choices=COUPLINGS, required=False, default="one_way"),
    "heads": NamedMapping(Quantity("length"), required=False),
    "pressures": NamedMapping(Quantity("stress", low=0.0), required=False),
    "opening": Text(choices=("drained", "lined"), required=False)}, required=False, rule=_water_rule)


STAGE_WATER = Mapping({"duration": Quantity("time", low=0.0, open_low=True),
                       "steps": Integer(low=1, high=1000, required=False, default=10)}, required=False)


def flows(d: dict) -> bool:
    """True if the scene's checked data `d` asks for flow along the joints (outputs.flow, or water
    with boundaries the flow runs between)."""
    w = d.get("water", {})
    return "flow" in d["outputs"] or bool(w.get("heads") or w.get("pressures") or w.get("opening") == "drained")


def boundary_names(d: dict) -> list:
    """[(key path, boundary name)] of every boundary the water names (checked against the faces)."""
    w = d.get("water", {})
    out = [(("outputs", "flow", "heads", k), k) for k in d["outputs"].get("flow", {}).get("heads", {})]
    for kind in ("heads", "pressures"):
        out += [(("water", kind, k), k) for k in w.get(kind, {})]
    return out


def check(d: dict, c) -> None:
    """Relations of the water with the scene: one way to give the flow, an initial table needs
    the in-situ stress that holds it, `opening` belongs to a tunnel (and a tunnel's water says
    what its opening is), and every joint set of a scene with flow has its transmissivity."""
    g, w = d["geometry"], d.get("water")
    if w is not None:
        if "flow" in d["outputs"]:
            c.fail(("outputs", "flow"), "the scene has water: give the flow's boundaries there (water: {heads: ...}), "
                                        "not in outputs")
        if "table" in w and "in_situ" not in d and g["kind"] != "slope":   # a slope's table is prescribed
            c.fail(("water", "table"), "an initial water table needs the in-situ stress that holds it (in_situ:)")
        if g["kind"] != "tunnel" and "opening" in w:
            c.fail(("water", "opening"), f"a {g['kind']} has no opening")
        if g["kind"] == "tunnel":
            if "opening" not in w:
                c.fail(("water",), "missing key 'opening': is the tunnel drained (p = 0 on its wall) or lined (no flow)?")
            for kind in ("heads", "pressures"):
                if "opening" in w.get(kind, {}):
                    c.fail(("water", kind, "opening"), "the opening's water is water.opening (drained or lined)")
        if d["plan"].get("smeared"):
            c.fail(("plan", "smeared"), "the water runs along the joint network and acts on the joints: "
                                        "smeared sets are not modelled with water; keep the sets discrete")
    for i, stage in enumerate(d["stages"]):
        if "water" in stage and not (w is not None and flows(d)):
            c.fail(("stages", i, "water"), "a transient water stage needs the scene's water with the flow's "
                                           "boundaries (water: {heads, pressures or opening: drained})")
    if not flows(d):
        return
    for name, joint in d["joints"].items():
        if "flow" not in joint:
            c.fail(("joints", name), "the scene asks for flow: give the set's transmissivity "
                                     "(flow: {law: ...}, docs/flow.md)")
        if flow.built_from_walls(joint["flow"]["law"]) and "topography" not in joint["law"]:
            c.fail(("joints", name, "flow", "law"), f"{joint['flow']['law']} needs the set's walls: "
                   "its law must be a topography")
