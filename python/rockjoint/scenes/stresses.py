# SPDX-License-Identifier: MIT
"""The homogeneous stress of a scene's stages and how much of a joint set's shear strength it
mobilises: what the planner (which laws, which sets smeared, the table range) and the statics
checks (statics.py: which set opens or slides, freeing which block) both read, and the upper bound
of any joint's normal stress the tables must cover (the planner's table range)."""
from __future__ import annotations

import math

import numpy as np


from . import defaults, geometry, slope_keys

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
    if d["geometry"]["kind"] == "slope":   # a slope's weight, at its bottom (the largest)
        s0 = slope_keys.weight_stress(d)
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


def shear_capacity(strength, normal_stress):
    """τ_max [Pa] of a set's strength (its JointStrength, Scene.strengths) at `normal_stress` [Pa]
    (a number or an array; compression +): the joint's own JointStrength.shear_strength
    (docs/joint-strength.md: Coulomb c + σ_n tan φ, or Barton's angle capped at its
    maximum_friction_angle), not a copy of it."""
    sn = np.asarray(normal_stress, dtype=float)
    out = np.array([strength.shear_strength(float(v)) for v in sn.ravel()]).reshape(sn.shape)
    return float(out) if out.ndim == 0 else out


def mobilised_friction(strength, normal: np.ndarray, stress: np.ndarray) -> float:
    """τ / τ_max on the plane of unit `normal` under `stress` (tension positive)."""
    t = stress @ normal
    sn = -float(t @ normal)
    tau = float(np.linalg.norm(t + sn * normal))
    capacity = shear_capacity(strength, max(sn, 0.0))   # a tension bound counts as no compression
    return math.inf if capacity <= 0 else tau / capacity


def wall_mobilised_friction(strength, hoop: float) -> float:
    """The largest τ/(c + σ_n tan φ) over every plane through the uniaxial wall state σ_θ = hoop,
    σ_r = 0 (a joint meets the wall at every angle): planes at angle α to the wall carry σ_n =
    σ_θ sin²α, τ = σ_θ sinα cosα."""
    alpha = np.linspace(1e-3, math.pi / 2, 400)
    sn, tau = hoop * np.sin(alpha) ** 2, hoop * np.sin(alpha) * np.cos(alpha)
    cap = shear_capacity(strength, sn)
    return float(np.max(tau / np.maximum(cap, 1e-300)))


def concentration(scene) -> tuple:
    """(factor, words): the stress-concentration bound of the scene's geometry: Kirsch's 3 at an
    opening, block corners where joint sets of different orientation cross, else 1. A D's or a
    horseshoe's corners (wall to floor or invert, a segmental crown to its walls) have no finite
    elastic bound (the stress is singular at a corner): the planner keeps Kirsch's 3 and says so,
    and the run names any joint that leaves its table (runner.beyond_tables)."""
    g = scene.data["geometry"]
    if "opening" in g:
        if g["opening"]["shape"] == "circle":
            return defaults.OPENING_CONCENTRATION, "x 3 Kirsch concentration at the opening"
        return (defaults.OPENING_CONCENTRATION, f"x 3 Kirsch concentration at the opening (a circle's: the "
                f"{g['opening']['shape']}'s corners concentrate more, the run names any joint past its table)")
    orientations = {(round(s["dip"], 6), round(s["dip_direction"], 6)) for s in g.get("joint_sets", [])}
    if len(orientations) > 1:
        return (defaults.BLOCK_CORNER_CONCENTRATION,
                f"x {defaults.BLOCK_CORNER_CONCENTRATION:g} at block corners where joint sets cross")
    return 1.0, "no concentration: a homogeneous field"


def bending(scene) -> list:
    """Per stage, the bending stress [Pa] a shear traction on a face adds on a joint section:
    the moment τ W H of a shear τ on a face of width W at lever arm H, over the section modulus
    W²/6 (beam theory: 6 τ H/W), H the scene's extent normal to the face, W the smallest along it."""
    g = scene.data["geometry"]
    ext, dim = geometry.extent(g), g["dimension"]
    out, loads = [], {}
    for stage in scene.data["stages"]:
        loads.update(stage["loads"])
        extra = 0.0
        for face, load in loads.items():
            if "traction" not in load or face not in FACE_AXIS:
                continue
            axis = dim - 1 if face in ("bottom", "top") else (0 if face in ("left", "right") else 1)
            t = np.asarray(load["traction"], float)
            tau = float(np.linalg.norm(np.delete(t, axis)))
            along = np.delete(ext, axis).min()
            extra += 6.0 * tau * ext[axis] / along
        out.append(extra)
    return out


def normal_stress_bound(scene) -> float:
    """Upper bound [Pa] of any joint's normal stress over the stages."""
    factor = concentration(scene)[0]
    bound = 0.0
    for (_, s, pressure), extra in zip(stage_stresses(scene), bending(scene)):
        compression = max(0.0, -float(np.linalg.eigvalsh(s).min()))
        bound = max(bound, compression * factor + pressure + extra)
    return bound


def largest_stress(scene) -> float:
    """The largest principal stress magnitude [Pa] of any stage (pressures included); 1 MPa if
    nothing loads the scene (a table needs a range)."""
    top = max((max(float(np.abs(np.linalg.eigvalsh(s)).max(initial=0.0)), p)
               for _, s, p in stage_stresses(scene)), default=0.0)
    return top if top > 0 else 1e6
