# SPDX-License-Identifier: MIT
"""A scene's water (its `water:` section, water_keys.py, or `outputs: {flow: {heads}}`; docs/flow.md):
every joint set's transmissivity law T(Δ) (its `flow:` entry: from its own walls, or a conversion of
its mechanical aperture); the water table's hydrostatic water in the joints from the initial state
on; and after every stage the steady flow between the boundaries' heads and pressures: along the
jointed model's joint network, one way (each point's T from its closure then, the joints seeing
only the table's water) or two ways (the network's pressure acting on the joints, coupled to the
equilibrium: rockjoint.fem.water.coupled), and through the intact model when the rock has a
permeability (Darcy), beside it.
"""
from __future__ import annotations

import dataclasses
import logging

import numpy as np

import rockjoint
from rockjoint import Status, contact, flow
from rockjoint import topography as topo

from ..fem import Fluid, darcy_flow, network_flow
from ..fem.water.coupled import coupled_steady, gathered_pressure, pressure_at_points, scatter_pressure
from ..fem.water.joint_pressure import set_initial_joint_pressure
from ..meshes import joint_sets_of
from . import joint_laws, ladder, water_keys

log = logging.getLogger("rockjoint.scenes")


def requested(scene) -> bool:
    """True if the scene asks for the joints' flow (`outputs: {flow: ...}`, or `water:` with
    boundaries the flow runs between)."""
    return water_keys.flows(scene.data)


def transmissivity_laws(scene, plan) -> dict:
    """{joint set: rockjoint.flow.TransmissivityLaw} of the scene's `flow:` entries; a set whose
    law is a topography can take `law: walls`: T(Δ) of the same walls (BEM contact and Reynolds
    flow at the loads of its exact contact curve, up to the plan's table stress)."""
    out = {}
    rock = scene.data["rock"]
    for name, spec in scene.data["joints"].items():
        given = dict(spec["flow"])
        key = given.pop("law")
        if flow.built_from_walls(key):
            t = spec["law"]["topography"]
            n = t["points"]
            upper, lower = joint_laws.scan(t, n)
            aperture = topo.composite_topography(upper, lower, offset=(0, 0)).aperture
            curve = contact.closure_curve(aperture, rockjoint.composite_modulus(rock["young"], rock["poisson"]),
                                          ladder.contact_stresses(plan.table_max_stress), flow=True)
            given["curve"] = curve
            log.info("joint set %s: transmissivity from its walls (%dx%d, %d loads)", name, n, n,
                     curve.closure.size)
        out[name] = flow.transmissivity_law(key, **given)
    return out


def conditions(scene, excavated) -> tuple:
    """(heads {boundary: h [m]}, pressures {boundary: p [Pa]}) of the flow in a stage after the
    boundaries `excavated` were excavated: a drained opening has p = 0 once it is excavated (before,
    the rock fills it and no water leaves there); a lined one lets none through (no condition)."""
    d = scene.data
    if "flow" in d["outputs"]:
        return dict(d["outputs"]["flow"]["heads"]), {}
    w = d.get("water", {})
    heads, pressures = dict(w.get("heads", {})), dict(w.get("pressures", {}))
    if w.get("opening") == "drained" and "opening" in excavated:
        pressures["opening"] = 0.0
    return heads, pressures


def hydrostatic(table: float, fluid: Fluid = Fluid()):
    """p(x) = ρ g (z_table - z) below the table, 0 above [Pa] (z the last coordinate of x (gdim, n))."""
    return lambda x: fluid.density * fluid.gravity * np.maximum(table - np.asarray(x)[-1], 0.0)


def initial_water(scene, model) -> None:
    """The water table's hydrostatic water in the joints of `model` from the initial state on."""
    table = scene.data.get("water", {}).get("table")
    if table is not None:
        set_initial_joint_pressure(model, hydrostatic(table))


@dataclasses.dataclass
class StageWater:
    """The water of one stage of one model."""

    #: {boundary with a condition: flow into the rock there [m³/s; m²/s per metre in 2D]};
    #: None: no flow asked for, or the intact rock has none
    flow_rates: dict | None = None
    network: object = None          #: the jointed model's NetworkFlow
    max_pressure: float = 0.0       #: the largest water pressure in the joints [Pa]
    opened_by_water: int = 0        #: joint points held open by water (opened_by_water)
    iterations: int = 0             #: staggered iterations of the two-way coupling (0: one way)
    wet: bool = False               #: the scene has water and the model joints to hold it


def after_stage(scene, model, solution, laws: dict | None, excavated, name: str) -> tuple:
    """(the stage's final StageResult, StageWater) after `solution` was solved. The jointed model
    (`laws`: {joint set: TransmissivityLaw}) with `coupling: two_way`: the coupled steady state
    (coupled_steady: each iteration a stage '<name>: water k'; the last one is returned); one way:
    the network at the stage's closures. The intact model: Darcy with the rock's permeability
    between heads (none with pressures given: Darcy here takes uniform heads only)."""
    water = StageWater()
    heads, pressures = conditions(scene, excavated)
    bcs = dict(heads=heads, **({"pressures": pressures} if pressures else {}))
    flows = requested(scene) and bool(heads or pressures)   # e.g. a drained opening not yet excavated: no flow
    if flows and laws is not None:
        per_joint = _per_joint(model, laws)
        if two_way(scene):
            coupled = coupled_steady(model, per_joint, name=f"{name}: water", **bcs)
            solution, network, water.iterations = model.stages[-1], coupled.network, coupled.iterations
        else:
            network = network_flow(model, per_joint, stage=solution, **bcs)
        water.flow_rates, water.network = network.flow_rates, network
    elif flows and not pressures and scene.data["rock"].get("permeability") is not None:
        k = scene.data["rock"]["permeability"]
        water.flow_rates = darcy_flow(model.dmesh, k * np.eye(model.gdim), heads).flow_rates
    if "water" in scene.data and model.behaviours:   # the jointed model: its joints hold the water
        water.wet = True
        water.max_pressure, opened = opened_by_water(model, solution)
        water.opened_by_water = int(np.count_nonzero(opened))
    return solution, water


def two_way(scene) -> bool:
    """The scene's water acts on the joints, coupled to the equilibrium (coupling: two_way)."""
    return scene.data.get("water", {}).get("coupling") == "two_way"


def _per_joint(model, laws: dict) -> dict:
    """{joint name: T(closure)} of the model's joints from {joint set: TransmissivityLaw}."""
    return {n: laws[s].transmissivity for n, s in joint_sets_of(model.dmesh.names).items()}


def before_stage(scene, model, laws: dict | None, excavated) -> None:
    """Two ways, before a stage is solved: the water its conditions bring (e.g. an opening drained
    as it is excavated), the network at the last closures, ramped over the stage with its loads, so
    that the joints drain or fill while the rock moves (slip is path dependent); after the stage
    the coupling corrects it (after_stage). Nothing one way, or before the first stage."""
    heads, pressures = conditions(scene, excavated)
    if laws is None or not two_way(scene) or not model.stages or not (heads or pressures):
        return
    last = model.stages[-1]
    network = network_flow(model, _per_joint(model, laws), heads=heads, stage=last,
                           **({"pressures": pressures} if pressures else {}))
    x = np.asarray(last.gather_joints()["coordinates"], dtype=float).reshape(-1, model.gdim)
    scatter_pressure(model, last, pressure_at_points(network, x, network.fluid))


def opened_by_water(model, solution) -> tuple:
    """(the largest joint pressure p [Pa], a mask of the points opened by water), gathered: a joint
    point is opened by water when it is open (status open: its walls apart, its law carrying nothing)
    while water fills it (p > 0) and its total normal stress σ_n = σ'_n + α p is compressive
    (> 0): the rock presses the walls together and only the water holds them apart. A point pulled
    open by the rock (σ_n <= 0) is not counted. Collective."""
    state, p = solution.gather_joints(), gathered_pressure(model)
    tags = np.asarray(state["tag"])
    alpha = np.array([model.behaviours[int(t)].effective_stress_coefficient for t in tags])
    total = np.asarray(state["normal_stress"]) + alpha * p
    opened = (np.asarray(state["status"]) == int(Status.open)) & (p > 0.0) & (total > 0.0)
    return float(p.max(initial=0.0)), opened
