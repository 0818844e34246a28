"""The homogeneous stress of a scene's stages and how much of a joint set's shear strength it
mobilises: what the planner (which laws, which sets smeared, the table range) and the statics
checks (statics.py: which set opens or slides, freeing which block) both read."""
from __future__ import annotations

import math

import numpy as np

from rockjoint.joint import make_strength

#: axis-aligned faces: (axis, outward sign); bottom/top take the last axis (y in 2D, z in 3D)
FACE_AXIS = {"left": (0, -1), "right": (0, 1), "bottom": (1, -1), "top": (1, 1),
         "front": (None, -1), "back": (None, 1)}


def stage_stresses(scene) -> list:
    """Per stage, the homogeneous stress tensor (tension positive [Pa]) of in-situ + the loads
    in force: a traction on an axis-aligned face gives σ·n = t there (the far field of the
    section); pressures on an opening are counted in the normal-stress bound only."""
    d = scene.data
    dim = d["geometry"]["dimension"]
    s0 = np.zeros((dim, dim))
    if "in_situ" in d:
        sv, k = d["in_situ"]["vertical"], d["in_situ"]["horizontal_ratio"]
        s0 = -k * sv * np.eye(dim)
        s0[dim - 1, dim - 1] = -sv
    loads, out = {}, []
    for stage in d["stages"]:
        loads.update(stage["loads"])
        s = s0.copy()
        for face, load in loads.items():
            if "traction" in load and face in FACE_AXIS:
                axis, sign = FACE_AXIS[face]
                axis = dim - 1 if face in ("bottom", "top") else (axis if axis is not None else 1)
                s[:, axis] = sign * np.asarray(load["traction"])
                s[axis, :] = s[:, axis]
        pressure = max((abs(v["pressure"]) for v in loads.values() if "pressure" in v), default=0.0)
        out.append((stage["name"], s, pressure))
    return out


def shear_capacity(strength: dict, normal_stress):
    """τ_max [Pa] of a scene's strength description at `normal_stress` [Pa] (a number or an array;
    compression +): the joint's own JointStrength.shear_strength (docs/joint-strength.md: Coulomb c + σ_n tan φ,
    or Barton's angle capped at its maximum_friction_angle), not a copy of it."""
    joint = make_strength(strength)
    sn = np.asarray(normal_stress, dtype=float)
    out = np.array([joint.shear_strength(float(v)) for v in sn.ravel()]).reshape(sn.shape)
    return float(out) if out.ndim == 0 else out


def mobilised_friction(strength: dict, normal: np.ndarray, stress: np.ndarray) -> float:
    """τ / τ_max on the plane of unit `normal` under `stress` (tension positive)."""
    t = stress @ normal
    sn = -float(t @ normal)
    tau = float(np.linalg.norm(t + sn * normal))
    capacity = shear_capacity(strength, max(sn, 0.0))   # a tension bound counts as no compression
    return math.inf if capacity <= 0 else tau / capacity


def wall_mobilised_friction(strength: dict, hoop: float) -> float:
    """The largest τ/(c + σ_n tan φ) over every plane through the uniaxial wall state σ_θ = hoop,
    σ_r = 0 (a joint meets the wall at every angle): planes at angle α to the wall carry σ_n =
    σ_θ sin²α, τ = σ_θ sinα cosα."""
    alpha = np.linspace(1e-3, math.pi / 2, 400)
    sn, tau = hoop * np.sin(alpha) ** 2, hoop * np.sin(alpha) * np.cos(alpha)
    cap = shear_capacity(strength, sn)
    return float(np.max(tau / np.maximum(cap, 1e-300)))
