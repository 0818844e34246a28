# SPDX-License-Identifier: MIT
"""Steady flow through rock with smeared joint sets: the equivalent permeability of the sets and
Darcy's law on the DOLFINx mesh (docs/flow.md).

A set of parallel joints of transmissivity T = e_h³/12 [m³] every s [m] conducts like the rock of
permeability T/s along its planes and nothing across them; the sets add up (parallel plates,
Snow 1969; Oda 1985's crack tensor for persistent joints):

    k = Σ_i (T_i / s_i) (I - n_i ⊗ n_i)    [m²]                                        (F2)
    q = -(ρ g / μ) k ∇h,   ∇·q = 0          (Darcy; h the hydraulic head [m])            (F3)

solved with P1 elements, heads on named boundaries; the flow rate through a boundary with a head
is the reaction of the assembled (unconstrained) operator at its dofs, which conserves mass to
solver tolerance. In 2D flow rates are per metre out of plane [m²/s]; in 3D [m³/s].
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Mapping, Sequence

import numpy as np
import ufl
from dolfinx import fem
from dolfinx.fem import petsc as fem_petsc
from petsc4py import PETSc

from ..mesh.distributed_mesh import lookup
from .joint_flow import Fluid


def equivalent_permeability(sets: Sequence[tuple], gdim: int) -> np.ndarray:
    """(F2): k [m²] (gdim x gdim) of smeared sets given as (normal, spacing [m], T [m³]); the normal
    need not be unit. ValueError naming a bad set."""
    k = np.zeros((gdim, gdim))
    for i, (normal, spacing, transmissivity) in enumerate(sets):
        n = np.asarray(normal, dtype=float)
        if n.shape != (gdim,) or not np.all(np.isfinite(n)) or np.linalg.norm(n) == 0:
            raise ValueError(f"set {i}: normal {normal!r} must be {gdim} finite numbers, not all 0")
        if not (math.isfinite(spacing) and spacing > 0):
            raise ValueError(f"set {i}: spacing {spacing!r} must be finite and > 0 [m]")
        if not (math.isfinite(transmissivity) and transmissivity >= 0):
            raise ValueError(f"set {i}: transmissivity {transmissivity!r} must be finite and >= 0 [m³]")
        n = n / np.linalg.norm(n)
        k += transmissivity / spacing * (np.eye(gdim) - np.outer(n, n))
    return k


@dataclass
class DarcyFlow:
    """Steady Darcy flow on a mesh: the head (P1) and the flow rate into the rock through every
    boundary with a head (all ranks)."""

    head: fem.Function
    flow_rates: dict      # {boundary: Q into the rock [m³/s; m²/s in 2D]}


def darcy_flow(dmesh, permeability, heads: Mapping[str, float], fluid: Fluid = Fluid(),
               rtol: float = 1e-12) -> DarcyFlow:
    """(F3) on the mesh of `dmesh` (a DistributedJointMesh of the intact or smeared model) with the
    permeability tensor k [m²] (gdim x gdim, (F2)) and heads {boundary name: h [m]}. Collective.
    Boundaries with different heads must not meet (ValueError naming them)."""
    mesh = dmesh.mesh
    gdim, tdim = mesh.geometry.dim, mesh.topology.dim
    k = np.asarray(permeability, dtype=float)
    if k.shape != (gdim, gdim) or not np.all(np.isfinite(k)) or not np.allclose(k, k.T, rtol=1e-12, atol=0):
        raise ValueError(f"darcy_flow: permeability must be a finite symmetric {gdim}x{gdim} tensor [m²]")
    if not heads:
        raise ValueError("darcy_flow: give heads={boundary name: h [m]} on at least one boundary")
    V = fem.functionspace(mesh, ("Lagrange", 1))
    h, v = ufl.TrialFunction(V), ufl.TestFunction(V)
    conductivity = fem.Constant(mesh, PETSc.ScalarType(fluid.conductivity_factor) * k)
    a = fem.form(ufl.inner(ufl.dot(conductivity, ufl.grad(h)), ufl.grad(v)) * ufl.dx)
    L = fem.form(fem.Constant(mesh, PETSc.ScalarType(0.0)) * v * ufl.dx)
    mesh.topology.create_connectivity(tdim - 1, tdim)
    bcs, owned, given = [], {}, {}
    n_owned = V.dofmap.index_map.size_local
    for name, value in heads.items():
        lookup(dmesh, "boundaries", name)
        if not (isinstance(value, (int, float)) and math.isfinite(value)):
            raise ValueError(f"darcy_flow: head on {name!r} = {value!r} must be a finite number [m]")
        dofs = fem.locate_dofs_topological(V, tdim - 1, dmesh.boundary(name))
        given[name] = dofs
        owned[name] = dofs[dofs < n_owned]
        bcs.append(fem.dirichletbc(PETSc.ScalarType(value), dofs, V))
    # A vertex on two boundaries with different heads has no head: refused (collective).
    clash = sorted({f"{p} and {q}" for i, p in enumerate(given) for q in list(given)[i + 1:]
                    if heads[p] != heads[q] and np.intersect1d(given[p], given[q]).size})
    clash = sorted(set().union(*mesh.comm.allgather(set(clash))))
    if clash:
        raise ValueError(f"darcy_flow: boundaries {', '.join(clash)} meet, with different heads: "
                         "a vertex there would have two heads")
    A = fem_petsc.assemble_matrix(a, bcs=bcs)
    A.assemble()
    b = fem_petsc.assemble_vector(L)
    fem_petsc.apply_lifting(b, [a], bcs=[bcs])
    b.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
    fem_petsc.set_bc(b, bcs)
    solution = fem.Function(V, name="head")
    ksp = PETSc.KSP().create(mesh.comm)
    ksp.setOperators(A)
    ksp.setType("cg")
    ksp.getPC().setType("gamg")
    ksp.setTolerances(rtol=rtol, atol=0.0, max_it=2000)
    ksp.solve(b, solution.x.petsc_vec)
    if ksp.getConvergedReason() <= 0:
        raise RuntimeError(f"darcy_flow: CG did not converge (reason {ksp.getConvergedReason()})")
    solution.x.scatter_forward()
    # Reactions of the unconstrained operator: the flow into the rock at the dofs with a head.
    A0 = fem_petsc.assemble_matrix(a)
    A0.assemble()
    reaction = A0.createVecLeft()
    A0.mult(solution.x.petsc_vec, reaction)
    r = reaction.getArray(readonly=True)
    rates = {name: mesh.comm.allreduce(float(r[dofs].sum())) for name, dofs in owned.items()}
    for obj in (ksp, A, A0, b, reaction):
        obj.destroy()
    return DarcyFlow(solution, rates)
