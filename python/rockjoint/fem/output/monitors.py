# SPDX-License-Identifier: MIT
"""What a user or a scene reads off a solved model's fields (UFL assembly over the mesh, all
ranks): boundary means of the displacement and the total stress."""
from __future__ import annotations

import numpy as np
import ufl
from dolfinx import fem

from ..mesh.distributed_mesh import lookup


def _boundary_measure(model, boundary: str):
    tag = lookup(model.dmesh, "boundaries", boundary)
    return ufl.Measure("ds", domain=model.mesh, subdomain_data=model.dmesh.boundaries)(tag)


def boundary_mean_displacement(model, boundary: str) -> np.ndarray:
    """Mean displacement vector [m] over a named boundary (∫u ds / ∫ds, all ranks)."""
    ds = _boundary_measure(model, boundary)
    area = model.comm.allreduce(fem.assemble_scalar(fem.form(fem.Constant(model.mesh, 1.0) * ds)))
    return np.array([model.comm.allreduce(fem.assemble_scalar(fem.form(model.u[i] * ds))) / area
                     for i in range(model.gdim)])


def mean_normal_displacement(model, boundary: str) -> float:
    """∫ u·n ds / ∫ ds over a named boundary, n the rock's outward normal [m] (into an opening:
    its convergence; on a loaded face: its outward movement). All ranks."""
    ds = _boundary_measure(model, boundary)
    n = ufl.FacetNormal(model.mesh)
    area = model.comm.allreduce(fem.assemble_scalar(fem.form(fem.Constant(model.mesh, 1.0) * ds)))
    return model.comm.allreduce(fem.assemble_scalar(fem.form(ufl.dot(model.u, n) * ds))) / area


def total_stress(u, sigma, sigma0, degree: int) -> fem.Function:
    """σ0 + σ(u) [Pa, tension positive] (σ0 None: σ(u)) interpolated in a discontinuous tensor
    space of `degree` on u's mesh."""
    mesh = u.function_space.mesh
    T = fem.functionspace(mesh, ("DG", degree, (mesh.geometry.dim, mesh.geometry.dim)))
    stress = sigma(u)
    if sigma0 is not None:
        stress = stress + sigma0
    out = fem.Function(T, name="total_stress")
    out.interpolate(fem.Expression(stress, T.element.interpolation_points))
    return out
