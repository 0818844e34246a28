# SPDX-License-Identifier: MIT
"""Output of a solved model: XDMF files (the displacement field, and the joint point state as a
point cloud) and the mesh data gathered on rank 0 for pictures (2D triangles, 3D boundary faces
and sections; rockjoint.scenes.pictures draws them).

The joint state lives at the quadrature points of the joint facets (nodal rule: the facet
nodes, once per pair), which are not a function space: it is gathered to rank 0 and written by
meshio as an XDMF Polyvertex grid with HDF5 data (readable by ParaView): closure [m], normal stress [Pa], shear
traction [Pa], status (rockjoint.Status values), joint tag. One value per point and pair: a node on a facet
shared by k pairs appears k times.
"""
from __future__ import annotations

import os

import numpy as np
from dolfinx import fem
from dolfinx import mesh as dmesh
from dolfinx.io import XDMFFile


def write_joint_points(path: str, state: dict, gdim: int) -> None:
    """Write a gathered joint state dict (all points) as an XDMF Polyvertex grid with its
    heavy data in <stem>.h5 (meshio's XDMF writer, HDF5 through h5py). Attribute names carry
    their units: closure_m, normal_stress_Pa, shear_traction_Pa (vector, local axes t1[, t2]),
    status (rockjoint.Status values), joint_tag, and when the state has them slip_m (vector,
    local axes), dilation_m, shear_state (rockjoint.fem.ShearState values)."""
    import meshio  # Debian python3-meshio; imported here so the FE layer loads without it

    x = np.asarray(state["coordinates"], dtype=float).reshape(-1, gdim)
    n = x.shape[0]
    xyz = np.zeros((n, 3))
    xyz[:, :gdim] = x
    shear = np.zeros((n, 3))
    shear[:, :gdim - 1] = np.asarray(state["shear_traction"], dtype=float).reshape(n, gdim - 1)
    point_data = {"closure_m": np.asarray(state["closure"], dtype=float),
                  "normal_stress_Pa": np.asarray(state["normal_stress"], dtype=float),
                  "shear_traction_Pa": shear,
                  "status": np.asarray(state["status"], dtype=np.int32),
                  "joint_tag": np.asarray(state["tag"], dtype=np.int32)}
    if "slip" in state:  # joint strength: the path-dependent state
        slip = np.zeros((n, 3))
        slip[:, :gdim - 1] = np.asarray(state["slip"], dtype=float).reshape(n, gdim - 1)
        point_data["slip_m"] = slip
        point_data["dilation_m"] = np.asarray(state["dilation"], dtype=float)
        point_data["shear_state"] = np.asarray(state["shear_state"], dtype=np.int32)
    cells = [("vertex", np.arange(n, dtype=np.int64).reshape(-1, 1))]
    meshio.write(path, meshio.Mesh(xyz, cells, point_data=point_data), file_format="xdmf")


def write_functions(path: str, *functions: fem.Function) -> str:
    """Write functions on one mesh (e.g. model.total_stress()) with that mesh to an XDMF file;
    collective. Returns the path."""
    mesh = functions[0].function_space.mesh
    with XDMFFile(mesh.comm, path, "w") as f:
        f.write_mesh(mesh)
        for function in functions:
            f.write_function(function)
    return path


def write_xdmf(model, path: str) -> list:
    """Displacement to `path` (P1 interpolation for P2 fields) and joints to <stem>_joints.xdmf."""
    mesh, comm = model.mesh, model.comm
    u = model.solution.displacement
    if model.degree != 1:
        V1 = fem.functionspace(mesh, ("Lagrange", 1, (mesh.geometry.dim,)))
        u1 = fem.Function(V1, name="displacement")
        u1.interpolate(u)
        u = u1
    with XDMFFile(comm, path, "w") as f:
        f.write_mesh(mesh)
        f.write_function(u)
    state = model.solution.gather_joints()
    if np.asarray(state["closure"]).size == 0:  # an intact block: no joint points to write
        return [path]
    stem, _ = os.path.splitext(path)
    joints_path = stem + "_joints.xdmf"
    if comm.rank == 0:
        write_joint_points(joints_path, state, model.gdim)
    comm.barrier()
    return [path, joints_path]


def gather_triangles(u: fem.Function, cell_values=None, root: int = 0):
    """The owned cells of a 2D P1 displacement u, gathered on rank `root` for pictures drawn on
    the mesh (matplotlib tripcolor, deformed outlines): (vertex coordinates (cells, 3, 2) [m],
    u at those vertices (cells, 3, 2) [m]) and, with `cell_values` (one row per owned cell),
    those rows too. Other ranks get None for each. Collective."""
    V = u.function_space
    mesh = V.mesh
    if mesh.geometry.dim != 2 or V.ufl_element().embedded_superdegree != 1:
        raise ValueError("gather_triangles: a P1 displacement on a 2D triangle mesh is needed, got "
                         f"gdim {mesh.geometry.dim}, degree {V.ufl_element().embedded_superdegree}")
    n_cells = mesh.topology.index_map(2).size_local
    vertices = mesh.geometry.x[:, :2][mesh.geometry.dofmaps[0][:n_cells]]
    # P1: the cell's dof i sits on its vertex i.
    at_vertices = u.x.array.reshape(-1, 2)[V.dofmap.list[:n_cells]]
    parts = [vertices, at_vertices] + ([] if cell_values is None else [np.asarray(cell_values)])
    if len(parts) == 3 and parts[2].shape[0] != n_cells:
        raise ValueError(f"gather_triangles: cell_values has {parts[2].shape[0]} rows, the rank owns "
                         f"{n_cells} cells")
    gathered = [mesh.comm.gather(p, root=root) for p in parts]
    if mesh.comm.rank != root:
        return tuple(None for _ in parts)
    return tuple(np.concatenate(g) for g in gathered)


def boundary_triangles(u):
    """The boundary faces of a 3D P1 displacement's mesh (the outer faces and both faces of every
    joint: split nodes make them boundaries), gathered on rank 0: (vertices (n, 3, 3) [m], u at
    them (n, 3, 3) [m]); None elsewhere. Collective."""
    V = u.function_space
    mesh = V.mesh
    tdim = mesh.topology.dim
    mesh.topology.create_connectivity(tdim - 1, tdim)
    facets = dmesh.exterior_facet_indices(mesh.topology)
    nodes = dmesh.entities_to_geometry(mesh, tdim - 1, facets, False)
    # P1 on simplices: a cell's geometry nodes and its dofs follow the same vertex order
    n_cells = mesh.topology.index_map(tdim).size_local + mesh.topology.index_map(tdim).num_ghosts
    node_dof = np.zeros(mesh.geometry.x.shape[0], dtype=np.int64)
    node_dof[mesh.geometry.dofmaps[0][:n_cells].ravel()] = V.dofmap.list[:n_cells].ravel()
    x = mesh.geometry.x[nodes]
    values = u.x.array.reshape(-1, 3)[node_dof[nodes]]
    parts = [mesh.comm.gather(p, root=0) for p in (x, values)]
    if mesh.comm.rank != 0:
        return None, None
    return tuple(np.concatenate(p) for p in parts)


def section_triangles(u, y: float):
    """The section of a 3D P1 displacement's mesh by the plane y = `y`, across a tunnel whose axis
    is y (meshes.tunnel_section: the 2D section's (x, y) are (x, z) in 3D), gathered on rank 0:
    triangles (n, 3, 2) [m] in section coordinates (x, z), u at their corners (n, 3, 3) [m] (linear
    in each tetrahedron, so exact for P1). None elsewhere. Collective."""
    V = u.function_space
    mesh = V.mesh
    n_cells = mesh.topology.index_map(3).size_local
    x = mesh.geometry.x[mesh.geometry.dofmaps[0][:n_cells]]          # (cells, 4, 3)
    values = u.x.array.reshape(-1, 3)[V.dofmap.list[:n_cells]]      # P1: dof i on vertex i
    x = x[:, :, [0, 2, 1]]                      # (x, z) in the plane, y across it
    values = values[:, :, [0, 2, 1]]
    d = x[:, :, 2] - y
    cut = (d.min(axis=1) < 0) & (d.max(axis=1) > 0)
    tris, us = [], []
    for xc, uc, dc in zip(x[cut], values[cut], d[cut]):
        points, at = [], []
        for i, j in ((0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)):
            if (dc[i] < 0) != (dc[j] < 0):
                w = dc[i] / (dc[i] - dc[j])
                points.append(xc[i, :2] + w * (xc[j, :2] - xc[i, :2]))
                at.append(uc[i] + w * (uc[j] - uc[i]))
        points, at = np.array(points), np.array(at)
        order = np.argsort(np.arctan2(*(points - points.mean(axis=0)).T[::-1]))
        points, at = points[order], at[order]
        for k in range(1, len(points) - 1):   # a triangle or a quadrilateral: fan triangles
            tris.append(points[[0, k, k + 1]])
            us.append(at[[0, k, k + 1]])
    parts = [np.array(tris).reshape(-1, 3, 2), np.array(us).reshape(-1, 3, 3)]
    gathered = [mesh.comm.gather(p, root=0) for p in parts]
    if mesh.comm.rank != 0:
        return None, None
    tri, us = (np.concatenate(g) for g in gathered)
    return tri, us[:, :, [0, 2, 1]]             # u back in (x, y, z)
