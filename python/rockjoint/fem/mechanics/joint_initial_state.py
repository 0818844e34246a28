# SPDX-License-Identifier: MIT
"""Joints pre-loaded by an in-situ stress: the initial jump that makes them carry σ0 at u = 0.

At a joint point with local frame F (rows n, t1[, t2]; n from the minus to the plus side), the
in-situ traction in local components is t = F σ0 n. The joint element's local traction is
(-σ_n(Δ), k_s j_s) with Δ = -j_n (joint/joint_behaviour.cpp), so the joint carries t at
u = 0 when its initial jump j0 (CONTRACTS A.3) is::

    j0_n = -Δ0,  σ_n(Δ0) = σ_n0 = -t_n  (compression positive; σ_n = law + k_r Δ, solved by
                                         closure_at_normal_stress, joint/joint_behaviour.hpp),
    j0_s = t_s / k_s,  k_s constant or ratio × (k_n(Δ0) + k_r).

With the nodal (vertex) rule on P1 facets, the joint's force at vertex a of a facet is
w_a t_a = ``|f|``/gdim · t_a, while the bulk's in-situ stress pulls on that vertex with the consistent
∫_f σ0 n N_a = ``|f|`` (t_a + Σ_b t_b) / (gdim (gdim + 1)) (t linear on the facet, e.g. a depth gradient
along an inclined joint): the point traction is taken as t'_a = (t_a + Σ_b t_b) / (gdim + 1), the
same for a uniform σ0 and exact equilibrium for a linear one.

Water in the joints from the initial state on (fem.water.joint_pressure.set_initial_joint_pressure,
e.g. a hydrostatic water table) carries part of the total normal stress: the joint element's normal
traction is -(σ(Δ) + k_r Δ + α p) (docs/flow.md), so the pre-closure is the law's at the effective
stress, σ_n(Δ0) = σ_n0 - α p0, point by point (p acts at each point, not through the facet average). Gauss points (P1) and the P2 nodal
rule in 2D integrate t N_a exactly with t'_a = t(x_a); the P2 nodal rule in 3D does not (a residual
imbalance of order h² ∇σ0, reported by the model's equilibrium check).
"""
from __future__ import annotations

import numpy as np

from ...joint import ShearModel, closure_at_normal_stress


def initial_jump(interface, in_situ, behaviours: dict, gdim: int, joint_names: dict,
                 vertex_rule: bool = True, pore_pressure=None) -> np.ndarray:
    """(num_points, gdim) initial local jumps of this rank's joint points for the in-situ stress.

    behaviours: {joint tag: JointBehaviour}; joint_names: {name: tag} (for messages); vertex_rule:
    the points are the vertices of P1 facets (nodal rule): consistent point tractions;
    pore_pressure: the initial water p0 [Pa] at every point of this rank (None: dry). Raises
    ValueError where σ0 pulls a joint apart (a joint carries no tension), where the water reaches
    the in-situ normal stress (hydraulic jacking in situ) or where σ0 shears a joint that has no
    shear stiffness."""
    frames = interface.point_frames()
    j0 = np.zeros((frames.shape[0], gdim))
    if frames.shape[0] == 0:
        return j0
    state = interface.state()
    points, tags = np.asarray(state["coordinates"]), np.asarray(state["tag"])
    sigma0 = in_situ.at(points.reshape(frames.shape[0], -1), gdim)
    traction = np.einsum("pij,pj->pi", sigma0, frames[:, 0])   # σ0 n, global components
    if vertex_rule:
        per_pair = traction.reshape(-1, gdim, gdim)  # (pairs, vertices, components)
        traction = ((per_pair + per_pair.sum(axis=1, keepdims=True)) / (gdim + 1)).reshape(-1, gdim)
    local = np.einsum("pij,pj->pi", frames, traction)          # F σ0 n
    scale = max(np.abs(sigma0).max(), 1e-300)
    name_of = {t: n for n, t in joint_names.items()}
    # The points of each joint as index arrays, found once: a mask per joint (tags == tag) cost
    # 0.13 s for the 268 joints and 44k points of the continuum bench's discrete tunnel.
    order = np.argsort(tags, kind="stable")
    sorted_tags = tags[order]
    for tag, behaviour in behaviours.items():
        sel = order[np.searchsorted(sorted_tags, tag, "left"):np.searchsorted(sorted_tags, tag, "right")]
        if not sel.size:
            continue
        normal_stress = -local[sel, 0]
        tension = normal_stress < -1e-9 * scale
        if tension.any():
            k = sel[np.argmax(tension)]
            raise ValueError(f"the in-situ stress pulls joint {name_of.get(tag, tag)!r} apart: normal stress "
                             f"{-local[k, 0]:.4g} Pa (tension) at {points[k].tolist()}; a joint carries no tension")
        if pore_pressure is not None:   # the law carries the effective stress σ_n0 - α p0
            effective = normal_stress - behaviour.effective_stress_coefficient * np.asarray(pore_pressure)[sel]
            jacked = effective < -1e-9 * scale
            if jacked.any():
                k = sel[np.argmax(jacked)]
                raise ValueError(f"the initial water in joint {name_of.get(tag, tag)!r} reaches its in-situ normal "
                                 f"stress: p0 = {pore_pressure[k]:.4g} Pa against σ_n0 = {-local[k, 0]:.4g} Pa at "
                                 f"{points[k].tolist()} (hydraulic jacking in situ): lower the water table")
            normal_stress = effective
        normal_stress = np.maximum(normal_stress, 0.0)
        try:
            closure = closure_at_normal_stress(behaviour, normal_stress)
        except ValueError as error:
            raise ValueError(f"pre-closure of joint {name_of.get(tag, tag)!r} by the in-situ stress: "
                             f"{error}") from error
        j0[sel, 0] = -closure
        if behaviour.shear_model == ShearModel.proportional:
            ks = behaviour.shear_stiffness_ratio * (np.asarray(behaviour.law.normal_stiffness(closure))
                                                   + behaviour.residual_stiffness)
        else:
            ks = np.full(closure.shape, behaviour.shear_stiffness)
        shear = local[sel, 1:]
        sheared = np.any(np.abs(shear) > 1e-9 * scale, axis=1)
        if np.any(sheared & ~(ks > 0)):
            raise ValueError(f"the in-situ stress shears joint {name_of.get(tag, tag)!r} (τ0 up to "
                             f"{np.abs(shear).max():.4g} Pa) but its shear stiffness is 0: give shear_stiffness > 0")
        j0[sel, 1:] = np.where(ks[:, None] > 0, shear / np.where(ks > 0, ks, 1.0)[:, None], 0.0)
    return j0
