#!/usr/bin/env python3
"""A blocky rock mass under biaxial load: bedding planes and a cross-joint set, beside the intact rock.

Read it top to bottom; run it as it is (serial or `mpirun -n 2`):

    PYTHONPATH=python:build/python /usr/bin/python3 demos/demo_blocky_rock_mass.py [--output DIR]

A 12 m x 8 m section (2D plane strain) of granite is cut by three horizontal bedding joints
(2 m apart) and three cross joints dipping 70° (3 m apart), which together make a blocky mass.
The bedding planes carry the Tang & Jiao law of a measured-like rough joint (theory §7
parameters), the cross joints a Barton-Bandis law from their JRC, JCS and aperture; both are
tabulated once and the tables go into the FE model. The mass is loaded by a vertical stress on
top and a smaller horizontal stress on one side (rollers on the other two sides), in load steps.
The intact section under the same loads is solved beside it, so the joints' share of the
deformation and the equivalent moduli of the mass come out directly.

Outputs (in DIR, default the working directory): blocky_rock_mass.png (displacement of both
sections, joint normal stress), blocky_rock_mass.txt (the numbers), blocky_jointed.xdmf (+
blocky_jointed_joints.xdmf, the joint state) and blocky_intact.xdmf for ParaView.
Units in print: mm, MPa, GPa.
"""
import argparse
import logging
import os

import numpy as np
from mpi4py import MPI

import rockjoint
from rockjoint import meshes
from rockjoint.fem import JointedRockModel, NewtonOptions, distribute

COMM = MPI.COMM_WORLD
# DOLFINx compiles forms on first use through setuptools, which sets the root logger to INFO
# and would print every compiler command: a handler of our own that passes warnings only.
logging.basicConfig(level=logging.WARNING)
logging.getLogger().handlers[0].setLevel(logging.WARNING)


def say(*args):
    if COMM.rank == 0:
        print(*args, flush=True)


# %% The rock mass -----------------------------------------------------------------------------
WIDTH, HEIGHT = 12.0, 8.0            # [m]
YOUNG, POISSON = 50e9, 0.25          # granite [Pa], [-]
VERTICAL_STRESS = 10e6               # on top [Pa]
HORIZONTAL_STRESS = 5e6              # on the right face [Pa]
SHEAR_RATIO = 0.1                    # joint shear stiffness k_s = 0.1 k_n(Δ)

# Bedding: horizontal, 2 m apart. Cross joints: dip 70° toward +x, 3 m apart along their normal;
# both sets persist across the section (crossings make the blocks).
BEDDING = meshes.joint_set(2.0, 0.0, 90.0, origin=(WIDTH / 2, 2.0), count=3, name="bedding")
CROSS = meshes.joint_set(3.0, 70.0, 90.0, origin=(3.0, HEIGHT / 2), count=3, name="cross")


def joint_laws():
    """Bedding: Tang & Jiao over Tang's substrate law; cross joints: Barton-Bandis from JRC/JCS."""
    e_star = rockjoint.composite_modulus(YOUNG, POISSON)
    bedding = rockjoint.TangJiao(rockjoint.TangSubstrate(e_star, 0.3e6, 2.5e-3, 0.05e-3))
    cross = rockjoint.BartonBandis.from_joint_properties(jrc=10.0, jcs=100e6, initial_aperture=0.5e-3)
    say(f"cross joints (Bandis 1983): K_ni = {cross.initial_normal_stiffness * 1e-9:.2f} MPa/mm, "
        f"V_m = {cross.maximum_closure * 1e3:.3f} mm")
    # Tables cover the stresses the scene can reach (twice the largest applied stress).
    return {"bedding": rockjoint.tabulate(bedding, max_stress=2 * VERTICAL_STRESS),
            "cross": rockjoint.tabulate(cross, max_stress=2 * VERTICAL_STRESS)}


def model_of(dmesh, tables):
    joints = {}
    for name in dmesh.names["joints"].values():
        joints[name] = tables[name.split("_")[0]]
    model = JointedRockModel(dmesh, rock=(YOUNG, POISSON), joints=joints,
                             shear_stiffness_ratio=SHEAR_RATIO if joints else None,
                             plane="strain", newton=NewtonOptions(verbose=False))
    model.fix("bottom", "y")
    model.fix("left", "x")
    model.add_traction("top", (0.0, -VERTICAL_STRESS))
    model.add_traction("right", (-HORIZONTAL_STRESS, 0.0))
    return model


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--output", default=".", help="output folder")
    ap.add_argument("--mesh-size", type=float, default=0.4, help="element size away from joints [m]")
    args = ap.parse_args()
    os.makedirs(args.output, exist_ok=True)
    out = lambda name: os.path.join(args.output, name)  # noqa: E731

    # %% 1. Laws, tabulated once ----------------------------------------------------------------
    tables = joint_laws()
    for name, t in tables.items():
        say(f"{name} table: {t.knot_count} knots, checked error σ {t.checked_error_stress:.1e}")

    # %% 2. Meshes: jointed (refined toward the joints) and intact --------------------------------
    h = args.mesh_size
    jointed = distribute(meshes.jointed_block((WIDTH, HEIGHT), BEDDING + CROSS, dim=2, mesh_size=h,
                                              joint_mesh_size=h / 2, comm=COMM), COMM)
    intact = distribute(meshes.jointed_block((WIDTH, HEIGHT), [], dim=2, mesh_size=h, comm=COMM), COMM)
    say(f"jointed section: {len(jointed.names['blocks'])} blocks, "
        f"{COMM.allreduce(len(jointed.pairs))} joint facet pairs")

    # %% 3. Solve both under the same loads -------------------------------------------------------
    results = {}
    for label, dmesh in (("intact", intact), ("jointed", jointed)):
        model = model_of(dmesh, tables)
        solution = model.solve(load_steps=4)
        steps = [r for r in solution.reports if r.converged]
        say(f"{label}: {len(steps)} load steps, {solution.newton_iterations} Newton iterations "
            f"({len(solution.reports) - len(steps)} step(s) cut)")
        top = model.boundary_mean_displacement("top")[1]
        right = model.boundary_mean_displacement("right")[0]
        results[label] = (model, solution, -top, -right)
        model.write_xdmf(out(f"blocky_{label}.xdmf"))

    # %% 4. What the joints do --------------------------------------------------------------------
    _, jsol, settle_j, squeeze_j = results["jointed"]
    _, _, settle_i, squeeze_i = results["intact"]
    state = jsol.gather_joints()
    names = {int(t): n for t, n in jointed.names["joints"].items()}
    lines = [f"{'':28}{'intact':>12}{'jointed':>12}",
             f"{'top settlement [mm]':28}{settle_i * 1e3:12.6f}{settle_j * 1e3:12.6f}",
             f"{'right face inward [mm]':28}{squeeze_i * 1e3:12.6f}{squeeze_j * 1e3:12.6f}",
             f"joints' share of the settlement: {100 * (settle_j - settle_i) / settle_j:.1f} %",
             f"{'joint set':12}{'max closure [mm]':>18}{'σ_n range [MPa]':>22}{'max |τ| [MPa]':>16}"]
    for prefix in ("bedding", "cross"):
        sel = np.array([names[int(t)].startswith(prefix) for t in state["tag"]])
        if not sel.any():
            continue
        sn = state["normal_stress"][sel] * 1e-6
        tau = np.abs(np.asarray(state["shear_traction"])[sel]).max() * 1e-6
        lines.append(f"{prefix:12}{state['closure'][sel].max() * 1e3:18.4f}"
                     f"{sn.min():11.2f} .. {sn.max():6.2f}{tau:16.3f}")
    say("\n" + "\n".join(lines))
    if COMM.rank == 0:
        with open(out("blocky_rock_mass.txt"), "w") as f:
            f.write("# rockjoint blocky rock mass: 12 m x 8 m granite section, plane strain, "
                    f"σ_v = {VERTICAL_STRESS * 1e-6:g} MPa, σ_h = {HORIZONTAL_STRESS * 1e-6:g} MPa\n")
            f.write("\n".join(lines) + "\n")
    plot(results, state, out("blocky_rock_mass.png"))
    say(f"wrote {out('blocky_rock_mass.png')}, {out('blocky_rock_mass.txt')}, "
        f"{out('blocky_jointed.xdmf')}, {out('blocky_intact.xdmf')}")


def owned_nodal_displacement(model):
    """(x, y, |u|) at the owned dofs of this rank, gathered on every rank [m]."""
    u = model.solution.displacement
    V = u.function_space
    n = V.dofmap.index_map.size_local
    x = V.tabulate_dof_coordinates()[:n, :2]
    mag = np.linalg.norm(u.x.array.reshape(-1, 2)[:n], axis=1)
    return [np.concatenate(COMM.allgather(a)) for a in (x[:, 0], x[:, 1], mag)]


def plot(results, state, path):
    fields = {label: owned_nodal_displacement(r[0]) for label, r in results.items()}
    if COMM.rank != 0:
        return
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    vmax = max(f[2].max() for f in fields.values()) * 1e3
    fig, axes = plt.subplots(1, 3, figsize=(16, 4.2))
    for ax, label in zip(axes[:2], ("intact", "jointed")):
        x, y, mag = fields[label]
        sc = ax.scatter(x, y, c=mag * 1e3, s=3, vmin=0.0, vmax=vmax, cmap="viridis")
        ax.set_title(f"{label} section: |u| [mm]")
        fig.colorbar(sc, ax=ax, label="|u| [mm]")
    xy = np.asarray(state["coordinates"]).reshape(-1, 2)
    sc = axes[2].scatter(xy[:, 0], xy[:, 1], c=np.asarray(state["normal_stress"]) * 1e-6, s=6,
                         cmap="inferno")
    fig.colorbar(sc, ax=axes[2], label="joint normal stress σ_n [MPa]")
    axes[2].set_title("joints: normal stress")
    for ax in axes:
        ax.set_aspect("equal")
        ax.set_xlim(0, WIDTH)
        ax.set_ylim(0, HEIGHT)
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
    fig.suptitle(f"blocky granite mass, σ_v = {VERTICAL_STRESS * 1e-6:g} MPa, "
                 f"σ_h = {HORIZONTAL_STRESS * 1e-6:g} MPa (plane strain)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


if __name__ == "__main__":
    main()
