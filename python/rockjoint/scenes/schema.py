# SPDX-License-Identifier: MIT
"""The scene file schema (docs/scenes.md) and `load_scene`: a YAML file checked whole, in SI.

Every value is checked before anything is built or run: unknown keys, missing values, wrong units
and out-of-range values raise SceneError naming the key path and its line. Law parameters are
checked against the law registry (rockjoint.law_registry: a law's parameters and their units).
"""
from __future__ import annotations

import copy
import dataclasses
import math
import os

from .. import flow, law_registry
from ..joint import make_strength
from .fields import (Anything, Checker, Flag, Integer, ListOf, Mapping, NamedMapping, Quantity,
                     Text)
from .units import LAW_UNIT_DIMENSION, parse_quantity
from . import opening_keys, slope_keys, water_keys
from .yamlnodes import SceneError, compose

POSITIVE = dict(low=0.0, open_low=True)
_LENGTH = Quantity("length", **POSITIVE)
_POINT = ListOf(Quantity("length"), length=(2, 3))
_COMPONENTS = ("x", "y", "z", "xy", "xz", "yz", "xyz", "all")


def _geometry_rule(g, path, c):
    kind = g["kind"]
    need = {"column": ("width", "height", "joint_heights"), "block": ("size",),
            "tunnel": ("width", "height", "opening"), "slope": ("height", "face_angle")}[kind]
    for key in need:
        if key not in g:
            c.fail(path, f"missing key {key!r} (needed for kind {kind})")
    unused = {"column": ("size", "opening", "joint_sets", "length"),
              "block": ("width", "height", "joint_heights", "opening", "length"),
              "tunnel": ("size", "joint_heights"), "slope": ("size", "width", "opening", "joint_heights")}[kind]
    for key in unused:
        if key in g:
            c.fail(path + (key,), f"not used by kind {kind}")
    slope_keys.geometry_rule(g, path, c)
    if kind == "column":
        g["dimension"] = g.get("dimension", 2)
    elif kind == "block":
        g["dimension"] = len(g["size"])
    else:
        g["dimension"] = 3 if "length" in g else 2
    # the box in the order of a joint set's point: (x, y) in 2D; (x, y, z) in 3D, where a
    # tunnel's axis is y (its section, width by height, lies in the x-z plane)
    box = {"block": g.get("size"), "tunnel": [g.get("width"), g["length"], g.get("height")]
           if "length" in g else [g.get("width"), g.get("height")]}.get(kind)
    for i, s in enumerate(g.get("joint_sets", [])):
        if len(s["point"]) != g["dimension"]:
            c.fail(path + ("joint_sets", i, "point"), f"{len(s['point'])} coordinates in a "
                   f"{g['dimension']}D scene")
        if box is not None and not all(0.0 < x < b for x, b in zip(s["point"], box)):
            c.fail(path + ("joint_sets", i, "point"), "the point is not inside the geometry")
        along_x = s["dip"] == 0.0 or any(abs(s["dip_direction"] - math.radians(a)) < 1e-9
                                         for a in (90.0, 270.0))
        if g["dimension"] == 2 and not along_x:
            c.fail(path + ("joint_sets", i, "dip_direction"), "in 2D a joint dips toward +x "
                   "(90 deg) or -x (270 deg)")
        elif kind in ("tunnel", "slope") and g["dimension"] == 3 and not along_x:
            c.fail(path + ("joint_sets", i, "dip_direction"), f"in a 3D {kind} a joint set runs along "
                   f"{'the tunnel axis ' if kind == 'tunnel' else ''}y (the section is extruded along y): dip 0, or dip_direction "
                   "90 deg (dipping toward +x) or 270 deg (toward -x)")


JOINT_SET = Mapping({
    "name": Text(), "point": _POINT,
    "dip": Quantity("angle", low=0.0, high=math.pi / 2 + 1e-12, required=False, default=0.0),
    "dip_direction": Quantity("angle", low=0.0, high=2 * math.pi, required=False,
                              default=math.pi / 2),
    "spacing": Quantity("length", required=False, default=1.0, **POSITIVE),
    "count": Integer(low=1, high=200, required=False, default=1)})

GEOMETRY = Mapping({
    "kind": Text(choices=("column", "block", "tunnel", "slope")),
    "dimension": Integer(low=2, high=3, required=False),
    "width": Quantity("length", required=False, **POSITIVE),
    "height": Quantity("length", required=False, **POSITIVE),
    "length": Quantity("length", required=False, **POSITIVE),
    "size": ListOf(_LENGTH, length=(2, 3), required=False),
    "joint_heights": ListOf(Quantity("length", **POSITIVE), required=False, min_length=1),
    "joint_sets": ListOf(JOINT_SET, required=False),
    "opening": opening_keys.OPENING,
    **slope_keys.FIELDS,
}, rule=_geometry_rule)

ELASTIC = Mapping({"young": Quantity("stress", **POSITIVE),
                   "poisson": Quantity("number", low=-0.99, high=0.499),
                   "density": Quantity("density", required=False, **POSITIVE)})
ROCK = Mapping({**ELASTIC.fields, "blocks": NamedMapping(ELASTIC, required=False),
               "permeability": Quantity("permeability", low=0.0, required=False)})

TOPOGRAPHY = Mapping({
    "hurst": Quantity("number", low=0.0, high=1.0, open_low=True),
    "rms_height": Quantity("length", **POSITIVE),
    "points": Integer(low=16, high=4096),
    "spacing": Quantity("length", **POSITIVE),
    "matedness": Quantity("length", **POSITIVE),
    "seed": Integer(low=0, required=False, default=1)})

def _strength_rule(v, path, c):
    if v["model"] == "barton":
        for key in ("jrc", "jcs"):
            if key not in v:
                c.fail(path, f"missing key {key!r} (needed for Barton's strength)")


STRENGTH = Mapping({
    "model": Text(choices=("coulomb", "barton")),
    "friction_angle": Quantity("angle", low=0.0, high=math.radians(89.0)),
    "cohesion": Quantity("stress", low=0.0, required=False, default=0.0),
    # T (default 0: no tension); at most c / tan φ, the apex of the Coulomb line (C++ checks it)
    "tensile_strength": Quantity("stress", low=0.0, required=False),
    "jrc": Quantity("number", low=0.0, high=20.0, required=False),
    "jcs": Quantity("stress", required=False, **POSITIVE),
    "dilation_angle": Quantity("angle", low=0.0, high=math.radians(60.0), required=False),
    "dilation_limit": Quantity("length", low=0.0, required=False),
    "maximum_friction_angle": Quantity("angle", low=0.0, high=math.radians(89.0), required=False)},
    rule=_strength_rule)


def _law_parameters(law, path, c):
    """A registered law's parameters (converted to SI): its own, or for an asperity law the summit
    statistics (E* comes from the rock); a law with history takes the history's (r, m) beside those
    of the registered law its `virgin` names. Names, units and ranges: the law's record
    (law_registry, from the C++ law's own metadata)."""
    laws = law_registry.parametric_laws()
    record = laws.get(law["model"])
    if record is None:
        c.fail(path + ("model",), f"{law['model']!r} is not a registered law; one of {', '.join(sorted(laws))}")
    names = {}
    if record.history:
        virgin = laws.get(law.get("virgin"))
        if virgin is None or virgin.history:
            c.fail(path + ("virgin",), f"a law with history needs virgin: a registered law without history, "
                   f"one of {', '.join(sorted(k for k, r in laws.items() if not r.history))}; "
                   f"got {law.get('virgin')!r}")
        names.update({q.name: q for q in record.quantities()})   # r and m (docs/hysteresis.md, H1-H2)
        record = virgin
    elif "virgin" in law:
        c.fail(path + ("virgin",), f"goes with a law with history, not {record.key}")
    names.update({q.name: q for q in record.quantities()})
    params = law.get("parameters") or {}
    for key in params:
        if key not in names:
            c.fail(path + ("parameters", key), f"unknown parameter {key!r} of {law['model']}; "
                   f"expected {', '.join(names)}")
    out = {}
    for key, q in names.items():
        if key not in params:
            c.fail(path + ("parameters",), f"missing parameter {key!r} ({q.symbol}, {q.unit})")
        try:
            out[key] = parse_quantity(params[key], LAW_UNIT_DIMENSION[q.unit])
        except ValueError as err:
            c.fail(path + ("parameters", key), str(err))
        problem = q.problem(out[key])   # the one range check (the C++ law's range)
        if problem:
            c.fail(path + ("parameters", key), f"{params[key]!r} is out of range: {problem}")
    law["parameters"] = out


def _law_rule(law, path, c):
    given = [k for k in ("model", "topography", "curve", "cycles", "table") if k in law]
    if len(given) != 1:
        c.fail(path, "give exactly one of model (with parameters), topography, curve, cycles or table; "
                     f"got {', '.join(given) or 'none'}")
    if "model" in law:
        _law_parameters(law, path, c)
    elif "parameters" in law or "virgin" in law:
        c.fail(path + ("parameters" if "parameters" in law else "virgin",), "goes with model")
    for key in ("curve", "cycles", "table"):
        if key in law:
            law[key] = os.path.join(c.base, law[key])
            if not os.path.isfile(law[key]):
                c.fail(path + (key,), f"no file {law[key]}")
    if "fit" in law and not ("curve" in law or "cycles" in law):
        c.fail(path + ("fit",), "goes with curve or cycles (measured data to calibrate)")
    if "intact_length" in law and "curve" not in law:
        c.fail(path + ("intact_length",), "goes with curve (a measured curve to calibrate)")
    for key, what in (("curve", "e.g. barton_bandis"), ("cycles", "the virgin law, e.g. barton_bandis")):
        if key in law and "fit" not in law:
            c.fail(path, f"{key} needs fit: the law to calibrate ({what})")


LAW = Mapping({
    "model": Text(required=False), "parameters": Anything(required=False), "virgin": Text(required=False),
    "topography": Mapping(TOPOGRAPHY.fields, required=False),
    "curve": Text(required=False), "cycles": Text(required=False), "fit": Text(required=False),
    "intact_length": Quantity("length", required=False, **POSITIVE),
    "table": Text(required=False)}, rule=_law_rule)

def _flow_law_rule(v, path, c):
    """A transmissivity law of rockjoint.flow with its parameters (docs/flow.md); one built from the
    walls takes the set's own (checked against its law in _cross_checks)."""
    if v.get("law") not in flow.TRANSMISSIVITY_LAWS:
        c.fail(path + ("law",), f"{v.get('law')!r} is not a transmissivity law; one of "
               f"{', '.join(sorted(flow.TRANSMISSIVITY_LAWS))}")
    record = flow.TRANSMISSIVITY_LAWS[v["law"]]
    for key in sorted(set(v) - {"law"}):
        if key not in record.parameters:
            c.fail(path + (key,), f"not a parameter of {v['law']} ({', '.join(flow.user_parameters(v['law'])) or 'none'})")
    for key in flow.user_parameters(v["law"], required=True):
        if key not in v:
            c.fail(path, f"{v['law']} needs {key} ({record.parameters[key]})")
    if not v.get("hydraulic_loss", 0.0) < 1.0:
        c.fail(path + ("hydraulic_loss",), f"{v['hydraulic_loss']} is out of range: the hydraulic loss d must be in "
                                           "[0, 1) (1 would keep no aperture on unloading)")


FLOW_LAW = Mapping({"law": Text(), "initial_aperture": Quantity("length", required=False, **POSITIVE),
                    "jrc": Quantity("number", required=False, low=0.0, open_low=True),
                    "component": Text(required=False),
                    # hydraulic_history (issue 41): its loss d in [0, 1) and the virgin law's key
                    "hydraulic_loss": Quantity("number", required=False, low=0.0),
                    "virgin": Text(choices=("cubic_law", "barton_jrc"), required=False)},
                   required=False, rule=_flow_law_rule)

JOINT = Mapping({
    "law": LAW,
    "flow": FLOW_LAW,
    "shear_stiffness_ratio": Quantity("number", low=0.0, required=False, default=0.1),
    "residual_stiffness": Quantity("stiffness", low=0.0, required=False, default=0.0),
    "strength": Mapping(STRENGTH.fields, required=False, rule=_strength_rule)})

IN_SITU = Mapping({"vertical": Quantity("stress", low=0.0),
                   "horizontal_ratio": Quantity("number", low=0.0, high=10.0, required=False,
                                                default=1.0)}, required=False)

LOAD = Mapping({"traction": ListOf(Quantity("stress"), length=(2, 3), required=False),
                "pressure": Quantity("stress", required=False)},
               rule=lambda v, p, c: None if len(v) == 1 else
               c.fail(p, "give exactly one of traction or pressure"))

STAGE = Mapping({"name": Text(), "steps": Integer(low=1, high=1000, required=False),
                 "excavate": Text(required=False),
                 "loads": NamedMapping(LOAD, required=False, default={}),
                 "water": water_keys.STAGE_WATER})

MESH = Mapping({"size": Quantity("length", **POSITIVE),
                "joint_size": Quantity("length", required=False, **POSITIVE),
                "opening_size": Quantity("length", required=False, **POSITIVE)})

PLAN = Mapping({"dimension": Integer(low=2, high=3, required=False),
                "law": Text(required=False),
                "table_max_stress": Quantity("stress", required=False, **POSITIVE),
                "table_tolerance": Quantity("fraction", required=False, **POSITIVE),
                "slip": Flag(), "refine": Flag(), "intact": Flag(),
                "smeared": ListOf(Text(), required=False),
                "element_degree": Integer(low=1, high=2, required=False),
                "quadrature": Text(choices=("nodal", "gauss"), required=False),
                "load_steps": Integer(low=1, high=1000, required=False)}, required=False,
               default={})

OUTPUTS = Mapping({"pictures": Flag(default=True), "xdmf": Flag(default=True),
                   "monitor": ListOf(Text(), required=False, default=[]),
                   "flow": Mapping({"heads": NamedMapping(Quantity("length"))}, required=False)},
                  required=False, default={"pictures": True, "xdmf": True, "monitor": []})

REDUCED = Mapping({"mesh_size": Quantity("length", required=False, **POSITIVE),
                   "topography_points": Integer(low=16, high=4096, required=False),
                   "load_steps": Integer(low=1, high=1000, required=False)},
                  required=False, default={})

SCENE = Mapping({
    "name": Text(), "description": Text(required=False),
    "geometry": GEOMETRY, "rock": ROCK,
    "joints": NamedMapping(JOINT, required=False, default={}),
    "in_situ": IN_SITU,
    "supports": NamedMapping(Text(choices=_COMPONENTS)),
    "stages": ListOf(STAGE, min_length=1),
    "error_budget": Quantity("fraction", low=0.0, high=1.0, open_low=True),
    "mesh": MESH, "outputs": OUTPUTS, "plan": PLAN, "reduced": REDUCED, "water": water_keys.WATER,
    "factor_of_safety": slope_keys.FACTOR_OF_SAFETY})


@dataclasses.dataclass
class Scene:
    """A checked scene: `data` in SI, where it came from (file, lines) for later messages;
    `reduced` for the scene at its reduced size (at_reduced_size); `strengths`: each joint set's
    strength, built once from its `strength:` section ({set: JointStrength, or None without one}),
    the one object the planner, the statics, the model and the smeared material use."""

    data: dict
    source: str
    lines: dict
    reduced: bool = False
    strengths: dict = dataclasses.field(default_factory=dict)

    def fail(self, path: tuple, message: str):
        """Raise SceneError naming the scene file, the line of `path` and the key path, with `message`."""
        _checker(self.source, self.lines).fail(path, message)

    def __getitem__(self, key):
        return self.data[key]

    def at_reduced_size(self) -> "Scene":
        """The scene as its `reduced:` section makes it (tests, quick runs), built once before
        planning so that the planner, the laws and the runner read it as any scene: the far-field
        mesh size, the scans' points, and one number of load steps for every stage (the reduced
        `load_steps`, or the plan's: a stage's own steps are dropped)."""
        data = copy.deepcopy(self.data)
        reduced = data["reduced"]
        if "mesh_size" in reduced:
            data["mesh"]["size"] = reduced["mesh_size"]
        if "topography_points" in reduced:
            for joint in data["joints"].values():
                if "topography" in joint["law"]:
                    joint["law"]["topography"]["points"] = reduced["topography_points"]
        if "load_steps" in reduced:
            data["plan"]["load_steps"] = reduced["load_steps"]
        for stage in data["stages"]:
            stage.pop("steps", None)
        return dataclasses.replace(self, data=data, reduced=True)


def _checker(source, lines):
    c = Checker(source, lines)
    c.base = os.path.dirname(os.path.abspath(source))
    return c


def _cross_checks(d: dict, c: Checker) -> None:
    """Relations between sections: joint sets have laws, loads name boundaries that exist."""
    g = d["geometry"]
    sets = [s["name"] for s in g.get("joint_sets", [])] if g["kind"] != "column" else ["joint"]
    sets += [slope_keys.CRACK] if slope_keys.CRACK in g else []
    for name in d["joints"]:
        if name not in sets:
            c.fail(("joints", name), f"no joint set {name!r} in the geometry (sets: "
                                     f"{', '.join(sets) or 'none'})")
    for name in sets:
        if name not in d["joints"]:
            c.fail(("joints",), f"joint set {name!r} of the geometry has no entry")
    faces = ["bottom", "top", "left", "right"] + (["front", "back"] if g["dimension"] == 3 else [])
    if g["kind"] == "tunnel":
        faces.append("opening")
    faces = list(slope_keys.FACES) + faces[4:6] if g["kind"] == "slope" else faces
    slope_keys.check(d, c)
    where = [(("supports", k), k) for k in d["supports"]]
    for i, stage in enumerate(d["stages"]):
        where += [(("stages", i, "loads", k), k) for k in stage["loads"]]
        if "excavate" in stage:
            where.append((("stages", i, "excavate"), stage["excavate"]))
        for k, load in stage["loads"].items():
            if "traction" in load and len(load["traction"]) != g["dimension"]:
                c.fail(("stages", i, "loads", k, "traction"),
                       f"{len(load['traction'])} components in a {g['dimension']}D scene")
    where += [(("outputs", "monitor", i), face) for i, face in enumerate(d["outputs"]["monitor"])]
    where += water_keys.boundary_names(d)
    water_keys.check(d, c)
    for path, face in where:
        if face not in faces:
            c.fail(path, f"no boundary {face!r}; one of {', '.join(faces)}")
    for i, h in enumerate(g.get("joint_heights", [])):
        if h >= g["height"]:
            c.fail(("geometry", "joint_heights", i), f"{h:g} m is not inside the column "
                                                     f"(height {g['height']:g} m)")
    if g["kind"] == "tunnel":
        opening_keys.check_inside(g, c)
    if d["mesh"]["size"] > max(g.get("size", [g.get("width", 0), g.get("height", 0)])):
        c.fail(("mesh", "size"), "larger than the whole scene")


def check_scene(data, lines: dict, source: str) -> Scene:
    """The checked Scene of the parsed YAML `data` ({key path: line} in `lines`, file name `source`).

    Raises SceneError naming the file, line and key of the first mistake.
    """
    c = _checker(source, lines)
    d = SCENE.check(data, (), c)
    _cross_checks(d, c)
    strengths = _strengths(d, c)
    slope_keys.free_crack(d, strengths)
    return Scene(d, source, lines, strengths=strengths)


def _strengths(d: dict, c: Checker) -> dict:
    """{set: JointStrength or None} of the scene's joint sets, built once (the C++ checks of a
    strength, e.g. Barton's JCS against its friction cap, named at the set's strength line)."""
    out = {}
    for name, joint in d["joints"].items():
        spec = joint.get("strength")
        try:
            out[name] = None if spec is None else make_strength(spec, name)
        except ValueError as err:
            c.fail(("joints", name, "strength"), str(err))
    return out


def load_scene(path) -> Scene:
    """Read and check a scene file (SceneError naming the key and line for any mistake)."""
    path = os.fspath(path)
    try:
        with open(path, encoding="utf-8") as f:
            text = f.read()
    except OSError as err:
        raise SceneError(f"{path}: cannot read the scene: {err.strerror}") from err
    data, lines = compose(text, path)
    return check_scene(data, lines, path)
