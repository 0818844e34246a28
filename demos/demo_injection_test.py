#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""A laboratory injection test: water injected at a constant rate along a jointed core through a normal-load cycle.

Read it top to bottom; run it as it is (serial or ``mpirun -n 2``)::

    PYTHONPATH=python:build/python /usr/bin/python3 demos/demo_injection_test.py [--output DIR] [--quick]

The set-up (demos/scenes/injection_test.yaml): a granite core 50 mm in diameter and 100 mm long,
split along its axis by one mated tensile joint, in a cell that presses the two halves together
with a normal stress σ (a confining pressure through a rubber sleeve: the same σ at every point
of the joint). Water is injected at a constant rate Q into the inlet plenum at one end of the
joint and drains at atmospheric pressure at the other end; the test records the injection
pressure p_in that pushes Q through the joint, at each level of a load cycle (loading to 20 MPa,
unloading to 1 MPa), once the flow is steady (a steady-state permeability test). The section
along the axis is modelled in 2D (plane strain, flows per metre of joint width).

The joint comes from its walls: a synthetic mated self-affine pair (as the main demo's, rms
0.1 mm: a tight joint) whose exact elastic contact (boundary elements) gives the virgin closure
curve, and whose gap field at each load gives the transmissivity T(Δ) by the Reynolds equation
(the ``walls`` law, docs/flow.md). The joint does not spring back on unloading: the hysteretic
law over that virgin curve with the laboratory's middle values (permanent closure 25 % of the
largest, unloading 3 times stiffer at the top; docs/hysteresis.md).

Two answers at each level:

* one way (``network_flow``): the joint closed by σ alone, the water not acting on it; T uniform
  along the joint and p_in = p_out + μ Q L / T(Δ(σ));
* two ways (``coupled_steady``): the water's pressure p(x) lowers the joint's effective normal
  stress σ' = σ - p, opens it and raises T, so the same Q needs less pressure. Continuity along
  the joint gives T(Δ(σ - p)) dp/dx = -μ Q, i.e. ∫_{p_out}^{p_in} T(Δ(σ - p)) dp = μ Q L.

The halves are soft in the FE model (E = 1 MPa) so that each joint point carries the cell's σ
undistributed, as the 1D balance above assumes (granite halves would bend under the uneven water
pressure and redistribute σ_n); the walls' contact uses the granite's modulus. Each load level is
applied with the water held in the joint (its closure unchanged: the pressure rises with σ), then
the water flows to its steady state: the path a joint takes in a test whose load steps are slow
against the flow, and one on which no joint point closes beyond where the steady state puts it.

Outputs (in DIR): injection_test.png (injection pressure against normal stress, both answers,
through the cycle), injection_test.txt (the numbers, with units). Units in print: MPa, mm, µm.
"""
import argparse
import os

import numpy as np
from mpi4py import MPI

import rockjoint
from rockjoint import contact, flow, meshes
from rockjoint import topography as topo
from rockjoint.console import quiet_compiler_logging, rank_logger
from rockjoint.fem import Fluid, JointedRockModel, NewtonOptions, distribute, network_flow
from rockjoint.fem.water.coupled import coupled_steady
from rockjoint.fem.water.joint_pressure import set_joint_pressure
from rockjoint.scenes import load_scene
from rockjoint.scenes.joint_laws import scan

COMM = MPI.COMM_WORLD
quiet_compiler_logging()  # DOLFINx's form compiler would log every command
log = rank_logger("demo_injection_test", COMM)

# %% The scene: demos/scenes/injection_test.yaml (the core, its joint's walls, the cell's load) ----
SCENE = load_scene(os.path.join(os.path.dirname(os.path.abspath(__file__)), "scenes", "injection_test.yaml"))
LENGTH, DIAMETER = SCENE["geometry"]["size"]              # the section: joint length L, core diameter [m]
WALLS = SCENE["joints"]["joint"]["law"]["topography"]      # the synthetic mated walls
YOUNG, POISSON = SCENE["rock"]["young"], SCENE["rock"]["poisson"]   # granite: the walls' contact
PEAK = -SCENE["stages"][-1]["loads"]["top"]["traction"][-1]         # the cycle's top σ [Pa]
JOINT = "joint_1"               # the joint's name in the column mesh
SOFT = (1e6, 0.0)               # the FE halves: E [Pa], ν (module docstring)
SEATING = 0.2e6                 # the core seated dry before the water [Pa]
# The cycle [Pa]: loading to the peak, unloading to 1 MPa (σ - p stays > 0 at the inlet: no jacking)
CYCLE = np.array([0.5, 1, 2, 4, 7, 10, 15, 20, 15, 10, 7, 4, 2, 1]) * 1e6
QUICK_CYCLE = np.array([0.5, 2, 7, 20, 7, 2, 1]) * 1e6
# The laboratory's middle values of a load cycle (Bandis et al. 1983; docs/hysteresis.md)
PERMANENT_FRACTION, UNLOADING_RATIO = 0.25, 3.0
# The injection: 1.5 mL/min through the joint, as wide as the core [m²/s per metre of width];
# at that rate the flow is laminar (Reynolds number ρ Q / μ below 1) and p_in stays below σ.
WIDTH = DIAMETER
RATE = 1.5e-6 / 60.0 / WIDTH
OUTLET_PRESSURE = 0.0           # drained to the atmosphere [Pa]
FLUID = Fluid()                 # water at 20 °C
# the walls' contact and flow solved at these loads, 25 % beyond the peak: the joint's table covers
# every effective stress the cycle reaches (round-off puts points a hair above σ)
CONTACT_STRESSES = np.geomspace(0.05e6, 1.25 * PEAK, 18)


def joint_laws(points: int):
    """The joint from its walls (points² scan): (hysteretic closure law, walls' transmissivity law,
    its virgin law). One contact solution with flow at CONTACT_STRESSES gives both curves."""
    upper, lower = scan(WALLS, points)
    aperture = topo.composite_topography(upper, lower, offset=(0, 0)).aperture
    curve = contact.closure_curve(aperture, rockjoint.composite_modulus(YOUNG, POISSON), CONTACT_STRESSES, flow=True)
    # the exact contact's table, seated as the planner's rung is (contact.EXACT_CONTACT_SEATING)
    virgin = contact.exact_elastic_law(
        curve, initial_stiffness=contact.EXACT_CONTACT_SEATING * curve.stress[0] / curve.closure[0])
    top = virgin.closure_at_stress(PEAK)
    # (H4): k_u / k_v = m σ_m / ((1 - r) Δ_m k_v(Δ_m)) = UNLOADING_RATIO at the peak
    m = UNLOADING_RATIO * (1 - PERMANENT_FRACTION) * top * virgin.normal_stiffness(top) / PEAK
    law = rockjoint.NormalHysteresis(virgin, PERMANENT_FRACTION, max(m, 1.0))
    walls = flow.transmissivity_law("walls", curve=curve)
    low = virgin.closure_at_stress(CYCLE[0])
    log.info("walls %dx%d at %.2g mm: closure %.4f mm, e_h %.1f µm at %.3g MPa; %.4f mm, %.1f µm at %.3g MPa; "
             "hysteresis r = %.2f, m = %.2f", points, points, WALLS["spacing"] * 1e3, low * 1e3,
             walls.hydraulic_aperture(low) * 1e6, CYCLE[0] * 1e-6, top * 1e3, walls.hydraulic_aperture(top) * 1e6,
             PEAK * 1e-6, PERMANENT_FRACTION, m)
    return law, walls, virgin


def core(dmesh, law):
    """The core's section with its joint along the axis, rollers under it and at the inlet end,
    the cell's stress on top (set per level through the returned load handle)."""
    model = JointedRockModel(dmesh, rock=SOFT, joints={JOINT: law}, shear_stiffness=1e6, plane="strain",
                             newton=NewtonOptions(verbose=False))
    for face, component in SCENE["supports"].items():
        model.fix(face, component)
    return model, model.add_traction("top", (0.0, -SEATING))


def inlet_pressure(network) -> float:
    """p at the injection port [Pa]: ρ g (h_port - z), the joint at mid-height."""
    return FLUID.density * FLUID.gravity * (network.port_heads["left"] - 0.5 * DIAMETER)


def run_cycle(dmesh, law, walls, cycle):
    """Both answers at every level of `cycle`: rows (σ, leg, p_in one way, p_in two ways, T one way,
    T two ways at the inlet, iterations, largest |σ_n/σ - 1|, outflow / Q + 1)."""
    t_law = {JOINT: walls.transmissivity}
    conditions = dict(pressures={"right": OUTLET_PRESSURE}, rates={"left": RATE})
    dry, dry_load = core(dmesh, law)
    wet, wet_load = core(dmesh, law)
    dry.solve(name="seated")
    wet.solve(name="seated, dry")
    rows, previous = [], SEATING
    peak = int(np.argmax(cycle))
    for i, sigma in enumerate(cycle):
        dry_load.value = wet_load.value = (0.0, -sigma)
        one = network_flow(dry, t_law, fluid=FLUID, stage=dry.solve(name=f"{sigma * 1e-6:g} MPa"), **conditions)
        # the level applied with the water held (σ' unchanged), then the steady flow both ways
        set_joint_pressure(wet, np.asarray(wet.interface.pore_pressure()) + (sigma - previous))
        wet.solve(name=f"{sigma * 1e-6:g} MPa, water held")
        two = coupled_steady(wet, t_law, fluid=FLUID, name=f"water at {sigma * 1e-6:g} MPa", **conditions)
        state = wet.solution.gather_joints()
        x = np.asarray(state["coordinates"]).reshape(-1, 2)[:, 0]
        total = np.asarray(state["normal_stress"]) + two.pressure          # σ_n = σ' + α p (α = 1)
        inlet = two.network.point_transmissivity[np.argmin(x)]
        rows.append((sigma, 1 if i <= peak else -1, inlet_pressure(one), inlet_pressure(two.network),
                     one.point_transmissivity.mean(), inlet, two.iterations, np.max(np.abs(total / sigma - 1)),
                     two.network.flow_rates["right"] / RATE + 1))
        log.info("σ = %5.2f MPa (%s): p_in one way %.4f MPa, two ways %.4f MPa (%d iterations)", sigma * 1e-6,
                 "loading" if i <= peak else "unloading", rows[-1][2] * 1e-6, rows[-1][3] * 1e-6, two.iterations)
        previous = sigma
    return np.array(rows)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--output", default=".", help="output folder")
    ap.add_argument("--quick", action="store_true",
                    help="a coarse version (the scene's reduced mesh, 5 mm joint elements, 7 load levels)")
    args = ap.parse_args()
    os.makedirs(args.output, exist_ok=True)
    out = lambda name: os.path.join(args.output, name)  # noqa: E731
    size = SCENE["reduced"]["mesh_size"] if args.quick else SCENE["mesh"]["size"]
    joint_size = 2 * SCENE["mesh"]["joint_size"] if args.quick else SCENE["mesh"]["joint_size"]
    cycle = QUICK_CYCLE if args.quick else CYCLE

    # %% 1. The joint from its walls: closure (exact contact + hysteresis) and transmissivity ------
    law, walls, _ = joint_laws(WALLS["points"])

    # %% 2. The core's section, both answers through the load cycle -------------------------------
    jm = meshes.column(LENGTH, DIAMETER, [0.5 * DIAMETER], dim=2, mesh_size=size,
                       joint_mesh_size=joint_size, comm=COMM)
    rows = run_cycle(distribute(jm, COMM), law, walls, cycle)

    # %% 3. The table and the picture ---------------------------------------------------------
    header = ("σ [MPa]  leg (1 loading, -1 unloading)  p_in one way [MPa]  p_in two ways [MPa]  "
              "T one way [m³]  T two ways at inlet [m³]  iterations  max |σ_n/σ - 1|  outflow/Q + 1")
    lines = [header] + [f"{r[0] * 1e-6:7.3f}  {int(r[1]):2d}  {r[2] * 1e-6:.12f}  {r[3] * 1e-6:.12f}  {r[4]:.6e}  "
                        f"{r[5]:.6e}  {int(r[6]):2d}  {r[7]:.2e}  {r[8]:.2e}" for r in rows]
    log.info("\n%s", "\n".join(lines))
    lower = rows[:, 3] / rows[:, 2]
    log.info("two ways / one way: %.3f at %.3g MPa loading, %.3f at the peak, %.3f at %.3g MPa unloaded",
             lower[0], rows[0, 0] * 1e-6, lower[np.argmax(rows[:, 0])], lower[-1], rows[-1, 0] * 1e-6)
    if COMM.rank == 0:
        with open(out("injection_test.txt"), "w") as f:
            f.write(f"# rockjoint injection test: joint {LENGTH * 1e3:g} mm long, Q = {RATE:.6e} m²/s per metre "
                    f"({RATE * WIDTH * 6e7:g} mL/min over {WIDTH * 1e3:g} mm), p_out = {OUTLET_PRESSURE:g} Pa, "
                    f"μ = {FLUID.viscosity:g} Pa s; hysteresis r = {law.permanent_fraction:.4f}, "
                    f"m = {law.unloading_exponent:.6f}\n# " + "\n".join(lines) + "\n")
        plot(rows, out("injection_test.png"))
    log.info("wrote %s, %s", out("injection_test.png"), out("injection_test.txt"))


def plot(rows, path):
    import matplotlib  # only for the picture (slow import)
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (ax, ratio) = plt.subplots(1, 2, figsize=(11.5, 4.6))
    peak = int(np.argmax(rows[:, 0]))
    s = rows[:, 0] * 1e-6
    for column, colour, label in ((2, "C0", "one way (water not acting on the joint)"),
                                  (3, "C3", "two ways (the water opens the joint)")):
        ax.plot(s[:peak + 1], rows[:peak + 1, column] * 1e-6, "o-", color=colour, mfc="none", label=f"{label}: loading")
        ax.plot(s[peak:], rows[peak:, column] * 1e-6, "s--", color=colour, mfc="none", label="unloading")
    top = np.array([0.0, s.max()])
    ax.plot(top, top, ":", color="0.5", label="p_in = σ (the joint would be jacked open)")
    ax.set_ylim(0.0, 1.15 * rows[:, 2:4].max() * 1e-6)
    ax.set_xlabel("normal stress σ [MPa]")
    ax.set_ylabel("injection pressure p_in [MPa]")
    ax.set_title(f"constant-rate injection ({RATE * WIDTH * 6e7:g} mL/min) along a jointed core")
    ax.legend(fontsize=7.5)
    ratio.plot(s[:peak + 1], rows[:peak + 1, 3] / rows[:peak + 1, 2], "o-", color="k", mfc="none", label="loading")
    ratio.plot(s[peak:], rows[peak:, 3] / rows[peak:, 2], "s--", color="k", mfc="none", label="unloading")
    ratio.set_xlabel("normal stress σ [MPa]")
    ratio.set_ylabel("p_in two ways / p_in one way [-]")
    ratio.set_title("what the water's push on the walls saves")
    ratio.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


if __name__ == "__main__":
    main()
