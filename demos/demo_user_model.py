#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Joints in your own DOLFINx model: a rock slope with a daylighting sliding plane.

Read it top to bottom; run it as it is (serial or `mpirun -n 2`):

    bash scripts/run.sh python3 demos/demo_user_model.py [--output DIR]

Everything here is the user's own FEniCSx model except the joints: the geometry is built in gmsh
(a 60 m wide section through a 20 m high slope, cut by a horizontal bedding joint at 5 m and an
inclined sliding plane that daylights on the slope face), the rock stiffness varies with depth
(a UFL expression), the loads are gravity and a surcharge on the crest, and the problem is solved
by PETSc SNES as DOLFINx 0.11 solves nonlinear problems (NonlinearProblem with
petsc_options_prefix and petsc_options). The mesh is read by DOLFINx's own
dolfinx.io.gmsh.model_to_mesh; rockjoint only splits the joint nodes (split_joints) and adds the
joints (JointCoupling, JointedNonlinearProblem) with their laws taken from saved .rjt tables.
Written for DOLFINx 0.11; on 0.9 the one difference, the gmsh reader's module, is taken from
rockjoint.fem.compat (docs/user-model.md).

As a check, the same model with a piecewise-constant E (one value per block) is solved both ways,
by the user's forms + JointCoupling and by rockjoint's JointedRockModel, and the difference is
printed: it must be at solver tolerance.

Outputs (in DIR, default the working directory): user_model.txt (the numbers), user_model.png
(|u| on the mesh with the deformed outline), user_model.xdmf (displacement and E, ParaView),
user_model_joints.xdmf (joint state), sliding_plane.rjt and bedding.rjt (the tables).
Units in print: mm, MPa, GPa.
"""
import argparse
import os

import gmsh
import numpy as np
import ufl
from dolfinx import fem
from dolfinx.io import XDMFFile
from mpi4py import MPI
from petsc4py import PETSc

import rockjoint
from rockjoint.console import quiet_compiler_logging, say
from rockjoint.fem import (JointCoupling, JointedNonlinearProblem, JointedRockModel, NewtonOptions,
                           split_joints)
from rockjoint.fem.compat import io_gmsh as gmshio  # = dolfinx.io.gmsh on DOLFINx 0.10+
from rockjoint.fem.output.fields import gather_triangles, write_joint_points

COMM = MPI.COMM_WORLD
quiet_compiler_logging()  # DOLFINx's form compiler would log every command



# %% The slope ---------------------------------------------------------------------------------
# Section outline (x right, y up) [m]: toe platform at y = 10, crest at y = 30, 45° slope face.
OUTLINE = [(0.0, 0.0), (60.0, 0.0), (60.0, 30.0), (35.0, 30.0), (15.0, 10.0), (0.0, 10.0)]
BEDDING_Y = 5.0                                   # horizontal bedding joint [m]
SLIDING_PLANE = [(25.0, 20.0), (52.5, 30.0)]      # from the slope face to the crest (dips 20°)
CREST = (35.0, 60.0)                              # x range of the crest [m]
DENSITY, GRAVITY = 2600.0, 9.81                   # [kg/m³], [m/s²]
SURCHARGE = 1.0e6                                 # on the crest [Pa]
POISSON = 0.25
E_BLOCK = {"foundation": 40e9, "mass": 20e9, "wedge": 20e9}   # [Pa]
SHEAR_STIFFNESS = 1e9                             # joint k_s [Pa/m]
SNES_OPTIONS = {"snes_type": "newtonls", "snes_linesearch_type": "basic", "snes_rtol": 1e-10,
                "snes_atol": 1e-12, "snes_stol": 0.0, "snes_max_it": 30,
                "ksp_type": "preonly", "pc_type": "lu", "pc_factor_mat_solver_type": "mumps"}


def build_slope(mesh_size: float) -> dict:
    """The user's gmsh model (rank 0): OCC surface, joints fragmented in, physical groups named.
    Returns {group name: physical tag}."""
    groups = {}
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("slope")
    occ = gmsh.model.occ
    corners = [occ.addPoint(x, y, 0.0) for x, y in OUTLINE]
    lines = [occ.addLine(corners[i], corners[(i + 1) % len(corners)]) for i in range(len(corners))]
    section = occ.addPlaneSurface([occ.addCurveLoop(lines)])
    bedding = occ.addLine(occ.addPoint(0.0, BEDDING_Y, 0.0), occ.addPoint(60.0, BEDDING_Y, 0.0))
    sliding = occ.addLine(*[occ.addPoint(x, y, 0.0) for x, y in SLIDING_PLANE])
    _, pieces = occ.fragment([(2, section)], [(1, bedding), (1, sliding)])
    occ.synchronize()

    # Blocks by where their centre of mass lies; joints from the fragment map.
    def centre(dim, tag):
        return occ.getCenterOfMass(dim, tag)[:2]

    (x0, y0), (x1, y1) = SLIDING_PLANE

    def block_of(x, y):
        if y < BEDDING_Y:
            return "foundation"
        return "wedge" if y > y0 + (x - x0) * (y1 - y0) / (x1 - x0) else "mass"

    for name in E_BLOCK:
        surfaces = [t for _, t in gmsh.model.getEntities(2) if block_of(*centre(2, t)) == name]
        groups[name] = gmsh.model.addPhysicalGroup(2, surfaces)
        gmsh.model.setPhysicalName(2, groups[name], name)
    for name, entities in (("bedding", pieces[1]), ("sliding_plane", pieces[2])):
        groups[name] = gmsh.model.addPhysicalGroup(1, [t for _, t in entities])
        gmsh.model.setPhysicalName(1, groups[name], name)

    # Named boundaries: supports and the loaded crest (the slope face stays free).
    sides = {"bottom": lambda x, y: abs(y) < 1e-6, "left": lambda x, y: abs(x) < 1e-6,
             "right": lambda x, y: abs(x - 60.0) < 1e-6,
             "crest": lambda x, y: abs(y - 30.0) < 1e-6 and CREST[0] < x < CREST[1]}
    outer = gmsh.model.getBoundary(gmsh.model.getEntities(2), combined=True, oriented=False)
    for name, on in sides.items():
        curves = [abs(t) for _, t in outer if on(*centre(1, abs(t)))]
        groups[name] = gmsh.model.addPhysicalGroup(1, curves)
        gmsh.model.setPhysicalName(1, groups[name], name)

    gmsh.option.setNumber("Mesh.MeshSizeMax", mesh_size)
    gmsh.model.mesh.generate(2)
    return groups


def joint_tables(out) -> dict:
    """Barton-Bandis laws from JRC/JCS, tabulated once and saved as .rjt files (paths returned)."""
    laws = {"sliding_plane": rockjoint.BartonBandis.from_joint_properties(jrc=6.0, jcs=80e6,
                                                                          initial_aperture=0.3e-3),
            "bedding": rockjoint.BartonBandis.from_joint_properties(jrc=10.0, jcs=100e6,
                                                                    initial_aperture=0.5e-3)}
    paths = {name: out(f"{name}.rjt") for name in laws}
    if COMM.rank == 0:
        for name, law in laws.items():
            rockjoint.tabulate(law, max_stress=10e6).save(paths[name])
    COMM.barrier()
    return paths


# %% The user's own DOLFINx model ----------------------------------------------------------------
def youngs_modulus(dmesh, graded: bool):
    """E per block (DG0) and, if graded, softened near the crest level: E · (0.4 + 0.6 min(1, depth/20 m))."""
    Q = fem.functionspace(dmesh.mesh, ("DG", 0))
    E_block = fem.Function(Q, name="E_block")
    tags = dmesh.cell_blocks
    for name, E in E_BLOCK.items():
        E_block.x.array[Q.dofmap.list.ravel()[tags.indices[tags.values == dmesh.block_tag(name)]]] = E
    if not graded:
        return E_block
    y = ufl.SpatialCoordinate(dmesh.mesh)[1]
    depth = OUTLINE[2][1] - y
    return E_block * (0.4 + 0.6 * ufl.min_value(1.0, depth / 20.0))


def user_problem(dmesh, tables, graded: bool):
    """Plane-strain elasticity with E(x), gravity and the crest surcharge, plus the joints."""
    mesh = dmesh.mesh
    V = fem.functionspace(mesh, ("Lagrange", 1, (mesh.geometry.dim,)))
    u, v = fem.Function(V, name="displacement"), ufl.TestFunction(V)
    E = youngs_modulus(dmesh, graded)
    mu, lam = E / (2 * (1 + POISSON)), E * POISSON / ((1 + POISSON) * (1 - 2 * POISSON))

    def sigma(w):
        eps = ufl.sym(ufl.grad(w))
        return 2 * mu * eps + lam * ufl.tr(eps) * ufl.Identity(2)

    # Surface loads through the boundary tags: a bare ds would also integrate over the joint faces.
    ds = ufl.Measure("ds", domain=mesh, subdomain_data=dmesh.boundaries)
    gravity = fem.Constant(mesh, (0.0, -DENSITY * GRAVITY))
    surcharge = fem.Constant(mesh, (0.0, -SURCHARGE))
    F = (ufl.inner(sigma(u), ufl.sym(ufl.grad(v))) * ufl.dx - ufl.inner(gravity, v) * ufl.dx
         - ufl.inner(surcharge, v) * ds(dmesh.boundary_tag("crest")))

    # Supports: bottom fixed, rollers on the sides.
    zero = PETSc.ScalarType(0.0)
    bottom = fem.locate_dofs_topological(V, 1, dmesh.boundary("bottom"))
    bcs = [fem.dirichletbc(np.zeros(2, dtype=PETSc.ScalarType), bottom, V)]
    for side in ("left", "right"):
        dofs = fem.locate_dofs_topological(V.sub(0), 1, dmesh.boundary(side))
        bcs.append(fem.dirichletbc(zero, dofs, V.sub(0)))

    # The joints: a law per joint name (here the saved tables), the shear stiffness.
    coupling = JointCoupling(V, dmesh, tables, shear_stiffness=SHEAR_STIFFNESS, bcs=bcs)
    # Solved by SNES: Newton with a full step ("basic" line search; the joints' closure limiter is
    # its pre-check), direct solves; snes_rtol is relative to the residual at u = 0, the load.
    problem = JointedNonlinearProblem(F, u, coupling, bcs=bcs, petsc_options_prefix="slope_",
                                      petsc_options=SNES_OPTIONS)
    return problem, E


def solve(problem) -> int:
    """problem.solve() as for DOLFINx's NonlinearProblem; SNES iterations."""
    problem.solve()
    reason = problem.solver.getConvergedReason()
    if reason <= 0:
        raise RuntimeError(f"SNES did not converge (reason {reason})")
    return problem.solver.getIterationNumber()


def boundary_mean(u, dmesh, name):
    """∫u ds / ∫ds over a named boundary [m] (all ranks)."""
    ds = ufl.Measure("ds", domain=dmesh.mesh, subdomain_data=dmesh.boundaries)(dmesh.boundary_tag(name))
    one = fem.Constant(dmesh.mesh, 1.0)
    area = COMM.allreduce(fem.assemble_scalar(fem.form(one * ds)))
    return np.array([COMM.allreduce(fem.assemble_scalar(fem.form(u[i] * ds))) / area for i in range(2)])


def max_difference(u, w):
    """max |u - w| over all dofs of all ranks [m] (the two Functions on identical spaces)."""
    n = u.function_space.dofmap.index_map.size_local * 2
    return COMM.allreduce(float(np.abs(u.x.array[:n] - w.x.array[:n]).max(initial=0.0)), op=MPI.MAX)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--output", default=".", help="output folder")
    ap.add_argument("--mesh-size", type=float, default=1.0, help="element size [m]")
    args = ap.parse_args()
    os.makedirs(args.output, exist_ok=True)
    out = lambda name: os.path.join(args.output, name)  # noqa: E731

    # %% 1. The user's geometry and mesh in gmsh, read by DOLFINx's gmsh reader ----------------------
    groups = COMM.bcast(build_slope(args.mesh_size) if COMM.rank == 0 else None, root=0)
    mesh_data = gmshio.model_to_mesh(gmsh.model if COMM.rank == 0 else None, COMM, 0, gdim=2)
    if COMM.rank == 0:
        gmsh.finalize()
    # rockjoint splits the nodes along the joints (one copy per side) and redistributes the mesh so
    # that both cells of every joint facet live on one rank.
    dmesh = split_joints(mesh_data,
                         joints={n: groups[n] for n in ("bedding", "sliding_plane")},
                         blocks={n: groups[n] for n in E_BLOCK},
                         boundaries={n: groups[n] for n in ("bottom", "left", "right", "crest")})
    say(f"slope: blocks {sorted(dmesh.names['blocks'].values())}, joints "
        f"{sorted(dmesh.names['joints'].values())}, {COMM.allreduce(len(dmesh.pairs))} joint facet pairs")

    # %% 2. Joint laws: tables made once, saved, and read back by path -------------------------------
    tables = joint_tables(out)

    # %% 3. The graded-E model, solved by SNES ---------------------------------------------------------
    problem, E = user_problem(dmesh, tables, graded=True)
    iterations = solve(problem)
    u = problem.u
    say(f"SNES: {iterations} iterations")
    lines = [f"SNES iterations (graded E)                  {iterations}"]

    crest = boundary_mean(u, dmesh, "crest")
    # The joint state over all ranks (the same numbers on every rank): per joint extremes.
    plane = problem.coupling.summary(u)["sliding_plane"]
    lines += [f"crest settlement, graded E [mm]             {-crest[1] * 1e3:.6f}",
              f"crest horizontal displacement [mm]          {crest[0] * 1e3:.6f}",
              f"sliding plane: max closure [mm]             {plane.max_closure * 1e3:.6f}",
              f"sliding plane: max normal stress [MPa]      {plane.max_normal_stress * 1e-6:.6f}",
              f"sliding plane: max |shear traction| [MPa]   {plane.max_shear_traction * 1e-6:.6f}"]

    # %% 4. Check: piecewise-constant E, the user's forms against JointedRockModel -------------------
    check, _ = user_problem(dmesh, tables, graded=False)
    solve(check)
    model = JointedRockModel(dmesh, rock={b: (E_BLOCK[b], POISSON) for b in E_BLOCK},
                             joints={name: rockjoint.TabulatedLaw.load(path) for name, path in tables.items()},
                             shear_stiffness=SHEAR_STIFFNESS, plane="strain",
                             newton=NewtonOptions(verbose=False))
    model.fix("bottom", "all")
    model.fix("left", "x")
    model.fix("right", "x")
    model.add_body_force((0.0, -DENSITY * GRAVITY))
    model.add_traction("crest", (0.0, -SURCHARGE))
    reference = model.solve().displacement
    diff = max_difference(check.u, reference)
    scale = COMM.allreduce(float(np.abs(reference.x.array).max(initial=0.0)), op=MPI.MAX)
    crest_check, crest_model = boundary_mean(check.u, dmesh, "crest"), boundary_mean(reference, dmesh, "crest")
    lines += [f"crest settlement, E per block, user [mm]    {-crest_check[1] * 1e3:.6f}",
              f"crest settlement, JointedRockModel [mm]     {-crest_model[1] * 1e3:.6f}",
              f"max |u_user - u_JointedRockModel| [m]       {diff:.3e}",
              f"relative to max |u|                         {diff / scale:.3e}"]
    say("\n" + "\n".join(lines))
    if COMM.rank == 0:
        with open(out("user_model.txt"), "w") as f:
            f.write("# rockjoint user-model demo: 60 m section through a 20 m slope, plane strain, "
                    f"gravity ({DENSITY:g} kg/m³), crest surcharge {SURCHARGE * 1e-6:g} MPa\n")
            f.write("\n".join(lines) + "\n")

    # %% 5. Output: XDMF for ParaView, a picture drawn on the mesh -----------------------------------
    Q = fem.functionspace(dmesh.mesh, ("DG", 0))
    E_cells = fem.Function(Q, name="youngs_modulus_Pa")
    E_cells.interpolate(fem.Expression(E, Q.element.interpolation_points))
    with XDMFFile(COMM, out("user_model.xdmf"), "w") as f:
        f.write_mesh(dmesh.mesh)
        f.write_function(u)
        f.write_function(E_cells)
    state = problem.coupling.state(u)                        # this rank's joint points
    gathered = {k: np.concatenate(COMM.allgather(np.asarray(v))) for k, v in state.items()}
    if COMM.rank == 0:
        write_joint_points(out("user_model_joints.xdmf"), gathered, 2)
    plot(u, dmesh, out("user_model.png"))
    say(f"wrote {out('user_model.txt')}, {out('user_model.png')}, {out('user_model.xdmf')}, "
        f"{out('user_model_joints.xdmf')}")


def plot(u, dmesh, path):
    """|u| as filled triangles (mm) on the undeformed mesh, and the outline and joint faces
    displaced by a magnified u."""
    from dolfinx.mesh import exterior_facet_indices
    mesh = dmesh.mesh
    tdim = mesh.topology.dim
    x = mesh.geometry.x[:, :2]
    values = u.x.array.reshape(-1, 2)
    tri_x, tri_u = gather_triangles(u)                                    # (cells, 3, 2) on rank 0
    # Outline: exterior facets of the split mesh, i.e. the boundary and both faces of every joint.
    mesh.topology.create_connectivity(tdim - 1, tdim)
    facets = exterior_facet_indices(mesh.topology)
    f2c = mesh.topology.connectivity(tdim - 1, tdim)
    c2f = mesh.topology.connectivity(tdim, tdim - 1)
    segs_x, segs_u = [], []
    for f in facets:
        c = f2c.links(f)[0]
        local = int(np.flatnonzero(c2f.links(c) == f)[0])
        verts = [i for i in range(3) if i != local]                      # facet i is opposite vertex i
        segs_x.append(x[mesh.geometry.dofmaps[0][c][verts]])
        segs_u.append(values[u.function_space.dofmap.cell_dofs(c)[verts]])
    parts = [COMM.gather(np.asarray(a).reshape(-1, 4), root=0) for a in (segs_x, segs_u)]
    if COMM.rank != 0:
        return
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import LineCollection
    segs_x, segs_u = (np.concatenate(p).reshape(-1, 2, 2) for p in parts)
    magnitude = np.linalg.norm(tri_u, axis=2).ravel() * 1e3
    scale = 0.05 * 60.0 / max(np.abs(segs_u).max(), 1e-300)               # largest shift = 3 m
    fig, ax = plt.subplots(figsize=(11, 5.2))
    points = tri_x.reshape(-1, 2)
    shading = ax.tripcolor(points[:, 0], points[:, 1], np.arange(points.shape[0]).reshape(-1, 3),
                           magnitude, shading="gouraud", cmap="viridis")
    fig.colorbar(shading, ax=ax, label="|u| [mm]")
    ax.add_collection(LineCollection(segs_x, colors="0.6", linewidths=0.6, label="undeformed"))
    ax.add_collection(LineCollection(segs_x + scale * segs_u, colors="crimson", linewidths=1.0,
                                     label=f"deformed outline and joint faces (u × {scale:.0f})"))
    ax.set_aspect("equal")
    ax.set_xlim(-2, 62)
    ax.set_ylim(-2, 36)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.legend(loc="upper left")
    ax.set_title("user's DOLFINx slope model with rockjoint joints: |u| under gravity and crest surcharge")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


if __name__ == "__main__":
    main()
