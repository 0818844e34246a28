"""XDMF output: the displacement field, and the joint point state as a point cloud.

The joint state lives at the quadrature points of the joint facets (nodal rule: the facet
nodes, once per pair), which are not a DOLFINx function space in 0.5.2 (quadrature spaces fail in
ds integrals, field notes): it is gathered to rank 0 and written as an XDMF Polyvertex grid with
inline XML data (readable by ParaView): closure [m], normal_stress [Pa], shear_traction [Pa],
status (rockjoint.Status values), joint tag. One value per point and pair: a node on a facet
shared by k pairs appears k times.
"""
from __future__ import annotations

import os

import numpy as np
from dolfinx import fem
from dolfinx.io import XDMFFile


def _data_item(a: np.ndarray, fmt: str) -> str:
    dims = " ".join(str(d) for d in a.shape)
    kind = "Int" if np.issubdtype(a.dtype, np.integer) else "Float"
    prec = 4 if kind == "Int" else 8
    body = "\n".join(" ".join(fmt % x for x in np.atleast_1d(row)) for row in a.reshape(a.shape[0], -1))
    return (f'<DataItem Dimensions="{dims}" NumberType="{kind}" Precision="{prec}" Format="XML">\n'
            f"{body}\n</DataItem>")


def write_joint_points(path: str, state: dict, gdim: int) -> None:
    """Write a gathered joint state dict (all points) as an XDMF Polyvertex grid."""
    x = np.asarray(state["coordinates"], dtype=float).reshape(-1, gdim)
    n = x.shape[0]
    xyz = np.zeros((n, 3))
    xyz[:, :gdim] = x
    attrs = [("closure", state["closure"], "Scalar"), ("normal_stress", state["normal_stress"], "Scalar"),
             ("status", state["status"], "Scalar"), ("joint_tag", state["tag"], "Scalar")]
    shear = np.asarray(state["shear_traction"]).reshape(n, gdim - 1)
    for i in range(gdim - 1):
        attrs.append((f"shear_traction_{i + 1}", shear[:, i], "Scalar"))
    parts = ['<?xml version="1.0" ?>', '<Xdmf Version="3.0">', "<Domain>", '<Grid Name="joints" GridType="Uniform">',
             f'<Topology TopologyType="Polyvertex" NumberOfElements="{n}" NodesPerElement="1"/>',
             '<Geometry GeometryType="XYZ">', _data_item(xyz, "%.17g"), "</Geometry>"]
    for name, a, kind in attrs:
        a = np.asarray(a)
        parts += [f'<Attribute Name="{name}" AttributeType="{kind}" Center="Node">',
                  _data_item(a, "%d" if np.issubdtype(a.dtype, np.integer) else "%.17g"), "</Attribute>"]
    parts += ["</Grid>", "</Domain>", "</Xdmf>"]
    with open(path, "w") as fh:
        fh.write("\n".join(parts) + "\n")


def write_xdmf(model, path: str) -> list:
    """Displacement to `path` (P1 interpolation for P2 fields) and joints to <stem>_joints.xdmf."""
    mesh, comm = model.mesh, model.comm
    u = model.solution.displacement
    if model.degree != 1:
        V1 = fem.VectorFunctionSpace(mesh, ("Lagrange", 1))
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
