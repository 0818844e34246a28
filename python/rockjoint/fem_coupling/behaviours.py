"""The joint behaviours of a mesh: {joint tag: JointBehaviour} from the user's law, shear
stiffness, residual stiffness and strength per joint name. The one place where these inputs are
checked and combined, for JointedRockModel(joints=...) and JointCoupling / joint_behaviours(laws=...).

    from rockjoint.fem_coupling import joint_behaviours
    behaviours = joint_behaviours({"fault": 3}, {"fault": law}, shear_stiffness=1e9,
                                  strength={"friction_angle": 0.5})
"""
from __future__ import annotations

import os
from typing import Mapping

from .. import _rockjoint
from ..joint import JointBehaviour, ShearModel, StrengthModel, strength_per_joint

__all__ = ["LawTypeError", "joint_behaviours", "per_joint", "symmetric_tangent"]


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
                     residual_stiffness=0.0, strength=None, argument: str = "laws",
                     closure_laws_only: bool = False) -> dict:
    """{joint tag: JointBehaviour} from a law per joint name.

    joint_tags: {joint name: tag} of every joint of the mesh. laws: {joint name: law} for every
    joint; a law is a rockjoint closure law or table, a NormalHysteresis (a virgin law with
    unloading branches: docs/hysteresis.md), the path of a .rjt table, or a JointBehaviour
    (then used as it is). shear_stiffness k_s [Pa/m], shear_stiffness_ratio (k_s = ratio × k_n(Δ)
    instead) and residual_stiffness k_r [Pa/m]: a float or {joint name: float}. strength: joint
    shear strength, None, one description or {joint name: description} (docs/joint-strength.md).
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
    out = {}
    for name, law in laws.items():
        if not closure_laws_only:
            if isinstance(law, JointBehaviour):
                out[int(joint_tags[name])] = law
                continue
            if isinstance(law, (str, os.PathLike)):
                if not os.path.isfile(law):
                    raise ValueError(f"{argument}[{name!r}]: no table file {os.fspath(law)!r}")
                law = _rockjoint.constitutive.TabulatedLaw.load(os.fspath(law))
        hysteresis = None
        if isinstance(law, _rockjoint.constitutive.NormalHysteresis):  # history: virgin law + branches
            hysteresis, law = law, law.virgin
        if not isinstance(law, _rockjoint.constitutive.ClosureLaw):
            kinds = "" if closure_laws_only else ", a .rjt path or a JointBehaviour"
            raise LawTypeError(f"{argument}[{name!r}] must be a rockjoint closure law or table{kinds}, "
                               f"got {type(law).__name__}")
        # JointBehaviour validates the stiffnesses (finite, >= 0) and names the bad one.
        if ratio is None:
            b = JointBehaviour(law, ShearModel.constant, shear_stiffness=ks[name], residual_stiffness=kr[name],
                               strength=strengths[name], hysteresis=hysteresis)
        else:
            b = JointBehaviour(law, ShearModel.proportional, shear_stiffness_ratio=ratio[name],
                               residual_stiffness=kr[name], strength=strengths[name], hysteresis=hysteresis)
        out[int(joint_tags[name])] = b
    return out


def symmetric_tangent(behaviours: Mapping[int, JointBehaviour]) -> bool:
    """True if the joint tangent is symmetric: a constant shear stiffness and no strength on every
    joint (k_s ∝ k_n(Δ) couples shear to closure; friction couples the shear strength to the
    normal stress)."""
    return all(b.shear_model == ShearModel.constant and b.strength.model == StrengthModel.none
               for b in behaviours.values())
