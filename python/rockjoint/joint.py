"""The per-point joint behaviour, without the FE stack: closure law + shear stiffness + residual
stiffness + shear strength of a joint, its traction and consistent tangent at a local jump, and
its path-dependent state (C++ `joint/`, bound as `rockjoint._rockjoint.joint`; needs neither
PETSc nor DOLFINx). The FE joints (`rockjoint.fem_coupling`) evaluate every quadrature point through it,
and so can a point driver: direct-shear curves, a calibration, an equivalent-continuum material.

    from math import radians
    from rockjoint import BartonBandis
    from rockjoint.joint import JointBehaviour, joint_response, make_strength
    b = JointBehaviour(BartonBandis(1e10, 1e-3), shear_stiffness=1e9,
                       strength=make_strength({"friction_angle": radians(30)}))
    r = joint_response(b, [-0.2e-3, 1e-3])   # local jump (normal, t1) [m]: traction, tangent, state

Strength (docs/joint-strength.md): Coulomb or Barton slip, dilation, tension cut-off; the return
mapping is C++ (joint/joint_slip.hpp). `make_strength` turns the user's description of a strength
into a validated `JointStrength`.
"""
from __future__ import annotations

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
