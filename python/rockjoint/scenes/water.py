# SPDX-License-Identifier: MIT
"""A scene's flow (`outputs: {flow: {heads: {boundary: h}}}`, docs/flow.md): every joint set's
transmissivity law T(Δ) (its `flow:` entry: from its own walls, or a conversion of its mechanical
aperture), and after every stage the steady flow between the heads: along the jointed model's joint
network (each point's T from its closure then), and through the intact model when the rock has a
permeability (Darcy), beside it.
"""
from __future__ import annotations

import logging

import numpy as np

import rockjoint
from rockjoint import contact, flow
from rockjoint import topography as topo

from ..fem import darcy_flow, network_flow
from ..meshes import joint_sets_of
from . import geometry, joint_laws, ladder

log = logging.getLogger("rockjoint.scenes")


def requested(scene) -> bool:
    """True if the scene asks for the joints' flow (a `flow` entry in `outputs:`)."""
    return "flow" in scene.data["outputs"]


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


def stage_flow(scene, model, solution, laws: dict | None):
    """The stage's flow: (flow rates {boundary: Q [m³/s; m²/s per metre in 2D]}, the network or
    None). The jointed model (`laws` given): along its joint network; the intact one: Darcy with
    the rock's permeability, or no flow (None) when the rock has none."""
    heads = scene.data["outputs"]["flow"]["heads"]
    if laws is not None:
        per_joint = {n: laws[s].transmissivity for n, s in joint_sets_of(model.dmesh.names).items()}
        network = network_flow(model, per_joint, heads, stage=solution)
        return network.flow_rates, network
    k = scene.data["rock"].get("permeability")
    if k is None:
        return None, None
    return darcy_flow(model.dmesh, k * np.eye(model.gdim), heads).flow_rates, None
