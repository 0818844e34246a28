# SPDX-License-Identifier: MIT
"""The per-point joint behaviour, without the FE stack: closure law + shear stiffness + residual
stiffness + shear strength of a joint, its traction and consistent tangent at a local jump, and
its path-dependent state (C++ `joint/`, bound as `rockjoint._rockjoint.joint`; needs neither
PETSc nor DOLFINx). The FE joints (`rockjoint.fem`) evaluate every quadrature point through it,
and so can a point driver: direct-shear curves, a calibration, an equivalent-continuum material::

    from math import radians
    from rockjoint import BartonBandis
    from rockjoint.joint import JointBehaviour, joint_response, make_strength
    b = JointBehaviour(BartonBandis(1e10, 1e-3), shear_stiffness=1e9,
                       strength=make_strength({"friction_angle": radians(30)}))
    r = joint_response(b, [-0.2e-3, 1e-3])   # local jump (normal, t1) [m]: traction, tangent, state

Strength (docs/joint-strength.md): Coulomb or Barton slip, dilation, tension cut-off; the return
mapping is C++ (joint/joint_slip.hpp). `make_strength` turns the user's description of a strength
into a validated `JointStrength`; `joint_behaviours` builds every joint of a mesh from the user's
law, shear stiffness, residual stiffness and strength per joint name (the one place where these
inputs are checked and combined, for JointedRockModel(joints=...), JointCoupling and smeared sets)::

    behaviours = joint_behaviours({"fault": 3}, {"fault": law}, shear_stiffness=1e9,
                                  strength={"friction_angle": 0.5})
"""
from __future__ import annotations

import os
from typing import Mapping

from ._rockjoint import constitutive as _constitutive
from ._rockjoint import joint as _cpp
from .validation import positive_number

ShearModel = _cpp.ShearModel
StrengthModel = _cpp.StrengthModel
ShearState = _cpp.ShearState
JointStrength = _cpp.JointStrength
JointPointState = _cpp.JointPointState
JointBehaviour = _cpp.JointBehaviour
#: {traction, tangent, closure, normal_stress, status, shear_state, state} at a local jump
joint_response = _cpp.joint_response
#: (traction, tangent, closure, normal stress, status) from the virgin state
local_response = _cpp.local_response
#: Δ >= 0 [m] with σ(Δ) + k_r Δ = σ_t [Pa] per entry (joint/joint_behaviour.hpp)
closure_at_normal_stress = _cpp.closure_at_normal_stress

#: keywords of a strength description besides "model" (SI units, angles in radians)
STRENGTH_PARAMETERS = ("friction_angle", "cohesion", "tensile_strength", "dilation_angle",
                       "dilation_limit", "jrc", "jcs", "maximum_friction_angle")


def make_strength(spec, joint: str = "") -> JointStrength:
    """A validated JointStrength from None (no strength), a JointStrength, or a dict
    {"model": "coulomb" | "barton" (default "coulomb"), friction_angle [rad], cohesion [Pa],
    tensile_strength [Pa], dilation_angle [rad], dilation_limit [m], jrc, jcs [Pa],
    maximum_friction_angle [rad]}. Raises ValueError naming the joint, key, value and range."""
    where = f"strength of joint {joint!r}" if joint else "strength"
    if spec is None:
        return JointStrength(StrengthModel.none)
    if isinstance(spec, JointStrength):
        return spec
    if not isinstance(spec, dict):
        raise ValueError(f"{where}: give a dict of {('model',) + STRENGTH_PARAMETERS} or a "
                         f"JointStrength, got {type(spec).__name__}")
    spec = dict(spec)
    model = spec.pop("model", "coulomb")
    if isinstance(model, str):
        names = {"none": StrengthModel.none, "coulomb": StrengthModel.coulomb,
                 "barton": StrengthModel.barton}
        if model not in names:
            raise ValueError(f"{where}: model {model!r} is unknown; use one of {sorted(names)}")
        model = names[model]
    unknown = set(spec) - set(STRENGTH_PARAMETERS)
    if unknown:
        raise ValueError(f"{where}: unknown parameter(s) {sorted(unknown)}; valid: "
                         f"{list(STRENGTH_PARAMETERS)} (angles in radians)")
    for key, value in spec.items():
        try:
            spec[key] = float(value)
        except (TypeError, ValueError):
            raise ValueError(f"{where}: {key} = {value!r} is not a number") from None
    try:
        return JointStrength(model, **spec)
    except ValueError as error:
        raise ValueError(f"{where}: {error}") from None


def barton_bandis_shear_stiffness(jrc: float, jcs: float, residual_friction_angle: float,
                                  normal_stress: float, block_length: float) -> float:
    """Peak shear stiffness K_s [Pa/m] of Barton & Choubey (1977) / Barton (1982) at the normal
    stress the joint will carry: the secant to Barton's peak strength reached after a shear
    displacement of 1 % of the block length, K_s = 100 τ_peak(σ_n) / L with
    τ_peak = σ_n tan(φ_r + JRC log10(JCS/σ_n)) (angle capped at 70°). A constant k_s for
    JointedRockModel(shear_stiffness=...); jcs, normal_stress in Pa, block_length in m, angle in
    radians."""
    normal_stress = positive_number("barton_bandis_shear_stiffness: normal_stress", normal_stress, unit="Pa")
    block_length = positive_number("barton_bandis_shear_stiffness: block_length", block_length, unit="m")
    strength = make_strength({"model": "barton", "friction_angle": residual_friction_angle, "jrc": jrc,
                              "jcs": jcs}, "barton_bandis_shear_stiffness")
    return 100.0 * strength.shear_strength(normal_stress) / block_length


def strength_per_joint(value, joint_names) -> dict:
    """{joint name: JointStrength} from None, one description for all joints, or a dict keyed by
    joint names (a dict whose keys are all joint names is per joint; otherwise one description)."""
    if isinstance(value, dict) and value and set(value) <= set(joint_names):
        return {n: make_strength(value.get(n), n) for n in joint_names}
    if isinstance(value, dict) and value and set(value) & set(joint_names):
        raise ValueError(f"strength: mixes joint names {sorted(set(value) & set(joint_names))} with "
                         f"other keys {sorted(set(value) - set(joint_names))}")
    return {n: make_strength(value, n) for n in joint_names}


# ---- the joint behaviours of a mesh: one place where the per-joint inputs are checked ----
class LawTypeError(TypeError, ValueError):
    """A joint's law is not a closure law, table, .rjt path or JointBehaviour (a TypeError, and a
    ValueError for callers that catch every bad input as one)."""


def per_joint(value, joint_names, what: str) -> dict:
    """{joint name: float} from a float for every joint, or a {joint name: float} dict (missing
    joints get 0); `what` names the argument in the error for an unknown joint name."""
    if isinstance(value, dict):
        unknown = set(value) - set(joint_names)
        if unknown:
            raise ValueError(f"{what}: unknown joint(s) {sorted(unknown)}; available joints: {sorted(joint_names)}")
        return {n: float(value.get(n, 0.0)) for n in joint_names}
    return {n: float(value) for n in joint_names}


def joint_behaviours(joint_tags: Mapping[str, int], laws: Mapping[str, object], *,
                     shear_stiffness=0.0, shear_stiffness_ratio=None,
                     residual_stiffness=0.0, strength=None, effective_stress_coefficient=1.0,
                     argument: str = "laws", closure_laws_only: bool = False) -> dict:
    """{joint tag: JointBehaviour} from a law per joint name.

    joint_tags: {joint name: tag} of every joint of the mesh. laws: {joint name: law} for every
    joint; a law is a rockjoint closure law or table (a law with history too, NormalHysteresis:
    a virgin law with unloading branches, docs/hysteresis.md), the path of a .rjt table, or a JointBehaviour
    (then used as it is). shear_stiffness k_s [Pa/m], shear_stiffness_ratio (k_s = ratio × k_n(Δ)
    instead) and residual_stiffness k_r [Pa/m]: a float or {joint name: float}. strength: joint
    shear strength, None, one description or {joint name: description} (docs/joint-strength.md).
    effective_stress_coefficient α [-] (a float or {joint name: float}, in [0, 1]): the law and
    the strength see σ'_n = σ_n - α p with water at pressure p in the joint (rockjoint.fem.water).
    argument: the caller's name of `laws` in error messages. closure_laws_only: accept closure laws
    and tables only (JointedRockModel's joints=).
    """
    if not isinstance(laws, Mapping):
        raise TypeError(f"{argument} must be a dict {{joint name: law}}, got {type(laws).__name__}")
    names = list(joint_tags)
    unknown = set(laws) - set(names)
    if unknown:
        raise ValueError(f"{argument}: unknown joint(s) {sorted(unknown)}; available joints: {sorted(names)}")
    missing = set(names) - set(laws)
    if missing:
        law = "closure law" if closure_laws_only else "law"
        raise ValueError(f"{argument}: no {law} for joint(s) {sorted(missing)}; give {argument}={{joint name: "
                         f"{law}}} for every joint of the mesh: {sorted(names)}")
    ks = per_joint(shear_stiffness, names, "shear_stiffness")
    kr = per_joint(residual_stiffness, names, "residual_stiffness")
    ratio = None if shear_stiffness_ratio is None else per_joint(shear_stiffness_ratio, names,
                                                                  "shear_stiffness_ratio")
    strengths = strength_per_joint(strength, names)
    alpha = per_joint(effective_stress_coefficient, names, "effective_stress_coefficient")
    if isinstance(effective_stress_coefficient, Mapping):   # a joint left out keeps α = 1 (Terzaghi)
        alpha.update({n: 1.0 for n in names if n not in effective_stress_coefficient})
    out = {}
    for name, law in laws.items():
        if not closure_laws_only:
            if isinstance(law, JointBehaviour):
                out[int(joint_tags[name])] = law
                continue
            if isinstance(law, (str, os.PathLike)):
                if not os.path.isfile(law):
                    raise ValueError(f"{argument}[{name!r}]: no table file {os.fspath(law)!r}")
                law = _constitutive.TabulatedLaw.load(os.fspath(law))
        if not isinstance(law, _constitutive.ClosureLaw):
            kinds = "" if closure_laws_only else ", a .rjt path or a JointBehaviour"
            raise LawTypeError(f"{argument}[{name!r}] must be a rockjoint closure law or table{kinds}, "
                               f"got {type(law).__name__}")
        # JointBehaviour validates the stiffnesses (finite, >= 0) and names the bad one.
        if ratio is None:
            b = JointBehaviour(law, ShearModel.constant, shear_stiffness=ks[name], residual_stiffness=kr[name],
                               strength=strengths[name], effective_stress_coefficient=alpha[name])
        else:
            b = JointBehaviour(law, ShearModel.proportional, shear_stiffness_ratio=ratio[name],
                               residual_stiffness=kr[name], strength=strengths[name],
                               effective_stress_coefficient=alpha[name])
        out[int(joint_tags[name])] = b
    return out


def symmetric_tangent(behaviours: Mapping[int, JointBehaviour]) -> bool:
    """True if the joint tangent is symmetric: a constant shear stiffness and no strength on every
    joint (k_s ∝ k_n(Δ) couples shear to closure; friction couples the shear strength to the
    normal stress)."""
    return all(b.shear_model == ShearModel.constant and b.strength.model == StrengthModel.none
               for b in behaviours.values())
