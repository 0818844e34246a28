#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""A blocky rock mass under biaxial load: bedding planes and a cross-joint set, with and without joint slip.

Read it top to bottom; run it as it is (serial or `mpirun -n 2`):

    PYTHONPATH=python:build/python /usr/bin/python3 demos/demo_blocky_rock_mass.py [--output DIR]

A 12 m x 8 m section (2D plane strain) of granite is cut by three horizontal bedding joints
(2 m apart) and three cross joints dipping 70° (3 m apart), which together make a blocky mass.
The bedding planes carry the Tang & Jiao law of a measured-like rough joint (theory §7
parameters), the cross joints a Barton-Bandis law from their JRC, JCS and aperture; both are
tabulated once and the tables go into the FE model. The mass is loaded by a vertical stress on
top and a smaller horizontal stress on one side (rollers on the other two sides). Three models
follow the same staged load path:

* **intact**: the section without joints (the closed-form biaxial state);
* **elastic joints**: the jointed section, joints closing by their laws and shearing
  elastically (k_s = 0.1 k_n) without limit;
* **slipping joints**: the same jointed section with a Coulomb strength on every joint
  (docs/joint-strength.md): a joint point slips once |τ| reaches c + σ_n tan φ.

Stage 1 applies σ_v = 10 MPa and σ_h = 5 MPa; stage 2 raises σ_v to 20 MPa at the same σ_h (a
larger deviatoric load, as beside an opening or under a foundation), which takes the cross
joints past the friction the elastic joints would need. The difference between the last two
models is what slip adds to the settlement and to the lateral convergence.

Outputs (in DIR, default the working directory): blocky_rock_mass.png (|u| of the three
sections), blocky_joint_slip.png (joints as line segments: friction mobilised by the elastic
joints; shear state and slip on the deformed slipping section), blocky_rock_mass.txt (the
numbers), blocky_intact.xdmf, blocky_jointed.xdmf and blocky_slip.xdmf (+ *_joints.xdmf, the
joint state incl. slip_m and shear_state) for ParaView. Units in print: mm, MPa, degrees.
"""
import argparse
import math
import os
import time

import numpy as np
from mpi4py import MPI

import rockjoint
from rockjoint.console import quiet_compiler_logging, say
from rockjoint import meshes
from rockjoint.fem import JointedRockModel, NewtonOptions, ShearState, distribute, make_strength
from rockjoint.fem.output.fields import gather_triangles
from rockjoint.scenes import geometry as scene_geometry, load_scene

COMM = MPI.COMM_WORLD
quiet_compiler_logging()  # DOLFINx's form compiler would log every command



# %% The rock mass -----------------------------------------------------------------------------
# The set-up is the scene demos/scenes/blocky_rock_mass.yaml (`python3 -m rockjoint run` runs it
# with the planner's choices); this script adds the elastic/slipping comparison and the pictures.
SCENE = load_scene(os.path.join(os.path.dirname(os.path.abspath(__file__)), "scenes",
                                "blocky_rock_mass.yaml"))
WIDTH, HEIGHT = SCENE["geometry"]["size"]                            # [m]
YOUNG, POISSON = SCENE["rock"]["young"], SCENE["rock"]["poisson"]   # granite [Pa], [-]
HORIZONTAL_STRESS = -SCENE["stages"][0]["loads"]["right"]["traction"][0]  # right face, both stages [Pa]
# The load path: (stage name, vertical stress on top [Pa], load steps)
STAGES = tuple((s["name"], -s["loads"]["top"]["traction"][1], s["steps"]) for s in SCENE["stages"])
SHEAR_RATIO = SCENE["joints"]["cross"]["shear_stiffness_ratio"]     # k_s = 0.1 k_n(Δ)
CROSS_JRC, CROSS_JCS, CROSS_APERTURE = 10.0, 100e6, 0.5e-3   # [-], [Pa], [m]

# Joint strength of the slipping model, both sets: Coulomb with the basic friction angle of wet
# fine-grained granite, φ_b = 29-31° (Barton & Choubey 1977, Table 2: 31-35° dry, 29-31° wet),
# taken as 30°, and no cohesion (Barton 1973: natural unfilled joints have no reliable cohesion or
# tensile strength). This is the strength of a planar or sheared-through (past-peak) joint, the
# lower bound: the rough cross joints' peak from the same JRC/JCS (Barton's criterion with
# φ_r = φ_b) is higher, and is printed beside it for comparison.
FRICTION_ANGLE = SCENE["joints"]["cross"]["strength"]["friction_angle"]  # [rad]
COHESION = SCENE["joints"]["cross"]["strength"]["cohesion"]              # [Pa]
STRENGTH = {"model": "coulomb", "friction_angle": FRICTION_ANGLE, "cohesion": COHESION}

# Bedding: horizontal, 2 m apart. Cross joints: dip 70° toward +x, 3 m apart along their normal;
# both sets persist across the section (crossings make the blocks).
_SETS = scene_geometry.joint_objects(SCENE)
BEDDING = [j for j in _SETS if j.name.startswith("bedding_")]
CROSS = [j for j in _SETS if j.name.startswith("cross_")]
JOINT_SETS = ("bedding", "cross")
MODELS = {"intact": "intact", "jointed": "elastic joints", "slip": "slipping joints"}


def joint_laws():
    """Bedding: Tang & Jiao over Tang's substrate law; cross joints: Barton-Bandis from JRC/JCS."""
    e_star = rockjoint.composite_modulus(YOUNG, POISSON)
    summits = SCENE["joints"]["bedding"]["law"]["parameters"]   # η, β, σ_s of the scene
    bedding = rockjoint.TangJiao(rockjoint.TangSubstrate(e_star, summits["summit_density"],
                                                         summits["summit_radius"],
                                                         summits["summit_height_std"]))
    cross = rockjoint.BartonBandis.from_joint_properties(jrc=CROSS_JRC, jcs=CROSS_JCS,
                                                         initial_aperture=CROSS_APERTURE)
    say(f"cross joints (Bandis 1983): K_ni = {cross.initial_normal_stiffness * 1e-9:.2f} MPa/mm, "
        f"V_m = {cross.maximum_closure * 1e3:.3f} mm")
    # Tables cover the stresses the scene can reach (twice the largest applied stress).
    top = 2 * max(s for _, s, _ in STAGES)
    return {"bedding": rockjoint.tabulate(bedding, max_stress=top),
            "cross": rockjoint.tabulate(cross, max_stress=top)}


def compare_with_barton_peak():
    """The Coulomb strength against the cross joints' Barton peak (same JRC/JCS, φ_r = φ_b)."""
    barton = make_strength({"model": "barton", "friction_angle": FRICTION_ANGLE, "jrc": CROSS_JRC,
                            "jcs": CROSS_JCS})
    coulomb = make_strength(STRENGTH)
    for sn in (3e6, 6e6):
        say(f"strength at σ_n = {sn * 1e-6:g} MPa: Coulomb (φ_b = {math.degrees(FRICTION_ANGLE):g}°) "
            f"{coulomb.shear_strength(sn) * 1e-6:.2f} MPa; Barton peak of the cross joints (JRC "
            f"{CROSS_JRC:g}, JCS {CROSS_JCS * 1e-6:g} MPa) {barton.shear_strength(sn) * 1e-6:.2f} MPa")


def model_of(dmesh, tables, strength=None):
    """The model with its supports and loads; returns it and the handle of the top load."""
    joints = {name: tables[s] for name, s in meshes.joint_sets_of(dmesh.names).items()}
    model = JointedRockModel(dmesh, rock=(YOUNG, POISSON), joints=joints,
                             shear_stiffness_ratio=SHEAR_RATIO if joints else None,
                             strength=strength if joints else None,
                             plane="strain", newton=NewtonOptions(verbose=False))
    model.fix("bottom", "y")
    model.fix("left", "x")
    top = model.add_traction("top", (0.0, -STAGES[0][1]))
    model.add_traction("right", (-HORIZONTAL_STRESS, 0.0))
    return model, top


def run_load_path(model, top):
    """Every stage of STAGES; per stage (settlement of the top, inward move of the right face
    [m], Newton iterations, load steps cut, gathered joint state)."""
    rows = []
    for name, vertical, steps in STAGES:
        top.value = (0.0, -vertical)
        stage = model.solve(load_steps=steps, name=name)
        cut = sum(1 for r in stage.reports if not r.converged)
        rows.append((-model.boundary_mean_displacement("top")[1],
                     -model.boundary_mean_displacement("right")[0],
                     stage.newton_iterations, cut, stage.gather_joints()))
    return rows


def joint_rows(label, k, state, set_of):
    """Per joint set: points, slipping and open points, max slip, σ_n range, max |τ|, and the
    largest mobilised friction angle atan(|τ|/σ_n) over the closed points."""
    lines = []
    shear_state = np.asarray(state["shear_state"])
    tau = np.abs(np.asarray(state["shear_traction"])).reshape(-1)
    sn = np.asarray(state["normal_stress"])
    slip = np.abs(np.asarray(state["slip"])).reshape(-1)
    for prefix in JOINT_SETS:
        sel = set_of == prefix
        closed = sel & (sn > 0)
        mobilised = np.degrees(np.arctan(tau[closed] / sn[closed])).max() if closed.any() else 0.0
        lines.append(f"{label:9}{k:>6}{prefix:>9}{sel.sum():>8}"
                     f"{(sel & (shear_state == int(ShearState.slip))).sum():>7}"
                     f"{(sel & (shear_state == int(ShearState.open))).sum():>6}"
                     f"{slip[sel].max() * 1e3:>15.6f}{sn[sel].min() * 1e-6:>10.2f} .. {sn[sel].max() * 1e-6:<6.2f}"
                     f"{tau[sel].max() * 1e-6:>12.3f}{mobilised:>10.1f}")
    return lines


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--output", default=".", help="output folder")
    ap.add_argument("--mesh-size", type=float, default=0.4, help="element size away from joints [m]")
    args = ap.parse_args()
    os.makedirs(args.output, exist_ok=True)
    out = lambda name: os.path.join(args.output, name)  # noqa: E731
    started = time.perf_counter()

    # %% 1. Laws, tabulated once; the strength ---------------------------------------------------
    tables = joint_laws()
    for name, t in tables.items():
        say(f"{name} table: {t.knot_count} knots, checked error σ {t.checked_error_stress:.1e}")
    compare_with_barton_peak()

    # %% 2. Meshes: jointed (refined toward the joints) and intact --------------------------------
    h = args.mesh_size
    jointed = distribute(meshes.jointed_block((WIDTH, HEIGHT), BEDDING + CROSS, dim=2, mesh_size=h,
                                              joint_mesh_size=h / 2, comm=COMM), COMM)
    intact = distribute(meshes.jointed_block((WIDTH, HEIGHT), [], dim=2, mesh_size=h, comm=COMM), COMM)
    say(f"jointed section: {len(jointed.names['blocks'])} blocks, "
        f"{COMM.allreduce(len(jointed.pairs))} joint facet pairs")

    # %% 3. The three models along the same load path --------------------------------------------
    models, results = {}, {}
    for label, dmesh, strength in (("intact", intact, None), ("jointed", jointed, None),
                                   ("slip", jointed, STRENGTH)):
        model, top = model_of(dmesh, tables, strength)
        results[label] = run_load_path(model, top)
        models[label] = model
        say(f"{MODELS[label]}: Newton iterations per stage "
            f"{[r[2] for r in results[label]]}, load steps cut {[r[3] for r in results[label]]}")
        model.write_xdmf(out(f"blocky_{label}.xdmf"))

    # %% 4. What slip adds ------------------------------------------------------------------------
    sets = meshes.joint_sets_of(jointed.names)   # the mesh's record of each joint's set
    set_of_tag = {int(t): sets[n] for t, n in jointed.names["joints"].items()}
    lines = [f"{'':32}{'intact':>12}{'elastic j.':>12}{'slipping j.':>12}"]
    for k, (stage, vertical, _) in enumerate(STAGES):
        lines.append(f"# stage {k + 1} ({stage}): σ_v = {vertical * 1e-6:g} MPa, "
                     f"σ_h = {HORIZONTAL_STRESS * 1e-6:g} MPa")
        for i, key in ((0, "top settlement [mm]"), (1, "right face inward [mm]")):
            lines.append(f"stage {k + 1} {key:24}"
                         + "".join(f"{results[m][k][i] * 1e3:12.6f}" for m in MODELS))
        lines.append(f"stage {k + 1} {'Newton iterations':24}"
                     + "".join(f"{results[m][k][2]:12d}" for m in MODELS))
    settle = {m: results[m][-1][0] for m in MODELS}
    squeeze = {m: results[m][-1][1] for m in MODELS}
    lines += [f"end of the path: the joints (elastic) add {1e3 * (settle['jointed'] - settle['intact']):.4f} mm "
              f"of settlement to the intact {1e3 * settle['intact']:.4f} mm; slip adds "
              f"{1e3 * (settle['slip'] - settle['jointed']):.4f} mm more "
              f"({100 * (settle['slip'] - settle['jointed']) / settle['jointed']:+.1f} %)",
              f"end of the path: the right face moves {1e3 * -squeeze['intact']:.4f} mm outward (intact), "
              f"{1e3 * -squeeze['jointed']:.4f} mm (elastic joints), {1e3 * -squeeze['slip']:.4f} mm "
              f"(slipping joints): slip adds {1e3 * (squeeze['jointed'] - squeeze['slip']):.4f} mm of "
              f"lateral expansion",
              f"strength (slipping joints): Coulomb, φ = {math.degrees(FRICTION_ANGLE):g}°, "
              f"c = {COHESION * 1e-6:g} MPa",
              f"{'model':9}{'stage':>6}{'set':>9}{'points':>8}{'slip':>7}{'open':>6}"
              f"{'max slip [mm]':>15}{'σ_n range [MPa]':>20}{'max|τ| [MPa]':>14}{'max atan':>10}"]
    for label in ("jointed", "slip"):
        for k, row in enumerate(results[label]):
            state = row[4]
            set_of = np.array([set_of_tag[int(t)] for t in state["tag"]])
            lines += joint_rows(label, k + 1, state, set_of)
    lines.append("(max atan: largest mobilised friction angle atan(|τ|/σ_n) of the closed points [°])")
    say("\n" + "\n".join(lines))
    if COMM.rank == 0:
        with open(out("blocky_rock_mass.txt"), "w") as f:
            f.write("# rockjoint blocky rock mass: 12 m x 8 m granite section, plane strain; "
                    "settlement and convergence [mm] at the end of every stage\n")
            f.write("\n".join(lines) + "\n")

    # %% 5. Pictures on the mesh ------------------------------------------------------------------
    plot_sections(models, out("blocky_rock_mass.png"))
    plot_joints(models, results, jointed, out("blocky_joint_slip.png"))
    wall = COMM.allreduce(time.perf_counter() - started, op=MPI.MAX)
    say(f"wall time: {wall:.1f} s on {COMM.size} rank(s) (mesh size {h:g} m)")
    if COMM.rank == 0:
        with open(out("blocky_rock_mass.txt"), "a") as f:
            f.write(f"wall time: {wall:.1f} s on {COMM.size} rank(s) (mesh size {h:g} m)\n")
    say(f"wrote {out('blocky_rock_mass.png')}, {out('blocky_joint_slip.png')}, "
        f"{out('blocky_rock_mass.txt')}, blocky_{{intact,jointed,slip}}.xdmf")


# %% Drawing -------------------------------------------------------------------------------------
def joint_segments(state, pairs, tri_x, tri_u):
    """The joint facets as half-segments, one per joint point (from the point to the facet's
    midpoint, so each carries its own point's state), with the displacement of each end: at a
    point the mean over the mesh nodes there (both faces of the joint), at the midpoint the mean
    of the facet's ends (P1 is linear along the facet). Returns (segments (n, 2, 2),
    displacements (n, 2, 2)) [m]."""
    from scipy.spatial import cKDTree
    x = np.asarray(state["coordinates"]).reshape(-1, 2)
    per_pair = x.shape[0] // pairs                      # points per facet pair (2: the facet nodes)
    nodes, u = tri_x.reshape(-1, 2), tri_u.reshape(-1, 2)
    hits = cKDTree(nodes).query_ball_point(x, r=1e-9 * WIDTH)
    u_points = np.array([u[h].mean(axis=0) for h in hits])

    def half_segments(a):                               # (points, 2) -> (points, 2 ends, 2)
        ends = a.reshape(pairs, per_pair, 2)
        mid = np.repeat(ends.mean(axis=1, keepdims=True), per_pair, axis=1)
        return np.stack([ends, mid], axis=2).reshape(-1, 2, 2)
    return half_segments(x), half_segments(u_points)


def style(ax, title):
    ax.set_aspect("equal")
    ax.set_xlim(-0.3, WIDTH + 0.3)
    ax.set_ylim(-0.3, HEIGHT + 0.3)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title(title, fontsize=10)


def save(fig, what, path):
    """Title (what, at the end of the load path, with the loads and the strength) and PNG."""
    import matplotlib.pyplot as plt
    fig.suptitle(f"{what} at the end of the load path: σ_v = {STAGES[-1][1] * 1e-6:g} MPa, "
                 f"σ_h = {HORIZONTAL_STRESS * 1e-6:g} MPa; strength: Coulomb φ = "
                 f"{math.degrees(FRICTION_ANGLE):g}°, c = {COHESION * 1e-6:g} MPa")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_sections(models, path):
    """|u| of the three sections at the end of the load path, filled triangles, one scale."""
    tris = {label: gather_triangles(m.solution.displacement) for label, m in models.items()}
    if COMM.rank != 0:
        return
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    vmax = max(np.linalg.norm(u, axis=2).max() for _, u in tris.values()) * 1e3
    fig, axes = plt.subplots(1, 3, figsize=(17, 4.4))
    for ax, (label, (tri_x, tri_u)) in zip(axes, tris.items()):
        pts = tri_x.reshape(-1, 2)
        shade = ax.tripcolor(pts[:, 0], pts[:, 1], np.arange(pts.shape[0]).reshape(-1, 3),
                             np.linalg.norm(tri_u, axis=2).ravel() * 1e3, shading="gouraud",
                             vmin=0.0, vmax=vmax, cmap="viridis")
        fig.colorbar(shade, ax=ax, label="|u| [mm]")
        style(ax, f"{MODELS[label]}: |u| [mm]")
    save(fig, "blocky granite mass (plane strain), |u|", path)


def plot_joints(models, results, jointed, path):
    """(a) friction mobilised by the elastic joints atan(|τ|/σ_n), (b) shear state and (c) slip of
    the slipping joints on the deformed section (u magnified), joints as line segments."""
    pairs = COMM.allreduce(len(jointed.pairs))
    elastic, slipping = results["jointed"][-1][4], results["slip"][-1][4]
    tri_x, tri_u = gather_triangles(models["slip"].solution.displacement)
    if COMM.rank != 0:
        return
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import LineCollection
    from matplotlib.colors import BoundaryNorm, ListedColormap, TwoSlopeNorm
    fig, axes = plt.subplots(1, 3, figsize=(17, 4.6))

    seg, _ = joint_segments(elastic, pairs, tri_x, tri_u)
    sn = np.asarray(elastic["normal_stress"])
    tau = np.abs(np.asarray(elastic["shear_traction"])).reshape(-1)
    angle = np.degrees(np.arctan2(tau, np.maximum(sn, 1e-30)))
    phi = math.degrees(FRICTION_ANGLE)
    lines = LineCollection(seg, array=angle, cmap="coolwarm", linewidths=2.0,
                           norm=TwoSlopeNorm(vcenter=phi, vmin=0.0, vmax=max(angle.max(), phi + 1.0)))
    axes[0].add_collection(lines)
    fig.colorbar(lines, ax=axes[0], label=f"atan(|τ|/σ_n) [°] (white: φ = {phi:g}°; red: beyond it)")
    style(axes[0], "elastic joints: friction they mobilise")

    seg, disp = joint_segments(slipping, pairs, tri_x, tri_u)
    scale = 0.4 / max(np.linalg.norm(tri_u, axis=2).max(), 1e-300)          # largest |u| drawn 0.4 m
    deformed = tri_x + scale * tri_u
    pts = deformed.reshape(-1, 2)
    magnitude = np.linalg.norm(tri_u, axis=2).ravel()
    for ax in axes[1:]:                                 # the deformed section, |u| in light grey
        ax.tripcolor(pts[:, 0], pts[:, 1], np.arange(pts.shape[0]).reshape(-1, 3), magnitude,
                     cmap="Greys", vmin=0.0, vmax=4.0 * magnitude.max(), shading="gouraud")
    states = ListedColormap(["tab:blue", "tab:red", "gold"])
    lines = LineCollection(seg + scale * disp, array=np.asarray(slipping["shear_state"], dtype=float),
                           cmap=states, norm=BoundaryNorm([-0.5, 0.5, 1.5, 2.5], 3), linewidths=2.2)
    axes[1].add_collection(lines)
    bar = fig.colorbar(lines, ax=axes[1], ticks=[0, 1, 2])
    bar.ax.set_yticklabels(["stick", "slip", "open"])
    style(axes[1], f"slipping joints: shear state (deformed, u × {scale:.0f})")
    slip = np.abs(np.asarray(slipping["slip"])).reshape(-1) * 1e3
    lines = LineCollection(seg + scale * disp, array=slip, cmap="magma_r", linewidths=2.2)
    axes[2].add_collection(lines)
    fig.colorbar(lines, ax=axes[2], label="|slip| [mm]")
    style(axes[2], f"slipping joints: slip [mm] (deformed, u × {scale:.0f})")
    save(fig, "joints", path)


if __name__ == "__main__":
    main()
