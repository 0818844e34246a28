# SPDX-License-Identifier: MIT
"""The loads, supports and load path of a jointed rock model (docs/staged-analysis.md).

Loads and supports are handles (loads.py) whose changes take effect at the next stage. A stage
interpolates the external load vector linearly from the previous stage's, f_prev, to the one of the
loads set now, f_next: f(λ) = f_prev + λ (f_next - f_prev), and the supported dofs from their
displacement at the start of the stage to the supports' values. With an in-situ stress σ0 the
initial state carries σ0·n on every named boundary (but not on the components a support holds on
the whole boundary: the support carries them) and gravity; JointedRockModel pre-closes the joints
(joint_initial_state.py) so that u = 0 is an equilibrium, and checks it.

`LoadPath` works on the blocks' space and forms (elastic_blocks.ElasticBlocks) and the named
groups of the mesh only: it knows nothing of joints or solvers. It owns where the model stands on
its path (`StageState`): the one record of it the model reads and changes.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import ufl
from dolfinx import fem
from dolfinx.fem import petsc as fem_petsc
from mpi4py import MPI
from petsc4py import PETSc

from ..compat import la_petsc
from ..mesh.distributed_mesh import lookup, names_of
from .in_situ import InSituStress
from .loads import Load, Support, load_term, make_coefficient, set_coefficient

_COMPONENTS = {"x": 0, "y": 1, "z": 2}


@dataclass
class StageState:
    """Where a model stands on its load path, in one place (LoadPath.stage)."""

    #: the initial state (in-situ loads, joint pre-closure) is set; a new in-situ stress or a
    #: restarted solve clears it
    initial_state_set: bool = False
    #: a stage has begun since the model was set up (model.problem() begins one only before that)
    begun: bool = False
    #: a stage opened by advance() is in progress (the next solve() ends it at the factor reached)
    advancing: bool = False
    #: "k/n" while run() drives the stages (the progress log's stage label), else None
    label: str | None = None


class LoadPath:
    """Loads, supports, in-situ stress and the stage interpolation f(λ) on `blocks`.

    dmesh: the DistributedJointMesh (named boundaries and blocks); blocks: ElasticBlocks;
    densities: {block name: ρ} (gravity acts only with densities). The model asks it for what
    changed (refresh), the external part of the residual (apply, add_external), the internal force
    and the reactions; it reads gravity (the gravity load handle or None), in_situ and sigma0.
    """

    def __init__(self, dmesh, blocks, densities: dict, gravity):
        self.dmesh, self.blocks = dmesh, blocks
        self.gdim = blocks.gdim
        self.densities = densities
        self.supports: list[Support] = []
        self.loads: list[Load] = []
        self.release: dict = {}      #: {boundary: excavation Load} of released in-situ tractions
        self.multipliers: dict = {}  #: {boundary: Constant fraction of σ0·n it carries}
        self.in_situ: InSituStress | None = None
        self.equilibrium_tolerance = 1e-8
        self._in_situ_compiled = None  # the InSituStress the in-situ forms were compiled for
        self._supports_changed = True  # since the last refresh()
        self._forms_changed = True
        self.gravity: Load | None = None
        if densities:
            self.gravity = self.add_load("gravity", None, self.gravity_vector(gravity))
        imap, bs = blocks.V.dofmap.index_map, blocks.V.dofmap.index_map_bs
        self._template = la_petsc.create_vector([(imap, bs)])
        self.f_lambda = self._template.duplicate()
        self.lift = self._template.duplicate()
        self.r_sigma0 = None  # ∫ε(v):σ0 dx (with an in-situ stress)
        self.sigma0 = None    #: the in-situ stress σ0 as a UFL expression (None without one)
        self.support_dofs: dict = {}
        self.constrained_local = np.zeros(0, dtype=np.int32)
        self.any_prescribed = False
        self.stage = StageState()  #: where the model stands on its path
        self.applied = None   # the load factor whose loads are in f_lambda and u
        self.state = None     # external loads the next stage starts from
        self._prescribed = np.zeros(blocks.num_local_dofs)  # per local dof (collect_prescribed)
        self._L_user = self._L_in_situ = None  # compiled load forms (compile_forms)
        self._applied_components: dict = {}    # {boundary: Constant mask of the σ0·n components}
        # the stage being solved (begin_stage): f_prev, f_next, their difference, and the
        # prescribed displacements at its start and their change over it
        self._f_prev = self._next = self._df = None
        self._g_prev = self._g_delta = np.zeros(0)

    # ---- checks ------------------------------------------------------------------------------
    def vector(self, value, what: str) -> np.ndarray:
        """`value` as a float array of gdim finite components; ValueError naming `what` otherwise."""
        v = np.asarray(value, dtype=float)
        if v.shape != (self.gdim,) or not np.all(np.isfinite(v)):
            raise ValueError(f"{what} must be {self.gdim} finite components, got {value!r}")
        return v

    def gravity_vector(self, gravity) -> np.ndarray:
        """Gravity as a gdim vector [m/s²]: g >= 0 acts along -y (2D) or -z (3D); a vector is checked."""
        if np.ndim(gravity) == 0:
            g = float(gravity)
            if not (np.isfinite(g) and g >= 0):
                raise ValueError(f"gravity = {gravity!r} m/s² is invalid; give g >= 0 or a vector")
            out = np.zeros(self.gdim)
            out[-1] = -g  # along -y (2D) / -z (3D)
            return out
        return self.vector(gravity, "gravity")

    def component_indices(self, components) -> list:
        """Indices of `components` ("all", None, "x", "y", "z", an index or a list of them).

        ValueError naming a component the model does not have.
        """
        if components in ("all", None):
            return list(range(self.gdim))
        if isinstance(components, (str, int)):
            components = [components]
        out = []
        for c in components:
            i = _COMPONENTS.get(c, c) if isinstance(c, str) else c
            if not isinstance(i, (int, np.integer)) or not 0 <= i < self.gdim:
                raise ValueError(f"support component {c!r} is invalid; use 'x', 'y'{', z' if self.gdim == 3 else ''}, "
                                 f"an index < {self.gdim} or 'all'")
            out.append(int(i))
        return out

    # ---- the handles' owner interface (loads.py) ---------------------------------------------
    def _check_load_value(self, load: Load, value):
        if load.kind == "traction" and callable(value):
            return value
        if load.kind in ("traction", "body_force", "gravity"):
            return self.vector(value, load.kind.replace("_", " "))
        try:
            v = float(value)
        except (TypeError, ValueError):
            raise ValueError(f"{load.kind} value must be a number, got {value!r}") from None
        if load.kind == "pressure" and not np.isfinite(v):
            raise ValueError(f"pressure on {load.boundary!r} must be finite, got {value!r} Pa")
        if load.kind == "excavation" and not 0.0 <= v <= 1.0:
            raise ValueError(f"excavation of {load.boundary!r}: the fraction of the in-situ traction left "
                             f"must be in [0, 1], got {value!r}")
        return v

    def _set_load_coefficient(self, load: Load) -> None:
        as_function = isinstance(load.coefficient, fem.Function)
        if load.kind == "traction" and callable(load.value) != as_function:
            load.coefficient = None  # a constant became a field or back: recompile the load form
            self._forms_changed = True
        else:
            set_coefficient(load)

    def _remove_load(self, load: Load) -> None:
        if load.kind == "excavation":
            load.coefficient.value = 1.0
            del self.release[load.boundary]
            return
        self.loads.remove(load)
        self._forms_changed = True

    def _remove_support(self, support: Support) -> None:
        self.supports.remove(support)
        self._supports_changed = True

    # ---- loads and supports (handles; changes take effect at the next stage) --------------
    def fix(self, boundary: str, components="all", block: str | None = None, value=0.0) -> Support:
        """See JointedRockModel.fix."""
        lookup(self.dmesh, "boundaries", boundary)
        block_tag = None if block is None else lookup(self.dmesh, "blocks", block)
        support = Support(self, boundary, self.component_indices(components), block_tag, value)
        self.supports.append(support)
        self._supports_changed = True
        return support

    def add_load(self, kind: str, boundary: str | None, value) -> Load:
        """Add a load of `kind` on `boundary` (None: a body load) with `value` in SI; returns it.

        ValueError naming an unknown boundary or a bad value.
        """
        if boundary is not None:
            lookup(self.dmesh, "boundaries", boundary)
        load = Load(self, kind, boundary, value)
        self.loads.append(load)
        self._forms_changed = True
        return load

    def excavate(self, boundary: str, fraction_left: float = 0.0) -> Load:
        """See JointedRockModel.excavate."""
        lookup(self.dmesh, "boundaries", boundary)
        if self.in_situ is None:
            raise RuntimeError(f"excavate({boundary!r}) releases the in-situ traction: set_in_situ_stress first")
        if boundary in self.release:
            self.release[boundary].value = fraction_left
            return self.release[boundary]
        load = Load(self, "excavation", boundary, fraction_left)
        load.coefficient = self._multiplier(boundary)
        set_coefficient(load)
        self.release[boundary] = load
        return load

    def set_in_situ_stress(self, in_situ: InSituStress, equilibrium_tolerance: float) -> None:
        """See JointedRockModel.set_in_situ_stress."""
        if not (np.isfinite(equilibrium_tolerance) and equilibrium_tolerance > 0):
            raise ValueError(f"equilibrium_tolerance = {equilibrium_tolerance!r} is invalid; it must be > 0")
        if not isinstance(in_situ, InSituStress):
            raise ValueError(f"set_in_situ_stress takes an InSituStress (uniform, depth_dependent, "
                             f"from_function), got {type(in_situ).__name__}")
        in_situ.check_dimension(self.gdim)
        gravity = self.gravity.value if self.gravity is not None and self.gravity.active else None
        in_situ.check_gravity(self.densities if gravity is not None else {}, gravity)
        self.in_situ = in_situ
        self.equilibrium_tolerance = float(equilibrium_tolerance)
        self._forms_changed = True
        self.stage.initial_state_set = False

    def _multiplier(self, boundary: str):
        """The fraction of σ0·n carried by `boundary` (a Constant, 1 until excavated)."""
        if boundary not in self.multipliers:
            self.multipliers[boundary] = fem.Constant(self.blocks.mesh, 1.0)
        return self.multipliers[boundary]

    def refresh(self, u: np.ndarray) -> tuple | None:
        """Bring the load path up to date with the handles changed since the last refresh: the
        supports' Dirichlet conditions, the load forms, the prescribed values (u: the current
        displacement, held by supports without a value). Returns dirichlet()'s (bcs, mask) when
        the supports changed (the bulk matrix must be assembled again with them), else None."""
        supports = self.dirichlet() if self._supports_changed else None
        if self._forms_changed:
            self.compile_forms()
        self.collect_prescribed(u)
        return supports

    # ---- supports → Dirichlet conditions -------------------------------------------------
    def dirichlet(self) -> tuple[list, np.ndarray]:
        """(DirichletBCs of every support, int8 mask of the constrained local dofs)."""
        V, fdim = self.blocks.V, self.blocks.mesh.topology.dim - 1
        f2c = self.blocks.mesh.topology.connectivity(fdim, fdim + 1)
        bcs, constrained = [], np.zeros(self.blocks.num_local_dofs, dtype=np.int8)
        self.support_dofs = {}
        for s in self.supports:
            facets = self.dmesh.boundary(s.boundary)
            if s.block_tag is not None:
                facets = np.array([f for f in facets if self.blocks.cell_tag[f2c.links(f)[0]] == s.block_tag],
                                  dtype=np.int32)
            entries = []
            for k, c in enumerate(s.components):
                Vc = V.sub(c)
                bc = fem.dirichletbc(PETSc.ScalarType(0), fem.locate_dofs_topological(Vc, fdim, facets), Vc)
                bcs.append(bc)
                idx, first_ghost = bc.dof_indices()
                constrained[idx] = 1
                entries.append((k, c, np.asarray(idx), np.asarray(idx[:first_ghost])))
            self.support_dofs[id(s)] = entries
        self.constrained_local = np.flatnonzero(constrained).astype(np.int32)
        self._supports_changed = False
        return bcs, constrained

    def collect_prescribed(self, u: np.ndarray) -> None:
        """Prescribed displacement per constrained local dof (the last support given wins; a
        support without a value holds the current displacement u)."""
        g = np.zeros(self.blocks.num_local_dofs)
        for s in self.supports:
            for k, _, idx, _ in self.support_dofs[id(s)]:
                g[idx] = u[idx] if s.value is None else s.value[k]
        self._prescribed = g

    # ---- load forms and vectors ------------------------------------------------------------
    def compile_forms(self) -> None:
        """The external load form of the active loads (+ the in-situ forms)."""
        b = self.blocks
        mesh, v, ds, n = b.mesh, b.v, b.ds, b.normal
        L = ufl.inner(fem.Constant(mesh, np.zeros(self.gdim)), v) * ufl.dx
        for load in self.loads:
            if load.coefficient is None:
                load.coefficient = make_coefficient(load, mesh, b.V)
                set_coefficient(load)
            where = ds(lookup(self.dmesh, "boundaries", load.boundary)) if load.boundary else None
            L += load_term(load, v, where, n, b.rho)
        self._L_user = fem.form(L)
        if self.in_situ is not None and self._in_situ_compiled is not self.in_situ:
            sigma0 = self.in_situ.expression(mesh, b.degree)
            self.sigma0 = sigma0
            if self.r_sigma0 is not None:
                self.r_sigma0.destroy()
            self.r_sigma0 = self.assemble(fem.form(ufl.inner(sigma0, b.eps(v)) * ufl.dx))
            # σ0·n on every named boundary, times the fraction it still carries (excavate()), left
            # out on the components a support holds on the whole boundary (the support carries
            # them: its reaction is then the whole force on the boundary).
            Lb = ufl.inner(fem.Constant(mesh, np.zeros(self.gdim)), v) * ufl.dx
            self._applied_components = {}
            for name, tag in names_of(self.dmesh, "boundaries").items():
                mask = fem.Constant(mesh, np.ones(self.gdim))
                self._applied_components[name] = mask
                t0 = ufl.elem_mult(mask, ufl.dot(sigma0, n))
                Lb += self._multiplier(name) * ufl.inner(t0, v) * ds(tag)
            self._L_in_situ = fem.form(Lb)
            self._in_situ_compiled = self.in_situ
        self._forms_changed = False

    @staticmethod
    def assemble(form) -> PETSc.Vec:
        """The assembled vector of the linear `form`, ghost contributions added to their owners."""
        b = fem_petsc.assemble_vector(form)
        b.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
        return b

    def external(self, initial: bool = False) -> PETSc.Vec:
        """The external load vector of the loads set now; initial=True: that of the initial state
        (with an in-situ stress: σ0·n on every boundary and gravity; else zero)."""
        if initial and self.in_situ is None:
            f = self._template.duplicate()
            f.set(0.0)
            return f
        if self.in_situ is None:
            return self.assemble(self._L_user)
        for mask in self._applied_components.values():
            mask.value = 1.0
        for s in self.supports:
            if s.block_tag is None:
                mask = self._applied_components[s.boundary]
                values = np.array(mask.value, dtype=float)
                values[s.components] = 0.0
                mask.value = values
        fractions = {b: c.value.copy() for b, c in self.multipliers.items()}
        if initial:
            for c in self.multipliers.values():
                c.value = 1.0
            gravity = self.gravity is not None and self.gravity.active
            f = self.assemble(fem.form(load_term(self.gravity, self.blocks.v, None, None, self.blocks.rho))) \
                if gravity else None
        else:
            f = self.assemble(self._L_user)
        in_situ = self.assemble(self._L_in_situ)
        for b, value in fractions.items():
            self.multipliers[b].value = value
        if f is None:
            return in_situ
        f.axpy(1.0, in_situ)
        in_situ.destroy()
        return f

    def start(self) -> None:
        """The initial state's loads become the state the first stage starts from."""
        self.state = self.external(initial=True)

    # ---- stages ------------------------------------------------------------------------------
    def begin_stage(self, u: np.ndarray, hold: bool = False) -> None:
        """Load factor 0 of a stage: loads f_prev (the last stage's) → f_next (set now; hold: the
        last stage's, as for the initial state's equilibrium check), prescribed displacements from
        the constrained dofs' current values in u to the supports' values."""
        self._next = self.state if hold else self.external()
        self._f_prev = self.state.copy()
        self._df = self._next.copy()
        self._df.axpy(-1.0, self._f_prev)
        cidx = self.constrained_local
        self._g_prev = u[cidx].copy()
        self._g_delta = self._prescribed[cidx] - self._g_prev
        moved = bool(np.any(self._g_prev != 0.0) or np.any(self._g_delta != 0.0))
        self.any_prescribed = self.blocks.mesh.comm.allreduce(moved, op=MPI.MAX)
        self.applied = None
        self.stage.begun = True

    def end_stage(self, reached: float) -> None:
        """The external loads of load factor `reached` become the state the next stage starts from
        (a stage advance() opened is closed)."""
        self.stage.advancing = False
        state = self.state.copy()
        state.scale(1.0 - reached)
        state.axpy(reached, self._next)
        self.state = state

    def apply(self, load_factor: float, u) -> None:
        """Loads f(λ) into f_lambda and the prescribed displacements of λ into u's constrained
        dofs (with their lift K_fc u_c); once per load factor."""
        if self.applied == load_factor:
            return
        self._f_prev.copy(self.f_lambda)
        self.f_lambda.axpy(load_factor, self._df)
        cidx = self.constrained_local
        u.x.array[cidx] = self._g_prev + load_factor * self._g_delta
        if self.any_prescribed:
            # K has zero columns at supported dofs: their prescribed values act through K_fc u_c.
            w = self.blocks.w.x.array
            w[:] = 0.0
            w[cidx] = u.x.array[cidx]
            with self.lift.localForm() as loc:
                loc.set(0.0)
            fem_petsc.assemble_vector(self.lift, self.blocks.internal_form)
            self.lift.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
        self.applied = load_factor

    def forget_applied(self) -> None:
        """u was set from outside (a step undone): apply() sets the prescribed values again."""
        self.applied = None

    def add_external(self, r: PETSc.Vec) -> None:
        """r += K_fc u_c (the prescribed displacements' lift) + ∫ε(v):σ0 dx - f(λ), at the load
        factor of the last apply()."""
        if self.any_prescribed:
            r.axpy(1.0, self.lift)
        if self.r_sigma0 is not None:
            r.axpy(1.0, self.r_sigma0)
        r.axpy(-1.0, self.f_lambda)

    def internal_force(self, u) -> PETSc.Vec:
        """The bulk internal force at u (+ ∫ε(v):σ0 dx), a new vector."""
        self.blocks.w.x.array[:] = u.x.array
        force = self.assemble(self.blocks.internal_form)
        if self.r_sigma0 is not None:
            force.axpy(1.0, self.r_sigma0)
        return force

    def check_initial_equilibrium(self, rnorm: float) -> None:
        """ValueError unless the residual norm of the initial state (u = 0, λ = 0) is within
        equilibrium_tolerance × the in-situ forces."""
        scale = self.load_norm(0.0)
        tolerance = self.equilibrium_tolerance
        if not rnorm <= tolerance * scale:
            raise ValueError(
                f"the in-situ stress is not in equilibrium with the model's loads: the initial residual is "
                f"{rnorm:.3e} N, {rnorm / max(scale, 1e-300):.2e} of the in-situ forces (allowed "
                f"{tolerance:g}). A uniform σ0 needs no gravity (density=None); a depth-dependent one needs "
                f"gravity with the same density; a field must satisfy div σ0 + ρ g = 0 (a discretisation "
                f"imbalance of a non-linear field: raise set_in_situ_stress(..., equilibrium_tolerance=))")

    def load_norm(self, load_factor: float) -> float:
        """Scale of the forces at `load_factor`: ||f(λ)|| (+ ||∫ε(v):σ0||)."""
        f = self._f_prev.copy()
        f.axpy(load_factor, self._df)
        out = f.norm()
        f.destroy()
        return out + (self.r_sigma0.norm() if self.r_sigma0 is not None else 0.0)

    def reactions(self, internal_force: PETSc.Vec) -> dict:
        """{(boundary, component): force the support exerts on the rock}: the internal force
        (bulk, in-situ and joints, at the current load factor) minus the external load at each
        support's constrained dofs, summed over its owned dofs and ranks."""
        internal_force.axpy(-1.0, self.f_lambda)
        values = internal_force.array_r
        out = {}
        for s in self.supports:
            for _, c, _, owned in self.support_dofs[id(s)]:
                key = (s.boundary, "xyz"[c])
                out[key] = out.get(key, 0.0) + float(values[owned].sum())
        keys = sorted(out)
        totals = self.blocks.mesh.comm.allreduce(np.array([out[k] for k in keys]))
        return dict(zip(keys, (float(t) for t in totals)))
