#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""A circular tunnel excavated in a jointed rock mass at 300 m depth, beside the same tunnel in intact rock.

Read it top to bottom; run it as it is (serial or `mpirun -n 2`):

    PYTHONPATH=python:build/python /usr/bin/python3 demos/demo_tunnel.py [--output DIR] [--quick]

With --opening horseshoe the same tunnel as a horseshoe (demos/scenes/tunnel_horseshoe.yaml: 8 m span,
semicircular crown, 3 m walls, 1 m invert) is run as its scene instead (`horseshoe` below).

The scene: an 8 m diameter tunnel (a = 4 m) with its axis 300 m deep in granite (ρ = 2700 kg/m³:
σ_v = ρ g z = 7.95 MPa at the axis, uniform over the section), horizontal stress σ_h = K0 σ_v with
K0 = 0.5, plane strain, in a 80 m x 80 m section (W/a = 20) with rollers on its four sides. Two joint
sets cross the tunnel: bedding planes (horizontal, 3 m apart) carrying the Tang & Jiao law of a
synthetic mated granite joint (its topography → η, β, σ_s → the recommended law, tabulated once), and
a cross set dipping 60° (5 m apart) with a Barton-Bandis law from JRC, JCS and aperture. The intact
section is meshed with the same triangles (the joint traces kept as mesh lines) and solved beside it,
and the jointed section twice: with elastic joints (any shear stress) and with slipping joints (a
Coulomb strength on both sets, docs/joint-strength.md: a joint point slips once |τ| = c + σ_n tan φ),
and a third time with hysteretic joints (docs/hysteresis.md: joints pre-closed in situ unload on stiff
branches with a permanent closure, as laboratory cycles show, instead of springing back along the soft
virgin curve).

Stages (rockjoint's staged analysis, docs/staged-analysis.md): in-situ (σ0 in equilibrium, joints
pre-closed to their law's closure at their initial normal stress) → excavation (the in-situ traction
on the opening released in load steps) → a 0.5 MPa lining pressure. Displacements are relative to
the in-situ state, so the intact tunnel's wall displacement is Kirsch's excavation displacement
(rockjoint.reference.kirsch), up to the W/a = 20 domain and the mesh (docs/tunnel.md).

Outputs (in DIR): tunnel.png (hoop stress on the mesh, the deformed opening outline, joints coloured
by their closure change), tunnel_joint_slip.png (the slipping joints on the deformed section, coloured
by shear state and by slip), tunnel.txt (the numbers), tunnel_{intact,jointed,slip}.xdmf (the
displacement at the end, + tunnel_{jointed,slip}_joints.xdmf, the joint state incl. slip_m and
shear_state), tunnel_<label>_stress.xdmf (the total stress after excavation, per cell, tension
positive [Pa]) for ParaView, and tunnel_slip_joints.npz (the slipping model's joint points after
excavation: coordinates, set, normal_stress, shear_traction [Pa], shear_state, slip [m]). Units in
print: mm, MPa, m.
"""
import argparse
import math
import os
import time

import numpy as np
from mpi4py import MPI

import rockjoint
from rockjoint.console import quiet_compiler_logging, rank_logger
from rockjoint import meshes
from rockjoint import topography as topo
from rockjoint import contact, flow
from rockjoint.fem import (InSituStress, JointedRockModel, NewtonOptions, ShearState, darcy_flow,
                                    distribute, network_flow)
from rockjoint.fem.output.fields import gather_triangles, write_functions
from rockjoint.fem.output.probe import probe
from rockjoint.reference import KirschSolution
from rockjoint.scenes import geometry as scene_geometry, load_scene, make_plan, run_scene
from rockjoint.scenes.summary import summary_table

COMM = MPI.COMM_WORLD
quiet_compiler_logging()  # DOLFINx's form compiler would log every command
log = rank_logger("demo_tunnel", COMM)

# %% The scene: demos/scenes/tunnel.yaml ------------------------------------------------------
# The scene file states the set-up (`python3 -m rockjoint run demos/scenes/tunnel.yaml` runs it with
# the planner's choices); this script adds the slipping/elastic comparison, Kirsch and the pictures.
SCENE = load_scene(os.path.join(os.path.dirname(os.path.abspath(__file__)), "scenes", "tunnel.yaml"))
_OPENING = SCENE["geometry"]["opening"]
RADIUS = _OPENING["radius"]        # tunnel radius a [m] (8 m diameter)
SIGMA_V = SCENE["in_situ"]["vertical"]  # ρ g z = 2700 kg/m³ x 9.81 m/s² x 300 m = 7.95 MPa
K0 = SCENE["in_situ"]["horizontal_ratio"]  # σ_h / σ_v
DEPTH = 300.0                      # depth of the axis [m] (titles; the scene's σ_v is ρ g z there)
WIDTH, HEIGHT = SCENE["geometry"]["width"], SCENE["geometry"]["height"]  # section [m], W/a = 20
CENTRE = tuple(_OPENING["centre"])
YOUNG, POISSON = SCENE["rock"]["young"], SCENE["rock"]["poisson"]        # granite
LINING_PRESSURE = SCENE["stages"][-1]["loads"]["opening"]["pressure"]    # [Pa]
_JOINT = SCENE["joints"]["bedding"]
SHEAR_RATIO = _JOINT["shear_stiffness_ratio"]     # joint shear stiffness k_s = 0.1 k_n(Δ)
RESIDUAL_STIFFNESS = _JOINT["residual_stiffness"]  # [Pa/m], keeps a block held only by open joints from being singular
# Strength of the slipping model, both sets: Coulomb with the basic friction angle of wet
# fine-grained granite, φ_b = 29-31° (Barton & Choubey 1977, Table 2: 31-35° dry, 29-31° wet),
# taken as 30°, and no cohesion (Barton 1973: natural unfilled joints have no reliable cohesion or
# tensile strength): the strength of a planar or sheared-through joint, the lower bound.
FRICTION_ANGLE = _JOINT["strength"]["friction_angle"]  # [rad]
COHESION = _JOINT["strength"]["cohesion"]              # [Pa]
STRENGTH = {"model": "coulomb", "friction_angle": FRICTION_ANGLE, "cohesion": COHESION}
MODELS = {"intact": "intact", "jointed": "elastic joints", "slip": "slipping joints"}
# Hysteretic joints (docs/hysteresis.md): the same virgin laws, unloading on branches with a
# permanent closure r = 0.25 of the largest closure and an unloading stiffness 3 times the loading
# one at the top: the middle of what Bandis et al. (1983) measured on fresh joints (20-30 %,
# 2-4 times). Not calibrated to this rock; the top is each set's in-situ closure (H4 gives m).
PERMANENT_FRACTION, UNLOADING_RATIO = 0.25, 3.0


def hysteretic(tables):
    """{set: NormalHysteresis} with m from (H4): k_u/k_v = m σ_m / ((1 - r) Δ_m k_v(Δ_m)) = 3 at
    the set's in-situ normal stress σ_m (joint normal (sin dip, cos dip) in the σ_h, σ_v field)."""
    out = {}
    for name, table in tables.items():
        dip = SCENE["geometry"]["joint_sets"][[s["name"] for s in SCENE["geometry"]["joint_sets"]].index(name)]["dip"]
        sigma = K0 * SIGMA_V * math.sin(dip) ** 2 + SIGMA_V * math.cos(dip) ** 2
        closure = table.closure_at_stress(sigma)
        m = UNLOADING_RATIO * (1 - PERMANENT_FRACTION) * closure * table.normal_stiffness(closure) / sigma
        out[name] = rockjoint.NormalHysteresis(table, PERMANENT_FRACTION, max(m, 1.0))
        log.info("%s hysteresis: r = %.2f, m = %.2f (unloading %.1f x stiffer at σ_n = %.2f MPa)", name,
                 PERMANENT_FRACTION, max(m, 1.0), UNLOADING_RATIO, sigma * 1e-6)
    return out

# Bedding: horizontal, 3 m apart, the nearest 1.5 m above and below the axis (none tangent to the
# opening); cross set: dip 60° toward +x, 5 m apart, one through the axis.
_SETS = scene_geometry.joint_objects(SCENE)
BEDDING = [j for j in _SETS if j.name.startswith("bedding_")]
CROSS = [j for j in _SETS if j.name.startswith("cross_")]


def joint_laws():
    """Bedding: Tang & Jiao from a synthetic mated granite joint; cross set: Barton-Bandis (JRC/JCS).
    Returns the tables and the bedding's walls (upper, lower, their closure parameters)."""
    scan = SCENE["joints"]["bedding"]["law"]["topography"]  # a 64 mm scan at 0.5 mm
    n, spacing = scan["points"], scan["spacing"]
    spec = topo.SelfAffineSpec(hurst_exponent=scan["hurst"], rms_height=scan["rms_height"])
    upper, lower = topo.mated_pair(spec, (n, n), spacing, scan["matedness"], seed=scan["seed"])
    analysis = topo.analyse(topo.composite_topography(upper, lower, offset=(0, 0)).composite)
    params = topo.closure_parameters(analysis, young=YOUNG, poisson=POISSON)
    bedding = rockjoint.laws.laws_from_topography(params, summits=analysis, empirical=False)
    bedding = bedding[rockjoint.laws.RECOMMENDED].law
    cross = rockjoint.BartonBandis.from_joint_properties(jrc=CROSS_JRC, jcs=80e6, initial_aperture=CROSS_APERTURE)
    log.info("bedding (Tang & Jiao from the topography): η = %.3f /mm², β = %.3f mm, σ_s = %.4f mm",
             params.summit_density * 1e-6, params.summit_radius * 1e3, params.summit_height_std * 1e3)
    log.info("cross set (Bandis 1983): K_ni = %.2f MPa/mm, V_m = %.3f mm",
             cross.initial_normal_stiffness * 1e-9, cross.maximum_closure * 1e3)
    # Tables cover the stresses the scene can reach (the sidewall hoop stress is 2.5 σ_v).
    top = 4.0 * SIGMA_V
    return {"bedding": rockjoint.tabulate(bedding, max_stress=top, tolerance=1e-6),
            "cross": rockjoint.tabulate(cross, max_stress=top, tolerance=1e-6)}, (upper, lower, params)


# Flow (docs/flow.md): water drains into the tunnel from the rock around it. Heads: the far field
# keeps the hydrostatic head of a water table at the surface, 300 m above the axis; the tunnel is
# drained (h = 0); elevation differences across the section (±40 m) are left out: the heads are
# pressure heads at the axis. Transmissivity: the bedding joint's from its own walls (BEM contact
# and Reynolds flow on its gap field); the cross set's by Barton's JRC conversion of its mechanical
# aperture (the same JRC and aperture as its closure law). Intact granite: k = 1e-19 m², within
# what Brace (1980, IJRMMS 17, 241-251) gives for intact crystalline rock at depth (1e-21 to 1e-18 m²).
FLOW_HEADS = {"left": DEPTH, "right": DEPTH, "bottom": DEPTH, "top": DEPTH, "opening": 0.0}   # [m]
ROCK_PERMEABILITY = 1e-19   # [m²]
CROSS_JRC, CROSS_APERTURE = 8.0, 0.4e-3


def transmissivity_laws(bedding_walls):
    """{set: TransmissivityLaw}: the bedding's from its walls' closure curve with flow, up to the
    tables' top stress; the cross set's Barton conversion."""
    upper, lower, params = bedding_walls
    aperture = topo.composite_topography(upper, lower, offset=(0, 0)).aperture
    curve = contact.closure_curve(aperture, params.composite_modulus,
                                  np.geomspace(0.05e6, 4.0 * SIGMA_V, 16), flow=True)
    return {"bedding": flow.transmissivity_law("walls", curve=curve),
            "cross": flow.transmissivity_law("barton_jrc", initial_aperture=CROSS_APERTURE, jrc=CROSS_JRC)}


def flow_lines(state, dist, theta, model, intact_dmesh, laws, names, out):
    """The joints' transmissivity before and after excavation (elastic joints) and the inflow into
    the drained tunnel: along the joint network with the in-situ and the excavated closures, and
    through the intact rock (Darcy) beside them."""
    sets = joint_set_of(state["in-situ"], names)   # names: the mesh's groups (dmesh.names)
    t = {}
    for stage in ("in-situ", "excavation"):
        closure = np.asarray(state[stage]["closure"])
        t[stage] = np.zeros(closure.size)
        for name, law in laws.items():
            t[stage][sets == name] = law.transmissivity(closure[sets == name])
    ratio = t["excavation"] / t["in-situ"]
    near = dist < 0.5
    crown = near & (np.abs(np.sin(theta)) > 0.9) & (sets == "bedding")
    side = near & (np.abs(np.cos(theta)) > 0.9) & (sets == "bedding")
    per_joint = {n: laws[s].transmissivity for n, s in meshes.joint_sets_of(names).items()}
    networks = {stage: network_flow(model, per_joint, FLOW_HEADS, stage=model.stages[i])
                for i, stage in ((0, "in-situ"), (1, "excavation"))}
    networks["excavation"].write(out("tunnel_flow.xdmf"), COMM)
    rates = {stage: network.flow_rates["opening"] for stage, network in networks.items()}
    intact = darcy_flow(intact_dmesh, ROCK_PERMEABILITY * np.eye(2), FLOW_HEADS).flow_rates["opening"]
    lmin = 6e4   # m²/s -> L/min per metre of tunnel
    return [
        "flow (water; far-field head 300 m, tunnel drained; docs/flow.md):",
        f"joint transmissivity after / before excavation, within 0.5 a of the wall: bedding at the crown "
        f"and invert median x{np.median(ratio[crown]):.3g} (radial stress released: they open), at the "
        f"sidewalls median x{np.median(ratio[side]):.3g} (hoop stress: they close); all joints "
        f"x{ratio[near].min():.3g} to x{ratio[near].max():.3g}",
        f"inflow into the tunnel [L/min per m]: intact rock (k = {ROCK_PERMEABILITY:g} m²) "
        f"{-intact * lmin:.4g}; joints at their in-situ closure {-rates['in-situ'] * lmin:.4g}, "
        f"after excavation {-rates['excavation'] * lmin:.4g} (x{rates['excavation'] / rates['in-situ']:.3g})"]


def section(mesh_size, intact):
    opening = meshes.CircularOpening(CENTRE, RADIUS)
    return meshes.tunnel_section(WIDTH, HEIGHT, opening, BEDDING + CROSS, mesh_size=mesh_size,
                                 opening_mesh_size=mesh_size / 8, opening_refine_distance=2 * RADIUS,
                                 joint_mesh_size=mesh_size / 4, joint_refine_distance=mesh_size,
                                 intact=intact, comm=COMM)


def staged_model(dmesh, tables, steps, after_excavation, strength=None):
    """In-situ → excavation → lining pressure; after_excavation(model) runs between the last two
    stages; strength: the joints' (None: elastic joints). Returns the model (its stages kept in
    model.stages)."""
    joints = {name: tables[s] for name, s in meshes.joint_sets_of(dmesh.names).items()}
    model = JointedRockModel(dmesh, rock=(YOUNG, POISSON), joints=joints,
                             shear_stiffness_ratio=SHEAR_RATIO if joints else None,
                             residual_stiffness=RESIDUAL_STIFFNESS if joints else 0.0,
                             strength=strength if joints else None,
                             plane="strain", newton=NewtonOptions(verbose=False))
    for side, component in (("left", "x"), ("right", "x"), ("bottom", "y"), ("top", "y")):
        model.fix(side, component)
    model.set_in_situ_stress(InSituStress.uniform([[-K0 * SIGMA_V, 0.0], [0.0, -SIGMA_V]]))
    model.solve(name="in-situ")
    model.excavate(meshes.OPENING)
    model.solve(load_steps=steps, name="excavation")
    after_excavation(model)
    model.add_pressure(meshes.OPENING, LINING_PRESSURE)
    model.solve(load_steps=1, name="lining")
    return model


def wall_points(h_wall):
    """Points just inside the rock at θ = 0 (right sidewall), 90° (crown), 180°, 270° (invert), and
    the outline (360 points) for the deformed-shape plot: at r = a + h²/(4a), twice the sagitta of
    the mesh's chords, so that they lie in the mesh."""
    r = RADIUS + h_wall ** 2 / (4 * RADIUS)
    th = np.concatenate([[0.0, 0.5 * math.pi, math.pi, 1.5 * math.pi], np.linspace(0, 2 * math.pi, 361)[:-1]])
    return r, th, np.stack([CENTRE[0] + r * np.cos(th), CENTRE[1] + r * np.sin(th)], axis=1)


def radial_hoop(sigma, th):
    """(σ_rr, σ_θθ) compression positive from tension-positive tensors (n, 2, 2) at angles th."""
    c, s = np.cos(th), np.sin(th)
    er, et = np.stack([c, s], 1), np.stack([-s, c], 1)
    return (-np.einsum("ni,nij,nj->n", er, sigma, er), -np.einsum("ni,nij,nj->n", et, sigma, et))


def cell_hoop_stress(model, stress):
    """(triangles (n, 3, 2), hoop stress [Pa, compression +]) of the owned cells, gathered on rank 0."""
    mesh = model.mesh
    n = mesh.topology.index_map(2).size_local
    x = mesh.geometry.x[:, :2]
    tri = x[mesh.geometry.dofmaps[0][:n]]
    centroid = tri.mean(axis=1)
    sig = stress.x.array.reshape(-1, 2, 2)[stress.function_space.dofmap.list.ravel().reshape(-1)[:n]]
    th = np.arctan2(centroid[:, 1] - CENTRE[1], centroid[:, 0] - CENTRE[0])
    hoop = radial_hoop(sig, th)[1]
    tri, _, hoop = gather_triangles(model.u, cell_values=hoop)
    return tri, hoop


def joint_segments(state):
    """(segments (m, 2, 2), per-segment point rows (m, k)) of the joints from the point state
    (points come in groups per facet pair, the pair's endpoints among them)."""
    xy = np.asarray(state["coordinates"]).reshape(-1, 2)
    k = 2  # points per pair of the nodal rule on P1 segments
    groups = np.arange(xy.shape[0]).reshape(-1, k)
    return xy[groups], groups


def joint_set_of(state, mesh_names):
    """The joint set ("bedding", "cross") of every joint point, from its tag: the mesh's own
    record of each joint's set (its names["joint_sets"])."""
    sets = meshes.joint_sets_of(mesh_names)
    return np.array([sets[mesh_names["joints"][int(t)]] for t in state["tag"]])


def slip_rows(state, mesh_names):
    """Per joint set after excavation (slipping model): points, slipping points (count and fraction),
    the farthest slipping point from the wall [tunnel radii], the largest slip [mm]."""
    set_of = joint_set_of(state, mesh_names)
    slips = np.asarray(state["shear_state"]) == int(ShearState.slip)
    xy = np.asarray(state["coordinates"]).reshape(-1, 2)
    dist = (np.hypot(xy[:, 0] - CENTRE[0], xy[:, 1] - CENTRE[1]) - RADIUS) / RADIUS
    slip = np.abs(np.asarray(state["slip"])).reshape(-1)
    lines = [f"slipping joints after excavation (Coulomb φ = {math.degrees(FRICTION_ANGLE):g}°, "
             f"c = {COHESION * 1e-6:g} MPa):",
             f"{'joint set':12}{'points':>8}{'slipping':>10}{'fraction':>10}{'farthest [a]':>14}{'max slip [mm]':>15}"]
    for name in ("bedding", "cross"):
        sel = set_of == name
        hit = sel & slips
        lines.append(f"{'slip ' + name:12}{sel.sum():8d}{hit.sum():10d}{100 * hit.sum() / sel.sum():9.1f}%"
                     f"{(dist[hit].max() if hit.any() else 0.0):14.2f}{slip[sel].max() * 1e3:15.4f}")
    return lines


def horseshoe(args):
    """The tunnel as a horseshoe (8 m span, semicircular crown, 3 m walls, 1 m invert): its scene
    file run as `python3 -m rockjoint run` runs it (the planner chooses the mesh, laws and slip;
    --quick: the scene's reduced size); outputs in OUTPUT/tunnel_horseshoe. Kirsch's closed form is
    a circle's: docs/tunnel.md compares the horseshoe's intact convergence with the circle of equal area."""
    scene = load_scene(os.path.join(os.path.dirname(os.path.abspath(__file__)), "scenes", "tunnel_horseshoe.yaml"))
    scene = scene.at_reduced_size() if args.quick else scene
    plan = make_plan(scene)
    log.info("horseshoe tunnel: %s", "; ".join(f"{c.topic}: {c.choice}" for c in plan.choices))
    result = run_scene(scene, plan, os.path.join(args.output, "tunnel_horseshoe"), comm=COMM)
    if COMM.rank == 0:
        print("\n" + summary_table(result), flush=True)
    log.info("wrote %s in %s (%.1f s)", ", ".join(result.files), os.path.join(args.output, "tunnel_horseshoe"),
             result.seconds)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--output", default=".", help="output folder")
    ap.add_argument("--mesh-size", type=float, default=2.0,
                    help="element size far from the opening [m]; opening h/8, joints h/4")
    ap.add_argument("--quick", action="store_true", help="a coarse version (mesh size 8 m, 2 excavation steps)")
    ap.add_argument("--opening", choices=("circle", "horseshoe"), default="circle",
                    help="horseshoe: the same tunnel as a horseshoe (demos/scenes/tunnel_horseshoe.yaml), run as "
                         "its scene: jointed beside intact, the planner's choices, pictures and the summary table")
    args = ap.parse_args()
    if args.opening == "horseshoe":
        return horseshoe(args)
    t_start = time.perf_counter()
    os.makedirs(args.output, exist_ok=True)
    out = lambda name: os.path.join(args.output, name)  # noqa: E731
    h = 8.0 if args.quick else args.mesh_size
    steps = 2 if args.quick else 4

    # %% 1. Joint laws, tabulated once ----------------------------------------------------------
    tables, bedding_walls = joint_laws()

    # %% 2. Meshes: jointed and intact on the same triangles ------------------------------------
    jointed = distribute(section(h, intact=False), COMM)
    intact = distribute(section(h, intact=True), COMM)
    log.info("jointed section: %d blocks, %d joint facet pairs; element size %.2f m at the wall, %.2f m far",
             len(jointed.names["blocks"]), COMM.allreduce(len(jointed.pairs)), h / 8, h)

    # %% 3. Stages: in-situ → excavation → lining; the wall and the stresses after excavation ------
    kirsch = KirschSolution(RADIUS, SIGMA_V, K0, YOUNG, POISSON, CENTRE)
    r_wall, th, pts = wall_points(h / 8)
    # P1 stresses are constant per cell: compare them where the wall cells' centroids lie (r ≈ a + h/3)
    r_stress = RADIUS + h / 24
    pts_stress = np.stack([CENTRE[0] + r_stress * np.cos(th[:4]), CENTRE[1] + r_stress * np.sin(th[:4])], axis=1)
    models, wall, stress_at = {}, {}, {}

    def record(label):
        def after_excavation(model):
            u = probe(model.u, pts)  # relative to the in-situ state
            wall[label] = (u, np.einsum("ni,ni->n", u, np.stack([np.cos(th), np.sin(th)], 1)))
            stress = model.total_stress()  # σ0 + σ(u), tension positive [Pa]
            stress.name = "total_stress_Pa"
            write_functions(out(f"tunnel_{label}_stress.xdmf"), stress)
            stress_at[label] = (stress, radial_hoop(probe(stress, pts_stress).reshape(-1, 2, 2), th[:4])[1])
        return after_excavation

    hyst = hysteretic(tables)
    for label, dmesh, laws, strength in (("intact", intact, tables, None), ("jointed", jointed, tables, None),
                                         ("slip", jointed, tables, STRENGTH), ("hyst", jointed, hyst, None)):
        t0 = time.perf_counter()
        models[label] = staged_model(dmesh, laws, steps, record(label), strength)
        log.info("%s: %s (%.1f s)", label, ", ".join(f"{s.name} {s.newton_iterations} Newton it."
                                                      for s in models[label].stages), time.perf_counter() - t0)
        models[label].write_xdmf(out(f"tunnel_{label}.xdmf"))  # the final (lining) stage

    # %% 4. Wall convergence, stress concentration, joints --------------------------------------
    ur_kirsch = kirsch.excavation_displacement(np.full(4, RADIUS), th[:4])[0]
    state = {name: models["jointed"].stages[i].gather_joints() for i, name in ((0, "in-situ"), (1, "excavation"))}
    closure_change = state["excavation"]["closure"] - state["in-situ"]["closure"]
    xy = np.asarray(state["excavation"]["coordinates"]).reshape(-1, 2)
    dist = (np.hypot(xy[:, 0] - CENTRE[0], xy[:, 1] - CENTRE[1]) - RADIUS) / RADIUS
    # Opened: the joint opened at excavation by more than 10 % of its in-situ closure (it lost a good
    # part of its pre-closure); separated: it lost contact (closure <= 0, no normal stress).
    opened = closure_change < -0.1 * np.asarray(state["in-situ"]["closure"])
    separated = np.asarray(state["excavation"]["closure"]) <= 0.0
    extent = float(dist[opened].max()) if opened.any() else 0.0
    extent_separated = float(dist[separated].max()) if separated.any() else 0.0

    names = ("right sidewall", "crown", "left sidewall", "invert")
    conv_i, conv_j, conv_s = (-wall[label][1][:4] for label in MODELS)
    conv_h = -wall["hyst"][1][:4]
    lines = [f"{'after excavation':34}{'Kirsch':>10}{'intact':>10}{'jointed':>10}{'slipping':>10}{'joints share':>14}",
             "(jointed: elastic joints; slipping: Coulomb joints; joints share: of the elastic-joint convergence)"]
    for k, name in enumerate(names):
        share = (conv_j[k] - conv_i[k]) / conv_j[k]
        lines.append(f"{'wall convergence ' + name + ' [mm]':34}{-ur_kirsch[k] * 1e3:10.3f}{conv_i[k] * 1e3:10.3f}"
                     f"{conv_j[k] * 1e3:10.3f}{conv_s[k] * 1e3:10.3f}{100 * share:13.1f}%")
    hoop_k = kirsch.polar_stress(np.full(4, r_stress), th[:4])[1]
    for k in (0, 1):
        lines.append(f"{'hoop stress ' + names[k] + ' [MPa]*':34}{hoop_k[k] * 1e-6:10.2f}"
                     + "".join(f"{stress_at[label][1][k] * 1e-6:10.2f}" for label in MODELS))
    lines += [f"* at r = a + h/3 = {r_stress:.3f} m (the wall cells' centroids, h = {h / 8:g} m at the wall)",
              f"stress concentration at the wall (Kirsch, r = a): sidewall {3 - K0:.2f} σ_v, crown {3 * K0 - 1:.2f} σ_v",
              f"joint closure change at excavation [mm]: min {closure_change.min() * 1e3:.4f}, "
              f"max {closure_change.max() * 1e3:.4f} (< 0: opening)",
              f"opened joint points (> 10 % of the in-situ closure): {int(opened.sum())} of {opened.size}; "
              f"opened zone extends {extent:.2f} a from the wall",
              f"separated joint points (closure <= 0): {int(separated.sum())}; farthest {extent_separated:.2f} a "
              "from the wall"]
    push = [probe(models[k].stages[2].displacement, pts[1:2])[0, 1] - wall[k][0][1, 1] for k in MODELS]
    lines.append(f"lining pressure {LINING_PRESSURE * 1e-6:g} MPa moves the crown up by [mm]: intact "
                 f"{push[0] * 1e3:.4f}, jointed {push[1] * 1e3:.4f}, slipping {push[2] * 1e3:.4f}")
    slipping = models["slip"].stages[1].gather_joints()
    lines += slip_rows(slipping, jointed.names)
    # Hysteretic joints: excavation unloads the joints near the wall on their stiff branches.
    hs = {name: models["hyst"].stages[i].gather_joints() for i, name in ((0, "in-situ"), (1, "excavation"))}
    h_change = np.asarray(hs["excavation"]["closure"]) - np.asarray(hs["in-situ"]["closure"])
    h_opened = h_change < -0.1 * np.asarray(hs["in-situ"]["closure"])
    h_extent = float(dist[h_opened].max()) if h_opened.any() else 0.0
    lines += [f"hysteretic joints (r = {PERMANENT_FRACTION}, unloading {UNLOADING_RATIO:g} x stiffer at the in-situ "
              "closure; docs/hysteresis.md):",
              "wall convergence hysteretic [mm]: " + ", ".join(
                  f"{name} {conv_h[k] * 1e3:.3f} (joints' share {100 * (conv_h[k] - conv_i[k]) / conv_h[k]:.1f}%)"
                  for k, name in enumerate(names)),
              f"hysteretic opened joint points (> 10 % of the in-situ closure): {int(h_opened.sum())} of "
              f"{h_opened.size}; opened zone extends {h_extent:.2f} a from the wall (elastic joints: "
              f"{int(opened.sum())}, {extent:.2f} a)"]
    lines.append("Newton iterations (in-situ, excavation, lining): " + "; ".join(
        f"{MODELS[label]} " + ", ".join(str(s.newton_iterations) for s in models[label].stages) for label in MODELS))
    lines.append("Newton iterations, hysteretic joints: " + ", ".join(str(s.newton_iterations)
                                                                      for s in models["hyst"].stages))
    xy0 = np.asarray(state["in-situ"]["coordinates"]).reshape(-1, 2)
    theta = np.arctan2(xy0[:, 1] - CENTRE[1], xy0[:, 0] - CENTRE[0])
    lines += flow_lines(state, dist, theta, models["jointed"], intact, transmissivity_laws(bedding_walls),
                        jointed.names, out)
    elapsed = time.perf_counter() - t_start
    lines.append(f"demo wall time [s]: {COMM.allreduce(elapsed, op=MPI.MAX):.1f} on {COMM.size} rank(s)")
    if COMM.rank == 0:
        print("\n" + "\n".join(lines), flush=True)
        with open(out("tunnel.txt"), "w") as f:
            f.write(f"# rockjoint tunnel demo: a = {RADIUS} m at {DEPTH:g} m depth, σ_v = {SIGMA_V * 1e-6:.2f} MPa, "
                    f"K0 = {K0}, plane strain, mesh size {h} m (wall {h / 8} m)\n")
            f.write("\n".join(lines) + "\n")
        np.savez(out("tunnel_slip_joints.npz"), set=joint_set_of(slipping, jointed.names),
                 **{k: np.asarray(slipping[k]) for k in ("coordinates", "normal_stress", "shear_traction",
                                                         "shear_state", "slip")})
    plot(models, stress_at, wall, pts, th, state, closure_change, out("tunnel.png"))
    plot_slip(models["slip"], slipping, wall["slip"], pts, out("tunnel_joint_slip.png"))


def frame(ax):
    """Equal axes on the central 3a x 3a around the opening, labelled in metres."""
    zoom = 3.0 * RADIUS
    ax.set_aspect("equal")
    ax.set_xlim(CENTRE[0] - zoom, CENTRE[0] + zoom)
    ax.set_ylim(CENTRE[1] - zoom, CENTRE[1] + zoom)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")


def plot(models, stress_at, wall, pts, th, state, closure_change, path):
    cells = {label: cell_hoop_stress(models[label], stress_at[label][0]) for label in ("intact", "jointed")}
    if COMM.rank != 0:
        return
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import LineCollection
    from matplotlib.tri import Triangulation

    fig, axes = plt.subplots(1, 3, figsize=(17, 5.4))
    vmax = max(c[1].max() for c in cells.values()) * 1e-6
    vmin = min(0.0, min(c[1].min() for c in cells.values()) * 1e-6)  # tension (< 0) at a low-K0 crown
    for ax, label in zip(axes[:2], ("intact", "jointed")):
        tri, hoop = cells[label]
        t = Triangulation(tri.reshape(-1, 2)[:, 0], tri.reshape(-1, 2)[:, 1], np.arange(tri.shape[0] * 3).reshape(-1, 3))
        pc = ax.tripcolor(t, facecolors=hoop * 1e-6, cmap="magma_r", vmin=vmin, vmax=vmax)
        fig.colorbar(pc, ax=ax, label="hoop stress σ_θθ [MPa] (compression +)")
        ax.set_title(f"{label}: hoop stress after excavation")
    # Deformed outline: the wall displacement magnified.
    ax = axes[2]
    outline = pts[4:]
    umax = max(np.abs(wall[label][0][4:]).max() for label in ("intact", "jointed"))
    scale = 0.15 * RADIUS / umax
    ax.plot(*np.vstack([outline, outline[:1]]).T, "k:", lw=1, label="opening (undeformed)")
    for label, style in (("intact", "C0-"), ("jointed", "C3-")):
        d = outline + scale * wall[label][0][4:]
        ax.plot(*np.vstack([d, d[:1]]).T, style, lw=1.5, label=f"{label}, displacement × {scale:.0f}")
    segs, groups = joint_segments(state["excavation"])
    change = closure_change[groups].mean(axis=1) * 1e3
    lim = np.abs(change).max()
    lc = LineCollection(segs, array=change, cmap="coolwarm_r", clim=(-lim, lim), linewidths=2.0)
    ax.add_collection(lc)
    fig.colorbar(lc, ax=ax, label="joint closure change at excavation [mm] (< 0: opening)")
    ax.set_title("deformed opening and joints")
    ax.legend(loc="lower left", fontsize=7)
    for ax in axes:
        frame(ax)
    fig.suptitle(f"{2 * RADIUS:g} m tunnel at {DEPTH:g} m depth, σ_v = {SIGMA_V * 1e-6:.2f} MPa, K0 = {K0} "
                 "(plane strain; the central 24 m of the 80 m section)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def plot_slip(model, state, wall, pts, path):
    """The slipping model's joints after excavation as line segments on the deformed section
    (displacement magnified; the joint points moved by the displacement of one of their faces):
    (a) shear state, (b) slip [mm]."""
    segs, groups = joint_segments(state)
    u = probe(model.stages[1].displacement, segs.reshape(-1, 2)).reshape(segs.shape)
    if COMM.rank != 0:
        return
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import LineCollection
    from matplotlib.colors import ListedColormap

    outline = pts[4:]
    scale = 0.15 * RADIUS / np.abs(wall[0][4:]).max()
    moved = outline + scale * wall[0][4:]
    shear_state = np.asarray(state["shear_state"])[groups]
    # a segment slips (opens) when either of its points does; open wins over slip
    seg_state = np.where((shear_state == int(ShearState.open)).any(1), int(ShearState.open),
                         np.where((shear_state == int(ShearState.slip)).any(1), int(ShearState.slip),
                                  int(ShearState.stick)))
    slip = np.abs(np.asarray(state["slip"])).reshape(-1)[groups].max(axis=1) * 1e3
    fig, axes = plt.subplots(1, 2, figsize=(13, 5.6))
    order = [int(ShearState.stick), int(ShearState.slip), int(ShearState.open)]
    colours = {int(ShearState.stick): "0.6", int(ShearState.slip): "C3", int(ShearState.open): "C0"}
    cmap = ListedColormap([colours[v] for v in sorted(order)])
    panels = ((seg_state.astype(float), cmap, (min(order) - 0.5, max(order) + 0.5), "shear state"),
              (slip, "viridis", (0.0, max(slip.max(), 1e-12)), "slip [mm]"))
    for ax, (values, cm, clim, label) in zip(axes, panels):
        ax.fill(*moved.T, color="white", ec="k", lw=1.0, zorder=3)
        lc = LineCollection(segs + scale * u, array=values, cmap=cm, clim=clim, linewidths=2.0)
        ax.add_collection(lc)
        bar = fig.colorbar(lc, ax=ax, label=label)
        if label == "shear state":
            bar.set_ticks(sorted(order))
            bar.ax.set_yticklabels([ShearState(v).name for v in sorted(order)])
        ax.set_title(f"{label} after excavation (deformed, u × {scale:.0f})")
        frame(ax)
    fig.suptitle(f"Coulomb joints (φ = {math.degrees(FRICTION_ANGLE):g}°, c = {COHESION * 1e-6:g} MPa) around the "
                 f"{2 * RADIUS:g} m tunnel at {DEPTH:g} m depth (the central 24 m of the 80 m section)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


if __name__ == "__main__":
    main()
