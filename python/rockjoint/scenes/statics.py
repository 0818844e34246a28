# SPDX-License-Identifier: MIT
"""Statics of a scene: why a scene has no static equilibrium, in words a user can act on.

- Before anything runs (`check`, called by the planner; the scene is then bad, exit 2): supports
  that leave a rigid-body motion of the whole rock free (the model would be singular whatever the
  joints do), a load on the wall of an opening that a later stage excavates (its rock is still in
  place), an excavation without an in-situ stress (it releases nothing).
- After a solve failed (`diagnose`, called by the runner; exit 1): on the homogeneous stress of the
  failed stage (stresses.stage_stresses), each discrete joint set that opens (σ_n <= 0, no residual
  stiffness), slides (τ >= c + σ_n tan φ) or carries no shear (k_s = 0, no strength); the blocks
  that are then joined to no support by a holding joint are free: no static equilibrium.
"""
from __future__ import annotations

import math

import numpy as np

from . import geometry, stresses

_FACE_AXIS = {"left": (0, 0), "right": (0, 1), "front": (1, 0), "back": (1, 1)}
_COMPONENT = {"x": 0, "y": 1, "z": 2}


def _face_points(g, face: str, dim: int) -> np.ndarray:
    """Corner points of a named boundary (an opening: points round its outline)."""
    ext = geometry.extent(g)
    if face == "opening":
        x, y = geometry.opening(g).outline(16).T
        if dim == 2:
            return np.c_[x, y]
        # 3D tunnel: the section in the x-z plane, extruded along y (meshes/tunnel.py)
        return np.vstack([np.c_[x, np.full(x.size, end), y] for end in (0.0, ext[1])])
    axis, side = (dim - 1, 0 if face == "bottom" else 1) if face in ("bottom", "top") else _FACE_AXIS[face]
    corners = np.array(np.meshgrid(*[[0.0, e] for e in ext], indexing="ij")).reshape(dim, -1).T
    return corners[np.isclose(corners[:, axis], side * ext[axis])]


def _modes(x: np.ndarray, dim: int) -> np.ndarray:
    """Rigid-body displacements at point x: (modes, dim); 2D: tx, ty, rz; 3D: tx, ty, tz, rx, ry, rz."""
    if dim == 2:
        return np.array([[1.0, 0.0], [0.0, 1.0], [-x[1], x[0]]])
    t = np.eye(3)
    r = np.array([np.cross(e, x) for e in np.eye(3)])
    return np.vstack([t, r])


def free_rigid_motions(scene) -> list:
    """Words for each rigid-body motion of the whole rock that the supports leave free."""
    d, g = scene.data, scene.data["geometry"]
    dim = g["dimension"]
    rows = []
    for face, comps in d["supports"].items():
        idx = range(dim) if comps in ("all", "xyz") else [_COMPONENT[c] for c in comps if _COMPONENT[c] < dim]
        for x in _face_points(g, face, dim):
            m = _modes(x, dim)
            rows += [m[:, c] for c in idx]
    n = 3 if dim == 2 else 6
    a = np.array(rows).reshape(-1, n)
    _, s, vt = np.linalg.svd(a) if a.size else (None, np.zeros(0), np.eye(n))
    scale = max(1.0, float(np.max(geometry.extent(g))))
    null = vt[int(np.sum(s > 1e-9 * scale * max(s.max(initial=0.0), 1.0))):]
    # Canonical basis: the free translations first, then rotations without translation parts
    # (an arbitrary SVD basis would mix them into rotations about arbitrary points).
    _, sw, vw = np.linalg.svd(null[:, dim:].T) if null.size else (None, np.zeros(0), np.zeros((0, 0)))
    k = int(np.sum(sw > 1e-9))
    translations = vw[k:] @ null
    rest = vw[:k] @ null
    if len(translations):
        rest = rest - (rest @ translations.T) @ translations
        # free translations along the axes where they span them (any basis of the same plane would do)
        axes = [np.eye(n)[i] for i in range(dim)
                if np.linalg.norm(np.eye(n)[i] - (translations @ np.eye(n)[i]) @ translations) < 1e-9]
        if len(axes) == len(translations):
            translations = np.array(axes)
    words = []
    for v in list(translations) + list(rest):
        v = v / np.abs(v).max()
        t, w = v[:dim], v[dim:]
        if np.abs(w).max() < 1e-9:
            words.append("translation along " + _direction(t))
        elif dim == 2:
            x0, y0 = -t[1] / w[0] + 0.0, t[0] / w[0] + 0.0  # u = ω (-(y - y0), x - x0); no -0
            words.append(f"rotation about the point ({x0:.3g} m, {y0:.3g} m)")
        else:
            words.append("rotation about an axis along " + _direction(w))
    return words


def _direction(v) -> str:
    v = np.asarray(v) / np.linalg.norm(v)
    for k, name in enumerate("xyz"[:len(v)]):
        if abs(abs(v[k]) - 1.0) < 1e-9:
            return name
    return "(" + ", ".join(f"{c:.3g}" for c in v) + ")"


def check(scene) -> None:
    """The statics errors a scene shows before anything runs (SceneError naming the key)."""
    d = scene.data
    free = free_rigid_motions(scene)
    if free:
        scene.fail(("supports",), "the supports leave the rock free to move as a rigid body ("
                   + "; ".join(free) + "): no load can be carried; support more components, e.g. "
                   "x and y on the bottom" + (" and z" if d["geometry"]["dimension"] == 3 else ""))
    stages = d["stages"]
    for i, stage in enumerate(stages):
        if "excavate" not in stage:
            continue
        face = stage["excavate"]
        if "in_situ" not in d:
            scene.fail(("stages", i, "excavate"), f"excavating '{face}' releases the in-situ stress it "
                       "carries, and the scene has none (no in_situ): the excavation would do nothing")
        for j, earlier in enumerate(stages[:i]):
            if face in earlier["loads"]:
                scene.fail(("stages", j, "loads", face), f"a load on '{face}' in stage '{earlier['name']}', "
                           f"before stage '{stage['name']}' excavates it: until then its rock is in "
                           "place and its wall carries nothing; apply the load from that stage on")


def _stage_stress(scene, stage: str) -> np.ndarray:
    tensors = stresses.stage_stresses(scene)
    for name, s, _ in tensors:
        if name == stage:
            return s
    # the in-situ state, or a stage not found: the first stage's stress without loads
    d, dim = scene.data, scene.data["geometry"]["dimension"]
    s = np.zeros((dim, dim))
    if "in_situ" in d:
        s = -d["in_situ"]["horizontal_ratio"] * d["in_situ"]["vertical"] * np.eye(dim)
        s[-1, -1] = -d["in_situ"]["vertical"]
    return s


def set_failures(scene, plan, stage: str) -> dict:
    """{set: words} for the discrete joint sets that cannot hold their blocks under the homogeneous
    stress of `stage`: open (σ_n <= 0 without residual stiffness), sliding (τ >= c + σ_n tan φ),
    or without shear stiffness or strength."""
    d = scene.data
    dim = plan.dimension
    s = _stage_stress(scene, stage)
    out = {}
    for js in geometry.joint_sets(scene):
        name = js["name"]
        if name in plan.smeared:
            continue
        j = d["joints"][name]
        n = geometry.set_normal(js, dim)
        t = s @ n
        sn = -float(t @ n)                     # compression positive
        tau = float(np.linalg.norm(t + sn * n))
        strength = scene.strengths[name] if plan.slip.get(name) else None
        if sn <= 0.0 and j["residual_stiffness"] == 0.0:
            out[name] = (f"opens: stage '{stage}' puts it in {-sn * 1e-6:.3g} MPa tension (a joint carries "
                         "no tension and it has no residual_stiffness)" if sn < 0 else
                         f"opens: stage '{stage}' puts no compression on it and it has no residual_stiffness")
        elif strength is not None and tau > 0.0:
            capacity = stresses.shear_capacity(strength, sn)
            if tau >= capacity:
                phi_tan = (capacity - strength.cohesion) / sn   # sn > 0: a capacity above c
                out[name] = (f"slides: stage '{stage}' mobilises τ/σ_n = {tau / sn:.3f} "
                             f"(tan {math.degrees(math.atan(tau / sn)):.1f}°) on it, its strength allows "
                             f"{capacity / sn:.3f} (tan φ = tan {math.degrees(math.atan(phi_tan)):.1f}°"
                             + (f", c = {strength.cohesion * 1e-6:.3g} MPa" if strength.cohesion else "")
                             + ")")
        elif strength is None and j["shear_stiffness_ratio"] == 0.0 and tau > 0.0:
            out[name] = (f"carries no shear: shear_stiffness_ratio 0 and no strength, under "
                         f"{tau * 1e-6:.3g} MPa shear in stage '{stage}'")
        elif strength is None and j["shear_stiffness_ratio"] == 0.0:
            out[name] = "carries no shear: shear_stiffness_ratio 0 and no strength"
    return out


def _supported_blocks(scene, jm) -> set:
    """Blocks (names) with a facet on a supported boundary."""
    names = jm.names
    face_tag = {v: k for k, v in names["boundaries"].items()}
    node_blocks = {}
    for cell, block in zip(jm.cells, jm.cell_blocks):
        for node in cell:
            node_blocks.setdefault(int(node), set()).add(int(block))
    out = set()
    for face in scene.data["supports"]:
        tag = face_tag.get(face)
        for facet in jm.boundary_facets[jm.boundary_tags == tag]:
            out |= set.intersection(*(node_blocks.get(int(v), set()) for v in facet))
    return {names["blocks"][b] for b in out}


def free_blocks(scene, jm, failing: dict) -> dict:
    """{free block: [failing sets that bound it]}: blocks joined to no supported block through
    joints of sets that hold."""
    names = jm.names
    set_of = jm.joint_sets()   # {joint: its set}, as the mesh records it
    block = {int(k): v for k, v in names["blocks"].items()}
    held = _supported_blocks(scene, jm)
    edges, bounds = [], {}
    for (c0, c1), tag in zip(jm.joint_facet_cells, jm.joint_tags):
        a, b = block[int(jm.cell_blocks[c0])], block[int(jm.cell_blocks[c1])]
        js = set_of[names["joints"][int(tag)]]
        if js in failing:
            bounds.setdefault(a, set()).add(js)
            bounds.setdefault(b, set()).add(js)
        else:
            edges.append((a, b))
    reached, changed = set(held), True
    while changed:
        changed = False
        for a, b in edges:
            if (a in reached) != (b in reached):
                reached |= {a, b}
                changed = True
    return {b: sorted(bounds.get(b, ())) for b in sorted(block.values()) if b not in reached}


def diagnose(scene, plan, jm, stage: str) -> str | None:
    """Why the jointed model of `stage` has no static equilibrium, or None if the homogeneous
    stress and the block graph do not explain the failure."""
    failing = set_failures(scene, plan, stage)
    if not failing:
        return None
    free = free_blocks(scene, jm, failing)
    if not free:
        return None
    words = [f"joint set {name} {why}" for name, why in failing.items()]
    hints = {"opens": "a residual_stiffness", "slides": "more strength (friction_angle, cohesion)",
             "carries": "a shear_stiffness_ratio > 0 or a strength"}
    fixes = sorted({hints[why.split(":")[0].split()[0]] for why in failing.values()})
    held = "; ".join(f"{b} is held only by joint set{'s' if len(sets) > 1 else ''} {', '.join(sets)}"
                     if sets else f"{b} is held by nothing" for b, sets in free.items())
    return (f"no static equilibrium in stage '{stage}': " + "; ".join(words) + f"; it frees {', '.join(free)} ("
            + held + " and no support). Support the block, or give the set " + " or ".join(fixes))
