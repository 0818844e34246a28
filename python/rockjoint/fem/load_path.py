"""The loads, supports and load path of a JointedRockModel (a mixin of the model).

Loads and supports are handles (loads.py) whose changes take effect at the next stage. A stage
interpolates the external load vector linearly from the previous stage's, f_prev, to the one of the
loads set now, f_next: f(λ) = f_prev + λ (f_next - f_prev), and the supported dofs from their
displacement at the start of the stage to the supports' values. With an in-situ stress σ0 the
initial state carries σ0·n on every named boundary (but not on the components a support holds on
the whole boundary: the support carries them) and gravity, and the joints are pre-closed
(joint_initial_state.py), so that u = 0 is an equilibrium; the model checks it.
"""
from __future__ import annotations

import numpy as np
import ufl
from dolfinx import fem
from dolfinx.fem import petsc as fem_petsc
from mpi4py import MPI
from petsc4py import PETSc

from .distributed_mesh import lookup, names_of
from .in_situ import InSituStress
from .joint_initial_state import initial_jump
from .loads import Load, Support, load_term, make_coefficient, set_coefficient


class StagedLoading:
    """Loads, supports, in-situ stress and the stage interpolation of JointedRockModel."""

    def _gravity_vector(self, gravity) -> np.ndarray:
        if np.ndim(gravity) == 0:
            g = float(gravity)
            if not (np.isfinite(g) and g >= 0):
                raise ValueError(f"gravity = {gravity!r} m/s² is invalid; give g >= 0 or a vector")
            out = np.zeros(self.gdim)
            out[-1] = -g  # along -y (2D) / -z (3D)
            return out
        return self._vector(gravity, "gravity")

    def _check_load_value(self, load: Load, value):
        if load.kind == "traction" and callable(value):
            return value
        if load.kind in ("traction", "body_force", "gravity"):
            return self._vector(value, load.kind.replace("_", " "))
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

    # ---- loads and supports (handles; changes take effect at the next stage) --------------
    def fix(self, boundary: str, components="all", block: str | None = None, value=0.0) -> Support:
        """Prescribed displacement `value` [m] (0: a fixed support) of `components` ("x", "y",
        "z", indices or "all") on a named boundary; one value or one per component. With `block`,
        only on the part of the boundary that belongs to that block (e.g. a roller under one block
        while the block above it, held by a joint, may slide). A non-zero or changed value is
        ramped over the next stage from the displacement the dofs have then; value=None holds
        the dofs where they are (a support installed in a later stage)."""
        lookup(self.dmesh, "boundaries", boundary)
        block_tag = None if block is None else lookup(self.dmesh, "blocks", block)
        support = Support(self, boundary, self._component_indices(components), block_tag, value)
        self._supports.append(support)
        self._supports_dirty = True
        return support

    def add_traction(self, boundary: str, traction) -> Load:
        """Surface traction [Pa] on a named boundary: a vector, or a callable f(x) -> (gdim, n)
        of the coordinates x (3, n) (interpolated in the displacement space)."""
        return self._add_load("traction", boundary, traction)

    def add_pressure(self, boundary: str, pressure: float) -> Load:
        """Normal pressure p [Pa] on a named boundary (curved ones too): traction t = -p n, n the
        outward normal of the rock; p > 0 pushes on the surface."""
        return self._add_load("pressure", boundary, pressure)

    def add_body_force(self, force) -> Load:
        """Body force per unit volume [N/m³] in every block."""
        return self._add_load("body_force", None, force)

    def excavate(self, boundary: str, fraction_left: float = 0.0) -> Load:
        """Excavation of an opening meshed as a hole: the in-situ traction σ0·n that `boundary`
        carries in the initial state is ramped to `fraction_left` of itself (default 0) over the
        next stage. The handle's value is that fraction; remove() puts the traction back."""
        lookup(self.dmesh, "boundaries", boundary)
        if self.in_situ is None:
            raise RuntimeError(f"excavate({boundary!r}) releases the in-situ traction: set_in_situ_stress first")
        if boundary in self._release:
            self._release[boundary].value = fraction_left
            return self._release[boundary]
        load = Load(self, "excavation", boundary, fraction_left)
        load.coefficient = self._multiplier(boundary)
        set_coefficient(load)
        self._release[boundary] = load
        return load

    def set_in_situ_stress(self, in_situ: InSituStress, equilibrium_tolerance: float = 1e-8) -> None:
        """The initial stress σ0 (before the first stage): the bulk stress, the tractions σ0·n on
        every named boundary (carried by the supports on supported components), gravity, and
        joints pre-closed to their law's closure at the initial normal stress make an equilibrium
        state with u = 0; ValueError if σ0 and the model's gravity disagree, or (at the first
        solve) if the initial residual exceeds equilibrium_tolerance × the in-situ forces. A field
        that P1/P2 cannot balance exactly (a non-linear from_function field, a gradient along joints
        with P2 in 3D) needs a larger tolerance; the first stage then moves u by the imbalance."""
        if not (np.isfinite(equilibrium_tolerance) and equilibrium_tolerance > 0):
            raise ValueError(f"equilibrium_tolerance = {equilibrium_tolerance!r} is invalid; it must be > 0")
        if self.stages:
            raise RuntimeError("set_in_situ_stress: the in-situ stress is the initial state; set it before "
                               "the first solve()")
        if not isinstance(in_situ, InSituStress):
            raise ValueError(f"set_in_situ_stress takes an InSituStress (uniform, depth_dependent, "
                             f"from_function), got {type(in_situ).__name__}")
        in_situ.check_dimension(self.gdim)
        gravity = self.gravity.value if self.gravity is not None and self.gravity.active else None
        in_situ.check_gravity(self.densities if gravity is not None else {}, gravity)
        self.in_situ = in_situ
        self._equilibrium_tolerance = float(equilibrium_tolerance)
        self._initialised = False
        self._forms_dirty = True

    def _add_load(self, kind: str, boundary: str | None, value) -> Load:
        if boundary is not None:
            lookup(self.dmesh, "boundaries", boundary)
        load = Load(self, kind, boundary, value)
        self._loads.append(load)
        self._forms_dirty = True
        return load

    def _set_load_coefficient(self, load: Load) -> None:
        as_function = isinstance(load.coefficient, fem.Function)
        if load.kind == "traction" and callable(load.value) != as_function:
            load.coefficient = None  # a constant became a field or back: recompile the load form
            self._forms_dirty = True
        else:
            set_coefficient(load)

    def _remove_load(self, load: Load) -> None:
        if load.kind == "excavation":
            load.coefficient.value = 1.0
            del self._release[load.boundary]
            return
        self._loads.remove(load)
        self._forms_dirty = True

    def _remove_support(self, support: Support) -> None:
        self._supports.remove(support)
        self._supports_dirty = True

    def _multiplier(self, boundary: str):
        """The fraction of σ0·n carried by `boundary` (a Constant, 1 until excavated)."""
        if boundary not in self._multipliers:
            self._multipliers[boundary] = fem.Constant(self.mesh, 1.0)
        return self._multipliers[boundary]

    def _collect_prescribed(self) -> None:
        """Prescribed displacement per constrained local dof (the last support given wins; a
        support without a value holds the current displacement)."""
        g = np.zeros(self._n_local)
        for s in self._supports:
            for k, _, idx, _ in self._support_dofs[id(s)]:
                g[idx] = self.u.x.array[idx] if s.value is None else s.value[k]
        self._prescribed = g

    def _compile_forms(self) -> None:
        """The external load form of the active loads (+ the in-situ forms)."""
        mesh, v, ds, n = self.mesh, self._v, self._ds, self._normal
        L = ufl.inner(fem.Constant(mesh, np.zeros(self.gdim)), v) * ufl.dx
        for load in self._loads:
            if load.coefficient is None:
                load.coefficient = make_coefficient(load, mesh, self.V)
                set_coefficient(load)
            where = ds(lookup(self.dmesh, "boundaries", load.boundary)) if load.boundary else None
            L += load_term(load, v, where, n, self._rho)
        self._L_user = fem.form(L)
        if self.in_situ is not None and self._in_situ_compiled is not self.in_situ:
            sigma0 = self.in_situ.expression(mesh, self.degree)
            self._sigma0 = sigma0
            if self._r_sigma0 is not None:
                self._r_sigma0.destroy()
            self._r_sigma0 = self._assemble(fem.form(ufl.inner(sigma0, self.eps(v)) * ufl.dx))
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
        self._forms_dirty = False

    def _assemble(self, form) -> PETSc.Vec:
        b = fem_petsc.assemble_vector(form)
        b.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
        return b

    def _external(self, initial: bool = False) -> PETSc.Vec:
        """The external load vector of the loads set now; initial=True: that of the initial state
        (with an in-situ stress: σ0·n on every boundary and gravity; else zero)."""
        if initial and self.in_situ is None:
            f = self.r.duplicate()
            f.set(0.0)
            return f
        if self.in_situ is None:
            return self._assemble(self._L_user)
        for name, mask in self._applied_components.items():
            mask.value = 1.0
        for s in self._supports:
            if s.block_tag is None:
                mask = self._applied_components[s.boundary]
                values = np.array(mask.value, dtype=float)
                values[s.components] = 0.0
                mask.value = values
        fractions = {b: c.value.copy() for b, c in self._multipliers.items()}
        if initial:
            for c in self._multipliers.values():
                c.value = 1.0
            gravity = self.gravity is not None and self.gravity.active
            f = self._assemble(fem.form(load_term(self.gravity, self._v, None, None, self._rho))) \
                if gravity else None
        else:
            f = self._assemble(self._L_user)
        in_situ = self._assemble(self._L_in_situ)
        for b, value in fractions.items():
            self._multipliers[b].value = value
        if f is None:
            return in_situ
        f.axpy(1.0, in_situ)
        in_situ.destroy()
        return f

    def _initial_state(self) -> None:
        """u = 0 and the loads of the initial state; with an in-situ stress, joints pre-closed and
        the equilibrium checked."""
        self.u.x.array[:] = 0.0
        self._state = self._external(initial=True)
        self._initialised = True
        if self.in_situ is None:
            return
        self._pre_close_joints()
        self._begin_stage(next_loads=self._state)
        rnorm = self.residual()
        scale = self.load_norm(0.0)
        tolerance = self._equilibrium_tolerance
        if not rnorm <= tolerance * scale:
            raise ValueError(
                f"the in-situ stress is not in equilibrium with the model's loads: the initial residual is "
                f"{rnorm:.3e} N, {rnorm / max(scale, 1e-300):.2e} of the in-situ forces (allowed "
                f"{tolerance:g}). A uniform σ0 needs no gravity (density=None); a depth-dependent one needs "
                f"gravity with the same density; a field must satisfy div σ0 + ρ g = 0 (a discretisation "
                f"imbalance of a non-linear field: raise set_in_situ_stress(..., equilibrium_tolerance=))")

    def _pre_close_joints(self) -> None:
        """Joints carry the in-situ traction at u = 0: initial jump j0 = (-Δ0, τ0/k_s) with
        Δ0 = law.closure_at_stress(σ_n0), σ_n0 = -n·σ0·n (compression positive), τ0 = t·σ0·n."""
        vertex_rule = self.quadrature == "nodal" and self.degree == 1
        self.coupling.set_initial_jump(initial_jump(self.coupling.interface, self.in_situ, self.behaviours,
                                                    self.gdim, names_of(self.dmesh, "joints"), vertex_rule))

    # ---- stages ------------------------------------------------------------------------------
    def _begin_stage(self, next_loads: PETSc.Vec | None = None) -> None:
        """Load factor 0 of a stage: loads f_prev (the last stage's) → f_next (set now), prescribed
        displacements from the constrained dofs' current values to the supports' values."""
        self._next = self._external() if next_loads is None else next_loads
        self._f_prev = self._state.copy()
        self._df = self._next.copy()
        self._df.axpy(-1.0, self._f_prev)
        cidx = self._constrained_local
        self._g_prev = self.u.x.array[cidx].copy()
        self._g_delta = self._prescribed[cidx] - self._g_prev
        moved = bool(np.any(self._g_prev != 0.0) or np.any(self._g_delta != 0.0))
        self._any_prescribed = self.comm.allreduce(moved, op=MPI.MAX)
        self.load_factor = 0.0
        self._applied = None
        self._step_iterations = 0

    def _end_stage(self, reached: float) -> None:
        """The external loads of load factor `reached` become the state the next stage starts from."""
        state = self._state.copy()
        state.scale(1.0 - reached)
        state.axpy(reached, self._next)
        self._state = state

    def _apply_load_factor(self) -> None:
        """Loads and prescribed displacements of the current load factor (once per factor)."""
        lam = self.load_factor
        if self._applied == lam:
            return
        self._f_prev.copy(self._f_lambda)
        self._f_lambda.axpy(lam, self._df)
        cidx = self._constrained_local
        self.u.x.array[cidx] = self._g_prev + lam * self._g_delta
        if self._any_prescribed:
            # K has zero columns at supported dofs: their prescribed values act through K_fc u_c.
            w = self._w.x.array
            w[:] = 0.0
            w[cidx] = self.u.x.array[cidx]
            with self._lift.localForm() as loc:
                loc.set(0.0)
            fem_petsc.assemble_vector(self._lift, self._internal_form)
            self._lift.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
        self._applied = lam

    def _reactions(self) -> dict:
        """{(boundary, component): force the support exerts on the rock}: internal force minus
        external load at the support's constrained dofs, summed over its owned dofs and ranks."""
        self._apply_load_factor()
        self._w.x.array[:] = self.u.x.array
        force = self._assemble(self._internal_form)
        if self._r_sigma0 is not None:
            force.axpy(1.0, self._r_sigma0)
        self._joint_forces()
        force.axpy(1.0, self._r_joint)
        force.axpy(-1.0, self._f_lambda)
        values = force.array_r
        out = {}
        for s in self._supports:
            for _, c, _, owned in self._support_dofs[id(s)]:
                key = (s.boundary, "xyz"[c])
                out[key] = out.get(key, 0.0) + float(values[owned].sum())
        force.destroy()
        keys = sorted(out)
        totals = self.comm.allreduce(np.array([out[k] for k in keys]))
        return dict(zip(keys, (float(t) for t in totals)))
