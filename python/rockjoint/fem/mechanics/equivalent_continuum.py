# SPDX-License-Identifier: MIT
"""The equivalent-continuum material in some blocks of a DOLFINx model (docs/equivalent-continuum.md).

A block given a `rockjoint.continuum.EquivalentContinuum` carries its joint sets
smeared: the stress at every quadrature point of its cells comes from the C++ material (rock
elasticity + the sets, each through the joint behaviour of the discrete joint elements), with its
consistent tangent. The other blocks stay linear elastic and may hold discrete joints, so one mesh
mixes smeared and discrete joints.

The bulk of JointedRockModel is the linear elastic K for every cell; a smeared block adds the
correction to it (one bulk, no parallel framework)::

    F_c = ∫_c (σ(ε0 + ε(u)) - σ0 - D ε(u)) · ε_v(v) dx,   J_c = ∫_c ε_v(v) · (C - D) ε_v(du) dx,

with Voigt vectors ε_v (engineering shear), σ0 the in-situ stress (∫ε(v):σ0 is already in the
model's residual) and ε0 the strain that carries it (the sets pre-closed by σ0). Both forms use
the quadrature degree of the stress/tangent quadrature spaces.

Viscous sets (`relaxation` = r, set by pseudo_transient.py): Duvaut-Lions at the material point,::

    σ = (σ_n + D (ε - ε_n) + r σ_ri(ε)) / (1 + r),   C = (D + r C_ri) / (1 + r),

with σ_n, ε_n the last committed stress and strain and σ_ri, C_ri the rate-independent response:
the joints' deformation lags behind the rock's by the relaxation time. The D part keeps the
tangent positive definite where the rate-independent one is not (sets sliding with a
non-associated flow rule), and the stationary state of the pseudo-time steps (ε = ε_n) is the
rate-independent equilibrium.
"""
from __future__ import annotations

import logging

import basix
import basix.ufl
import numpy as np
import ufl
from dolfinx import cpp as _cpp
from dolfinx import fem
from dolfinx.fem import petsc as fem_petsc
from mpi4py import MPI
from petsc4py import PETSc

from ...continuum import ContinuumPoints, EquivalentContinuum
from ...joint import StrengthModel
from ..compat import create_vector

log = logging.getLogger(__name__)


def voigt_strain(w, gdim: int):
    """ε(w) as a Voigt vector with engineering shear: (xx, yy, xy) or (xx, yy, zz, yz, xz, xy)."""
    e = ufl.sym(ufl.grad(w))
    if gdim == 2:
        return ufl.as_vector([e[0, 0], e[1, 1], 2 * e[0, 1]])
    return ufl.as_vector([e[0, 0], e[1, 1], e[2, 2], 2 * e[1, 2], 2 * e[0, 2], 2 * e[0, 1]])


def voigt_stress(tensors: np.ndarray) -> np.ndarray:
    """(n, gdim, gdim) stress tensors → (n, nv) Voigt stresses."""
    t = np.asarray(tensors, dtype=float)
    if t.shape[1] == 2:
        return np.stack([t[:, 0, 0], t[:, 1, 1], t[:, 0, 1]], axis=1)
    return np.stack([t[:, 0, 0], t[:, 1, 1], t[:, 2, 2], t[:, 1, 2], t[:, 0, 2], t[:, 0, 1]], axis=1)


class SmearedBlocks:
    """The smeared blocks of an ElasticBlocks mesh. materials: {block tag: EquivalentContinuum}
    (its E, ν must be the block's rock); quadrature_degree: of the stress and tangent spaces and of
    both forms (default 2 (p - 1), at least 1). Attributes: stress, tangent (quadrature Functions:
    σ [Pa] and C [Pa], row major), residual_form, jacobian_form, points ({tag: ContinuumPoints})."""

    def __init__(self, blocks, dmesh, materials: dict, rock: dict, quadrature_degree: int | None = None):
        mesh = blocks.mesh
        gdim, tdim = blocks.gdim, mesh.topology.dim
        if gdim == 2 and blocks.plane != "strain":
            raise ValueError(f"the equivalent continuum is plane strain in 2D; the model has plane={blocks.plane!r}")
        self.mesh, self.gdim, self.blocks = mesh, gdim, blocks
        nv = 3 if gdim == 2 else 6
        self.nv = nv
        q = quadrature_degree if quadrature_degree is not None else max(2 * (blocks.degree - 1), 1)
        if not (isinstance(q, int) and q >= 1):
            raise ValueError(f"quadrature_degree must be an integer >= 1, got {q!r}")
        self.quadrature_degree = q
        cell = mesh.basix_cell()
        Qs = fem.functionspace(mesh, basix.ufl.quadrature_element(cell, value_shape=(nv,), degree=q))
        Qc = fem.functionspace(mesh, basix.ufl.quadrature_element(cell, value_shape=(nv * nv,), degree=q))
        self.stress = fem.Function(Qs, name="continuum_stress")
        self.sigma0 = fem.Function(Qs, name="continuum_in_situ_stress")
        self.tangent = fem.Function(Qc, name="continuum_tangent")
        points, _ = basix.make_quadrature(basix.CellType[cell.name], q)
        self.num_qp = points.shape[0]
        self._strain_expr = fem.Expression(voigt_strain(blocks.u, gdim), points)
        self._x_expr = fem.Expression(ufl.SpatialCoordinate(mesh), points)

        n_owned = mesh.topology.index_map(tdim).size_local
        tags = dmesh.cell_blocks
        owned = tags.indices < n_owned
        self.cells, self.points, self.eps0 = {}, {}, {}
        for tag, material in materials.items():
            if not isinstance(material, EquivalentContinuum):
                raise ValueError(f"block {tag}: expected an EquivalentContinuum, got {type(material).__name__}")
            if material.gdim != gdim:
                raise ValueError(f"block {tag}: the material is {material.gdim}D, the mesh {gdim}D")
            E, nu = rock[tag]
            if not (np.isclose(E, material.young, rtol=1e-12) and np.isclose(nu, material.poisson, rtol=1e-12)):
                raise ValueError(f"block {tag}: the material's rock (E = {material.young:g} Pa, ν = "
                                 f"{material.poisson:g}) differs from the block's rock (E = {E:g} Pa, ν = {nu:g})")
            cells = np.sort(tags.indices[owned & (tags.values == tag)]).astype(np.int32)
            self.cells[tag] = cells
            self.points[tag] = ContinuumPoints(material, cells.size * self.num_qp)
            self.eps0[tag] = np.zeros((cells.size * self.num_qp, nv))
        #: r = Δt/τ of viscous sets (module docstring); None: rate-independent
        self.relaxation = None
        self._committed = {tag: (np.zeros_like(e), e.copy()) for tag, e in self.eps0.items()}  # σ_n, ε_n
        self._current = {}
        self._fill_elastic()

        v, du = blocks.v, ufl.TrialFunction(blocks.V)
        dx = ufl.Measure("dx", domain=mesh, subdomain_data=tags,
                         metadata={"quadrature_degree": q, "quadrature_rule": "default"})
        C = ufl.as_matrix([[self.tangent[i * nv + j] for j in range(nv)] for i in range(nv)])
        ev, edu = voigt_strain(v, gdim), voigt_strain(du, gdim)
        F = J = None
        for t in materials:
            f_t = (ufl.dot(self.stress - self.sigma0, ev) - ufl.inner(blocks.sigma(blocks.u), blocks.eps(v))) * dx(int(t))
            j_t = (ufl.dot(ev, ufl.dot(C, edu)) - ufl.inner(blocks.sigma(du), blocks.eps(v))) * dx(int(t))
            F = f_t if F is None else F + f_t
            J = j_t if J is None else J + j_t
        self.residual_form, self.jacobian_form = fem.form(F), fem.form(J)
        self._rc = create_vector(self.residual_form.function_spaces[0])

    def _dofs(self, tag) -> np.ndarray:
        return self.stress.function_space.dofmap.list[self.cells[tag]].ravel()

    def _fill_elastic(self) -> None:
        """Rock stiffness as the tangent before the first evaluation (cells outside: zero)."""
        nv = self.nv
        for tag, pts in self.points.items():
            D = pts.material.rock_stiffness().ravel()
            self.tangent.x.array.reshape(-1, nv * nv)[self._dofs(tag)] = D

    def set_in_situ(self, in_situ) -> None:
        """Start from the in-situ stress σ0 (rockjoint.fem.InSituStress): the sets pre-closed
        by σ0 at every quadrature point, ε0 the strain carrying it."""
        nv = self.nv
        for tag, pts in self.points.items():
            cells = self.cells[tag]
            if cells.size == 0:
                continue
            x = self._x_expr.eval(self.mesh, cells).reshape(-1, self.gdim)
            s0 = voigt_stress(in_situ.at(x, self.gdim))
            self.eps0[tag] = pts.initialise_from_stress(s0)
            self.sigma0.x.array.reshape(-1, nv)[self._dofs(tag)] = s0
            self.stress.x.array.reshape(-1, nv)[self._dofs(tag)] = s0
            self._committed[tag] = (s0.copy(), self.eps0[tag].copy())

    def update(self) -> bool:
        """Stress and tangent at the current displacement (trial state from the converged one);
        False if a local solve failed at some point of this rank."""
        nv, ok = self.nv, True
        for tag, pts in self.points.items():
            cells = self.cells[tag]
            if cells.size == 0:
                continue
            eps = self._strain_expr.eval(self.mesh, cells).reshape(-1, nv) + self.eps0[tag]
            stress, tangent, failed = pts.evaluate(eps)
            if self.relaxation is not None:
                r, (s_n, e_n) = self.relaxation, self._committed[tag]
                D = pts.material.rock_stiffness()
                stress = (s_n + (eps - e_n) @ D.T + r * stress) / (1.0 + r)
                tangent = (D.ravel()[None, :] + r * tangent) / (1.0 + r)
            self._current[tag] = (stress, eps)
            dofs = self._dofs(tag)
            self.stress.x.array.reshape(-1, nv)[dofs] = stress
            self.tangent.x.array.reshape(-1, nv * nv)[dofs] = tangent
            if failed:
                bad = np.flatnonzero(~np.isfinite(stress[:, 0]))
                #: (block tag, total strain) of a point whose local solve failed last (diagnostics)
                self.last_failure = (tag, eps[bad[0]].copy(), pts)
                log.debug("block %d: the local solve failed at %d point(s), e.g. ε = %s", tag, failed, eps[bad[0]])
            ok = ok and failed == 0
        return ok

    def add_residual(self, r: PETSc.Vec) -> bool:
        """r += F_c at the current displacement (collective); False (r untouched) if a local solve
        failed on any rank."""
        ok = self.mesh.comm.allreduce(self.update(), op=_and())
        if not ok:
            return False
        rc = self._rc
        with rc.localForm() as loc:
            loc.set(0.0)
        fem_petsc.assemble_vector(rc, self.residual_form)
        rc.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
        r.axpy(1.0, rc)
        return True

    def add_jacobian(self, A: PETSc.Mat, bcs: list) -> None:
        """A += J_c at the tangent of the last update, rows and columns of `bcs` left out (the
        diagonal there is K's)."""
        form = self.jacobian_form
        _cpp.fem.petsc.assemble_matrix(A, form._cpp_object, _cpp.fem.pack_constants(form._cpp_object),
                                       _cpp.fem.pack_coefficients(form._cpp_object),
                                       [bc._cpp_object for bc in bcs])

    def committed_stress(self, tag) -> np.ndarray:
        """The converged stress (Voigt, tension positive) [Pa] at the quadrature points of the
        smeared block `tag` on this rank, (points, strain size)."""
        return np.asarray(self._committed[tag][0]).reshape(-1, self.nv)

    def point_state(self) -> tuple:
        """(state, {set label: tag}, {set label: JointBehaviour}) of the smeared sets at their
        converged state on this rank, shaped as JointInterface.state for law_range.summarize:
        per quadrature point and set, closure -j_n [m] of the converged jump, σ_n = -n·σ·n [Pa]
        of the converged stress (traction continuity: the set's own normal stress), shear
        traction ``|σ·n + σ_n n|`` [Pa] and the status of the set's law at that closure (no shear
        state). Set labels and tags are the same on every rank."""
        pairs = [(0, 0), (1, 1), (0, 1)] if self.gdim == 2 else [(0, 0), (1, 1), (2, 2), (1, 2), (0, 2), (0, 1)]
        labels, behaviours, parts = {}, {}, []
        for tag in sorted(self.points):
            pts = self.points[tag]
            voigt = self.committed_stress(tag)
            sigma = np.zeros((voigt.shape[0], self.gdim, self.gdim))
            for k, (a, b) in enumerate(pairs):
                sigma[:, a, b] = sigma[:, b, a] = voigt[:, k]
            for k, js in enumerate(pts.material.sets):
                labels.setdefault(js.label, len(labels))
                behaviours.setdefault(js.label, js.behaviour)
                n = np.asarray(js.normal[:self.gdim])
                t = sigma @ n
                sn = -(t @ n)
                closure = -np.asarray(pts.set_state(k)["jump"])[:, 0]
                status = js.behaviour.law.evaluate(closure)[3] if closure.size else np.zeros(0)
                parts.append((np.full(closure.size, labels[js.label]), closure, sn,
                              np.linalg.norm(t + sn[:, None] * n, axis=1), np.asarray(status, dtype=np.int32)))
        keys = ("tag", "closure", "normal_stress", "shear_traction", "status")
        state = {key: np.concatenate([p[i] for p in parts]) if parts else np.zeros(0) for i, key in enumerate(keys)}
        return state, labels, behaviours

    def set_summary(self) -> dict:
        """{set label: (largest closure [m], largest σ_n [Pa], slipping points)} of the smeared sets
        over all ranks (the same on every rank; collective), from point_state(): slipping where τ
        reaches (1 - 1e-6) of the set's own shear strength at max(σ_n, 0) (JointStrength of its
        behaviour; a set without a strength never slips)."""
        state, sets, behaviours = self.point_state()
        comm = self.mesh.comm
        out = {}
        for label, tag in sorted(sets.items()):
            at = state["tag"] == tag
            closure, sn, tau = state["closure"][at], state["normal_stress"][at], state["shear_traction"][at]
            strength = behaviours[label].strength
            slipping = 0
            if strength.model != StrengthModel.none and sn.size:
                cap = np.array([strength.shear_strength(float(v)) for v in np.maximum(sn, 0.0)])
                slipping = int(np.sum((cap > 0) & (tau >= (1.0 - 1e-6) * cap)))
            out[label] = (comm.allreduce(float(closure.max(initial=-np.inf)), op=MPI.MAX),
                          comm.allreduce(float(sn.max(initial=-np.inf)), op=MPI.MAX),
                          comm.allreduce(slipping, op=MPI.SUM))
        return out

    def reset_state(self) -> None:
        """Back to the virgin state (no in-situ stress, no slip, sets unloaded): a restarted model."""
        nv = self.nv
        self.relaxation = None
        self.sigma0.x.array[:] = 0.0
        self.stress.x.array[:] = 0.0
        for tag, pts in self.points.items():
            self.eps0[tag] = pts.initialise_from_stress(np.zeros((pts.num_points, nv)))
            self._committed[tag] = (np.zeros((pts.num_points, nv)), self.eps0[tag].copy())
        self._current = {}
        self._fill_elastic()

    def commit_state(self) -> None:
        """Accept the trial joint-set states of every smeared block (after a converged load step)."""
        for tag, pts in self.points.items():
            pts.commit()
            if tag in self._current:
                self._committed[tag] = self._current[tag]

    def revert_state(self) -> None:
        """Drop the trial joint-set states of every smeared block (after a failed load step)."""
        for pts in self.points.values():
            pts.revert()


def _and():
    return MPI.LAND
