#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""A laboratory joint-closure test, from the roughness of the joint to the FE rock mass.

The main rockjoint demo. Read it top to bottom; run it as it is:

    bash scripts/demo.sh                       # builds, then runs this file in ./out
    PYTHONPATH=python:build/python /usr/bin/python3 demos/demo_lab_closure_test.py [--output DIR]
    mpirun -n 2 ... (the FE part runs in parallel too)

The set-up follows Tang & Jiao (2018): a 150 mm cube of granite split by one fresh, well-mated
tensile joint at mid-height, scanned at 0.5 mm, loaded in uniaxial compression to 30 MPa. The
intact cube is loaded beside it; the joint closure is the difference of the two (Bandis et al.
1983), which is exactly what the closure law describes (docs/theory.md §0).

Outputs (in DIR, default the working directory): lab_closure_test.png (the curves),
lab_closure_test_table.txt (the numbers), granite_joint.rjt (the tabulated law),
jointed_cube.xdmf / intact_cube.xdmf (+ joint state) for ParaView, and the load cycle:
lab_closure_cycle.png / lab_closure_cycle.txt (load to 30 MPa, unload, reload: the walls'
elastic-plastic contact beside the FE cube whose joint follows a hysteretic law), and the flow along
the joint through that cycle: lab_flow_cycle.png / lab_flow_cycle.txt (transmissivity from the walls'
own gap field, and the flow through the FE cube's joint between two heads).
Units in print: mm, MPa.
"""
import argparse
import os
import time

import numpy as np
from mpi4py import MPI

import rockjoint
from rockjoint.console import quiet_compiler_logging, say
from rockjoint import contact, flow, meshes
from rockjoint import topography as topo
from rockjoint.fem import Fluid, JointedRockModel, NewtonOptions, distribute, network_flow
from rockjoint.scenes import load_scene, make_plan
from rockjoint.scenes.joint_laws import topography_law

COMM = MPI.COMM_WORLD
quiet_compiler_logging()  # DOLFINx's form compiler would log every command



# %% Parameters: from the scene file demos/scenes/lab_closure_test.yaml ---------------------
# The scene states the set-up (`python3 -m rockjoint run demos/scenes/lab_closure_test.yaml` runs
# it at its top load); this script adds the load levels, the BEM yardstick and the curves.
SCENE = load_scene(os.path.join(os.path.dirname(os.path.abspath(__file__)), "scenes",
                                "lab_closure_test.yaml"))
PLAN = make_plan(SCENE)
PLAN_LAW = next(c for c in PLAN.choices if c.topic == "law of joint")
SIDE = SCENE["geometry"]["size"][0]                              # cube side [m]
SCAN = SCENE["joints"]["joint"]["law"]["topography"]             # the synthetic scan
SPACING = SCAN["spacing"]                                        # scan interval [m]
YOUNG, POISSON = SCENE["rock"]["young"], SCENE["rock"]["poisson"]   # granite [Pa], [-]
MAX_STRESS = -SCENE["stages"][-1]["loads"]["top"]["traction"][-1]   # [Pa]
STRESS_LEVELS = np.array([0.05, 0.1, 0.2, 0.5, 1, 2, 4, 7, 10, 15, 20, 25, 30]) * 1e6  # [Pa]
TOLERANCE = PLAN.table_tolerance  # relative error of the table against the law
# The table must cover every joint normal stress the loads reach. Under uniaxial compression with
# rollers the joint carries the applied stress exactly, so the planner's bound is MAX_STRESS, and
# round-off puts about half the joint points a hair above it: its table extends 25 % past the
# bound (a few knots more), and the model's own range check finds no point beyond.
TABLE_STRESS = PLAN.table_max_stress   # [Pa]
# The load cycle (section 4): the walls are elastic-perfectly plastic with the indentation hardness
# of granite's hard minerals taken as 5 GPa (feldspar to quartz; bench/results/contact_plastic.md
# runs 2-10 GPa: the permanent closure depends on it strongly). Path: up to 30 MPa, down to
# 0.5 MPa, back up to 30 MPa.
HARDNESS = 5e9   # [Pa]
CYCLE = np.r_[STRESS_LEVELS, np.array([20, 10, 5, 2, 1, 0.5, 1, 5, 10, 20, 30]) * 1e6]   # [Pa]
# The flow along the joint (section 5): water between heads of 1 m and 0 m on the cube's left and
# right faces.
FLOW_HEADS = {"left": 1.0, "right": 0.0}   # [m]


def joint_law():
    """Topography → (η, β, σ_s) → the asperity laws, and the exact contact of the walls (BEM)."""
    # A mated pair of self-affine walls: identical above the matedness wavelength (2.5 mm, a
    # few grains), independent below it. H = 0.8 and 1 mm rms over the specimen are typical
    # of granite fractures. Deterministic for the seed.
    n = int(round(SIDE / SPACING))
    spec = topo.SelfAffineSpec(hurst_exponent=SCAN["hurst"], rms_height=SCAN["rms_height"])
    upper, lower = topo.mated_pair(spec, (n, n), SPACING, SCAN["matedness"], seed=SCAN["seed"])
    # Contact state: mated (zero offset); the composite topography of the aperture field.
    joint = topo.composite_topography(upper, lower, offset=(0, 0))
    analysis = topo.analyse(joint.composite)
    params = topo.closure_parameters(analysis, young=YOUNG, poisson=POISSON)
    say(f"composite topography of the {n}x{n} scan at h = {SPACING * 1e3:g} mm:")
    say(f"  η = {params.summit_density * 1e-6:.3f} /mm², β = {params.summit_radius * 1e3:.3f} mm, "
        f"σ_s = {params.summit_height_std * 1e3:.4f} mm, E* = {params.composite_modulus * 1e-9:.2f} GPa")
    # GW, Tang, Tang & Jiao and the recommended law, seated at the measured first contact.
    laws = rockjoint.laws.laws_from_topography(params, summits=analysis, empirical=False)
    # The yardstick: exact elastic contact of the same walls (boundary elements, periodic: the
    # synthetic walls are one period), the reference every law is measured against.
    # With flow=True it also solves the Reynolds flow on the gap field at each load (docs/flow.md).
    bem = contact.closure_curve(joint.aperture, params.composite_modulus, STRESS_LEVELS, flow=True)
    return laws, params, bem, joint.aperture


def tabulated(law, path):
    """Tabulate once with error control; the FE model calls the table, not the law. The exact
    contact curve is a table already (through the BEM's points): it is used as it is."""
    if isinstance(law, rockjoint.TabulatedLaw):
        if COMM.rank == 0:
            law.save(path)
        say(f"table: the exact contact curve's own, {law.knot_count} knots (the BEM's loads); saved {path}")
        return law
    t0 = time.perf_counter()
    table = rockjoint.tabulate(law, max_stress=TABLE_STRESS, tolerance=TOLERANCE)
    build = time.perf_counter() - t0
    if COMM.rank == 0:
        table.save(path)
    say(f"table: {table.knot_count} knots, {table.memory_bytes / 1024:.1f} KiB, built in "
        f"{build:.2f} s; checked error σ {table.checked_error_stress:.1e}, "
        f"k {table.checked_error_stiffness:.1e} (tolerance {TOLERANCE:g}); saved {path}")
    return table


def cube(jointed, mesh_size):
    """The 150 mm cube, with one horizontal joint at mid-height or intact."""
    joints = [meshes.Joint((SIDE / 2, SIDE / 2, SIDE / 2), 0.0, 90.0, "joint")] if jointed else []
    jm = meshes.jointed_block((SIDE, SIDE, SIDE), joints, dim=3, mesh_size=mesh_size, comm=COMM)
    return distribute(jm, COMM)


def top_displacement(dmesh, law, stress):
    """Uniaxial compression with roller supports; returns the mean top settlement [m]."""
    joints = {"joint": law} if law is not None else {}
    model = JointedRockModel(dmesh, rock=(YOUNG, POISSON), joints=joints,
                             shear_stiffness_ratio=0.1 if law is not None else None,
                             plane=None, newton=NewtonOptions(verbose=False))
    model.fix("bottom", "z")
    model.fix("left", "x")
    model.fix("front", "y")
    model.add_traction("top", (0.0, 0.0, -stress))
    solution = model.solve(load_steps=1)
    return -model.boundary_mean_displacement("top")[2], model, solution


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--output", default=".", help="output folder")
    ap.add_argument("--mesh-size", type=float, default=SCENE["mesh"]["size"], help="element size [m]")
    args = ap.parse_args()
    os.makedirs(args.output, exist_ok=True)
    out = lambda name: os.path.join(args.output, name)  # noqa: E731

    # %% 1. Micro: the joint's roughness gives its closure law ------------------------------
    laws, params, bem, aperture = joint_law()
    closure_bem = bem.closure
    # The planner's pick within the scene's error budget, of least total cost: a law of the
    # family above, or the exact contact curve of the walls (BEM) as a table.
    say(f"planner: {PLAN_LAW.choice}; {PLAN_LAW.why}; cost {PLAN_LAW.cost}")
    law = topography_law(PLAN.laws["joint"], SCAN, int(round(SIDE / SPACING)), YOUNG, POISSON, TABLE_STRESS)
    table = tabulated(law, out("granite_joint.rjt"))

    # %% 2. Macro: jointed and intact cubes under the same loads ----------------------------
    jointed_mesh, intact_mesh = cube(True, args.mesh_size), cube(False, args.mesh_size)
    rows = []
    t0 = time.perf_counter()
    for i, stress in enumerate(STRESS_LEVELS):
        u_joint, jm, jsol = top_displacement(jointed_mesh, table, stress)
        u_intact, im, _ = top_displacement(intact_mesh, None, stress)
        closure_fe = u_joint - u_intact            # Bandis: jointed minus intact
        closure_law = law.closure_at_stress(stress)  # the law itself, not the table
        rows.append((stress, u_intact, u_joint, closure_fe, closure_law, closure_bem[i]))
        say(f"  [{i + 1}/{len(STRESS_LEVELS)}] σ = {stress * 1e-6:5.1f} MPa: closure FE "
            f"{closure_fe * 1e3:.5f} mm, law {closure_law * 1e3:.5f} mm "
            f"({time.perf_counter() - t0:.1f} s)")
    jm.write_xdmf(out("jointed_cube.xdmf"))
    im.write_xdmf(out("intact_cube.xdmf"))

    # %% 3. What the test shows -------------------------------------------------------------
    rows = np.array(rows)
    error = np.abs(rows[:, 3] - rows[:, 4]) / rows[:, 4]
    header = ("σ [MPa]  intact top [mm]  jointed top [mm]  closure FE [mm]  closure law [mm]  "
              "rel. difference  closure BEM [mm]")
    lines = [header] + [f"{r[0] * 1e-6:7.2f}  {r[1] * 1e3:15.6f}  {r[2] * 1e3:16.6f}  "
                        f"{r[3] * 1e3:15.6f}  {r[4] * 1e3:16.6f}  {e:15.2e}  {r[5] * 1e3:16.6f}"
                        for r, e in zip(rows, error)]
    say("\n" + "\n".join(lines))
    say(f"max relative difference FE closure vs law: {error.max():.2e} "
        f"(table tolerance {TOLERANCE:g}; solver tolerance 1e-10)")
    physics = rows[:, 4] / rows[:, 5] - 1.0
    above = rows[:, 0] >= 1e6
    say(f"law vs exact elastic contact of the same walls (BEM), 1-30 MPa: mean "
        f"{100 * np.mean(np.abs(physics[above])):.1f} %, max {100 * np.max(np.abs(physics[above])):.1f} %")
    if COMM.rank == 0:
        with open(out("lab_closure_test_table.txt"), "w") as f:
            f.write(f"# rockjoint lab closure test: {SIDE * 1e3:g} mm granite cube, E = "
                    f"{YOUNG * 1e-9:g} GPa, nu = {POISSON}; eta = {params.summit_density * 1e-6:.4f} "
                    f"1/mm2, beta = {params.summit_radius * 1e3:.4f} mm, sigma_s = "
                    f"{params.summit_height_std * 1e3:.5f} mm\n# " + "\n".join(lines) + "\n")
        plot(rows, laws, table, out("lab_closure_test.png"))
    say(f"wrote {out('lab_closure_test.png')}, {out('lab_closure_test_table.txt')}, "
        f"{out('jointed_cube.xdmf')}, {out('intact_cube.xdmf')}")

    # %% 4. Load and unload: the joint that does not spring back -----------------------------
    cycle = load_cycle(aperture, params, table, jointed_mesh, intact_mesh, out)

    # %% 5. Flow: the joint's transmissivity through the load cycle --------------------------
    flow_cycle(bem, cycle, out)


def load_cycle(aperture, params, table, jointed_mesh, intact_mesh, out):
    """The walls' elastic-plastic contact (BEM) along CYCLE beside the FE cube whose joint follows
    the hysteretic law: the demo's joint table (the planner's pick) as the virgin curve with unloading branches of
    the laboratory's middle values (Bandis et al. 1983: permanent closure r = 0.25 of the largest,
    unloading 3 times stiffer at the top; docs/hysteresis.md). `rockjoint calibrate --cycles` fits
    r and m to a measured cycle instead."""
    bem = contact.closure_curve(aperture, params.composite_modulus, CYCLE, hardness=HARDNESS)
    say(f"load cycle, walls elastic-plastic (H = {HARDNESS * 1e-9:g} GPa): largest closure "
        f"{bem.closure.max() * 1e3:.4f} mm, {100 * bem.plastic_area_ratio.max():.3f} % of the "
        f"area at H, permanent closure {bem.unloaded_closure * 1e3:.4f} mm "
        f"({100 * bem.unloaded_closure / bem.closure.max():.1f} %) when unloaded")
    if bem.plastic_area_ratio.max() == 0.0:
        say("  no asperity of this 0.5 mm scan reaches H up to 30 MPa: the exact contact unloads along "
            "its loading curve (plastic tips give permanent closures of the laboratory's size only on "
            "finer scans or softer minerals: bench/results/contact_plastic.md)")
    top = table.closure_at_stress(MAX_STRESS)
    r = 0.25
    m = max(1.0, 3.0 * (1 - r) * top * table.normal_stiffness(top) / MAX_STRESS)   # (H4)
    law = rockjoint.NormalHysteresis(table, r, m)
    say(f"hysteretic law: the joint's table, r = {r}, m = {m:.2f} (unloading 3 x stiffer at 30 MPa)")
    # FE: one model loaded along the path (its joint keeps its largest closure point by point);
    # the intact cube is linear: its settlement scales with σ.
    jointed = JointedRockModel(jointed_mesh, rock=(YOUNG, POISSON), joints={"joint": law},
                               shear_stiffness_ratio=0.1, plane=None, newton=NewtonOptions(verbose=False))
    for face, c in (("bottom", "z"), ("left", "x"), ("front", "y")):
        jointed.fix(face, c)
    jointed.add_traction("top", (0.0, 0.0, -MAX_STRESS))
    u_intact_max = top_displacement(intact_mesh, None, MAX_STRESS)[0]
    rows, solutions = [], []
    expected = law.closure_path(CYCLE)
    for stress, target, measured in zip(CYCLE, expected, bem.closure):
        solutions.append(jointed.advance(stress / MAX_STRESS, load_steps=1))
        u = -jointed.boundary_mean_displacement("top")[2]
        rows.append((stress, u - u_intact_max * stress / MAX_STRESS, target, measured))
    rows = np.array(rows)
    error = np.abs(rows[:, 1] - rows[:, 2]) / rows[:, 2]
    lines = ["σ [MPa]  closure FE [mm]  closure law [mm]  closure BEM elastic-plastic [mm]"] + [
        f"{r[0] * 1e-6:7.2f}  {r[1] * 1e3:15.6f}  {r[2] * 1e3:16.6f}  {r[3] * 1e3:16.6f}" for r in rows]
    say("\n" + "\n".join(lines))
    say(f"cycle: max relative difference FE vs hysteretic law {error.max():.2e}")
    if COMM.rank == 0:
        with open(out("lab_closure_cycle.txt"), "w") as f:
            f.write(f"# rockjoint lab closure test, load cycle: walls elastic-plastic, H = {HARDNESS * 1e-9:g} GPa; "
                    f"hysteretic law r = {law.permanent_fraction:.4f}, m = {law.unloading_exponent:.3f}\n# "
                    + "\n".join(lines) + "\n")
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6, 4.5))
        ax.plot(rows[:, 3] * 1e3, rows[:, 0] * 1e-6, "o-", mfc="none", color="k",
                label=f"exact contact, elastic-plastic walls (H = {HARDNESS * 1e-9:g} GPa)")
        ax.plot(rows[:, 2] * 1e3, rows[:, 0] * 1e-6, "-", color="C0", lw=2,
                label="hysteretic law (the joint's table + laboratory branches)")
        ax.plot(rows[:, 1] * 1e3, rows[:, 0] * 1e-6, "x", color="C3", ms=8, label="FE cube: jointed − intact")
        ax.set_xlabel("joint closure Δ [mm]")
        ax.set_ylabel("normal stress σ [MPa]")
        ax.set_title("load, unload, reload: the joint that does not spring back")
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(out("lab_closure_cycle.png"), dpi=120)
        plt.close(fig)
    return law, jointed, solutions


def flow_cycle(bem, cycle, out):
    """The transmissivity of the joint along the load cycle, and the flow through the FE cube's
    joint between heads on two opposite faces. T(Δ) comes from the walls themselves: the Reynolds
    (local cubic law) flow on their gap field at each load of the exact elastic contact (BEM),
    tabulated against closure (docs/flow.md); along the cycle T follows the closure of the
    hysteretic law. The FE cube: each joint point's T from its closure, flow along the joint
    (rockjoint.fem.network_flow); closed form for the uniform joint spanning the cube:
    Q = (ρ g / μ) T Δh (the joint is as wide as it is long)."""
    law, jointed, solutions = cycle
    walls = flow.transmissivity_law("walls", curve=bem)
    fluid = Fluid()
    rows = []
    for stress, solution, t in zip(CYCLE, solutions, flow.transmissivity_along(walls, law, CYCLE)):
        q = network_flow(jointed, {"joint": walls.transmissivity}, FLOW_HEADS, fluid, stage=solution).flow_rates["left"]
        rows.append((stress, t, q, fluid.conductivity_factor * t * (FLOW_HEADS["left"] - FLOW_HEADS["right"])))
    rows = np.array(rows)
    closure = law.closure_path(CYCLE)
    e_h, e = flow.hydraulic_aperture(rows[:, 1]), walls.mechanical_aperture(closure)
    error = np.abs(rows[:, 2] - rows[:, 3]) / rows[:, 3]
    lines = ["σ [MPa]  closure [mm]  T [m³]      e_h [µm]  e [µm]  e_h/e   Q FE [mL/min]  Q closed form [mL/min]"] + [
        f"{r[0] * 1e-6:7.2f}  {d * 1e3:12.5f}  {r[1]:10.3e}  {h * 1e6:8.2f}  {m * 1e6:6.1f}  {h / m:5.3f}  "
        f"{r[2] * 6e7:13.9g}  {r[3] * 6e7:22.9g}" for r, d, h, m in zip(rows, closure, e_h, e)]
    say("\nflow along the joint, heads 1 m and 0 m on two opposite faces of the cube (water, 20 °C):\n"
        + "\n".join(lines))
    first = np.argmax(CYCLE >= 30e6)
    say(f"transmissivity 0.05 -> 30 MPa: x{rows[first, 1] / rows[0, 1]:.3g}; after unloading to 0.5 MPa it is "
        f"x{rows[np.argmin(CYCLE[first:]) + first, 1] / rows[0, 1]:.3g} of the first-loading value at 0.05 MPa; "
        f"e_h/e {np.min(e_h / e):.2f}-{np.max(e_h / e):.2f}")
    say(f"flow: max relative difference FE vs closed form {error.max():.2e}")
    if COMM.rank == 0:
        with open(out("lab_flow_cycle.txt"), "w") as f:
            f.write("# rockjoint lab closure test, flow along the joint through the load cycle: T(Δ) from the "
                    "walls (BEM + Reynolds), the closure of the hysteretic law; heads 1 m / 0 m on the cube's "
                    "left / right faces\n# " + "\n".join(lines) + "\n")
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6, 4.5))
        top = int(first)
        low = int(np.argmin(CYCLE[top:]) + top)
        for part, style, label in ((slice(0, top + 1), "o-", "first loading"),
                                   (slice(top, low + 1), "s--", "unloading"),
                                   (slice(low, None), "^:", "reloading")):
            ax.semilogy(rows[part, 0] * 1e-6, rows[part, 1], style, mfc="none", label=label)
        ax.set_xlabel("normal stress σ [MPa]")
        ax.set_ylabel("transmissivity T = e_h³/12 [m³]")
        ax.set_title("the joint's transmissivity through the load cycle")
        ax.legend()
        fig.tight_layout()
        fig.savefig(out("lab_flow_cycle.png"), dpi=120)
        plt.close(fig)
    say(f"wrote {out('lab_flow_cycle.png')}, {out('lab_flow_cycle.txt')}")


def plot(rows, laws, table_law, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4.5))
    s = np.r_[0.0, rows[:, 0] * 1e-6]  # both specimens start unloaded at the origin
    a1.plot(np.r_[0.0, rows[:, 1]] * 1e3, s, "o-", color="0.4", label="intact cube (FE)")
    a1.plot(np.r_[0.0, rows[:, 2]] * 1e3, s, "s-", color="C3", label="jointed cube (FE)")
    a1.set_xlabel("top settlement [mm]")
    a1.set_ylabel("axial stress σ [MPa]")
    a1.set_title("150 mm granite cube, uniaxial compression")
    a1.legend()
    stress = np.linspace(0.0, MAX_STRESS, 200)[1:]
    if PLAN.laws["joint"] not in laws:   # the FE model's table is the exact contact curve
        a2.plot(np.r_[0, table_law.closure_at_stress(stress)] * 1e3, np.r_[0, stress] * 1e-6, "-",
                lw=2.5, label="exact contact (BEM) as a table: the FE model's law")
    for key, named in laws.items():
        # At A/A0 ~ 1 % Tang & Jiao lies on Tang (theory §5): thin lines, the FE law thick.
        in_fe = key == PLAN.laws["joint"]
        a2.plot(np.r_[0, named.law.closure_at_stress(stress)] * 1e3, np.r_[0, stress] * 1e-6,
                "-", lw=2.5 if in_fe else 1.0, alpha=1.0 if in_fe else 0.7,
                label=named.label + (": table in the FE model" if in_fe else ""))
    a2.plot(np.r_[0.0, rows[:, 5]] * 1e3, s, "o", mfc="none", color="k",
            label="exact elastic contact (BEM)")
    a2.plot(rows[:, 3] * 1e3, s[1:], "kx", ms=8, label="FE: jointed − intact")
    a2.set_xlabel("joint closure Δ [mm]")
    a2.set_ylabel("normal stress σ [MPa]")
    a2.set_title("joint closure: FE, laws and exact contact")
    a2.legend(loc="upper left", fontsize=7.5)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


if __name__ == "__main__":
    main()
