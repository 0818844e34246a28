# SPDX-License-Identifier: MIT
"""Loads and supports of a JointedRockModel as handles that change between stages.

A handle's `.value` may be set and the handle removed (`remove()`) between stages; the change takes
effect at the next stage, whose load steps interpolate linearly from the previous stage's values to
the new ones. A load enters the external load vector through its UFL term; its value lives in a
DOLFINx coefficient (Constant or Function), so changing a value only re-assembles a vector, and
adding or removing a load only recompiles the load form.
"""
from __future__ import annotations

import numpy as np
import ufl
from dolfinx import fem

LOAD_KINDS = ("traction", "pressure", "body_force", "gravity", "excavation")


class Load:
    """One load of a model: kind, where (a boundary name or None for the volume) and value.

    value: traction [Pa] (vector, or a callable f(x) -> (gdim, n) for x of shape (3, n)), pressure
    [Pa] (scalar, t = -p n), body force [N/m³] (vector), gravity [m/s²] (vector g; the force is
    ρ g), excavation (fraction of the in-situ traction σ0·n still carried by the boundary: 1 before,
    0 after the excavation; intermediate values release part of it)."""

    def __init__(self, owner, kind: str, boundary: str | None, value):
        if kind not in LOAD_KINDS:
            raise ValueError(f"load kind {kind!r} unknown; kinds: {LOAD_KINDS}")
        self._owner = owner
        self.kind = kind
        self.boundary = boundary
        self._value = None
        self.coefficient = None  #: the DOLFINx Constant/Function carrying the value (set by the LoadPath that owns it)
        self.active = True
        self.value = value

    @property
    def value(self):
        """The load's value in SI (settable while the load is active; RuntimeError once removed)."""
        return self._value

    @value.setter
    def value(self, value) -> None:
        if not self.active:
            raise RuntimeError(f"this {self.kind} load was removed; add a new one instead")
        self._value = self._owner._check_load_value(self, value)
        if self.coefficient is not None:
            self._owner._set_load_coefficient(self)

    def remove(self) -> None:
        """Remove the load: it is ramped to zero over the next stage."""
        if self.active:
            self._owner._remove_load(self)
            self.active = False

    def __repr__(self) -> str:
        where = f" on {self.boundary!r}" if self.boundary else ""
        return f"Load({self.kind}{where}, value={self._value!r}{'' if self.active else ', removed'})"


class Support:
    """Prescribed displacement [m] of some components on a boundary (0: a fixed support).

    value: one value for every component, or one per component (in the order given to fix), or
    None: hold the dofs where they are when the support is added."""

    def __init__(self, owner, boundary: str, components: list, block_tag, value):
        self._owner = owner
        self.boundary = boundary
        self.components = components
        self.block_tag = block_tag
        self.active = True
        self._value = None
        self.value = value

    @property
    def value(self) -> np.ndarray:
        """The prescribed displacement [m] (settable while the support is active)."""
        return self._value

    @value.setter
    def value(self, value) -> None:
        if not self.active:
            raise RuntimeError(f"the support on {self.boundary!r} was removed; fix the boundary again instead")
        if value is None:
            self._value = None
            return
        v = np.asarray(value, dtype=float)
        if v.ndim == 0:
            v = np.full(len(self.components), float(v))
        if v.shape != (len(self.components),) or not np.all(np.isfinite(v)):
            raise ValueError(f"support value on {self.boundary!r} must be one finite number or "
                             f"{len(self.components)} (one per component), got {value!r}")
        self._value = v

    def remove(self) -> None:
        """Free the components (the bulk matrix is rebuilt at the next stage)."""
        if self.active:
            self._owner._remove_support(self)
            self.active = False

    def __repr__(self) -> str:
        value = None if self._value is None else self._value.tolist()
        return (f"Support({self.boundary!r}, components={self.components}, value={value}"
                f"{'' if self.active else ', removed'})")


def load_term(load: Load, v, ds, n, density):
    """The UFL term ∫ load · v of one load (its coefficient must exist)."""
    c = load.coefficient
    if load.kind == "traction":
        return ufl.inner(c, v) * ds
    if load.kind == "pressure":
        return -c * ufl.inner(n, v) * ds  # t = -p n, n the outward normal of the rock
    if load.kind == "body_force":
        return ufl.inner(c, v) * ufl.dx
    if load.kind == "gravity":
        return density * ufl.inner(c, v) * ufl.dx
    raise ValueError(f"load kind {load.kind!r} has no UFL term of its own")


def make_coefficient(load: Load, mesh, V):
    """A fresh DOLFINx coefficient for the load's value (a Function for callable tractions)."""
    if load.kind == "traction" and callable(load.value):
        return fem.Function(V, name=f"traction_{load.boundary}")
    if load.kind in ("pressure", "excavation"):
        return fem.Constant(mesh, 0.0)
    return fem.Constant(mesh, np.zeros(mesh.geometry.dim))


def set_coefficient(load: Load) -> None:
    """Copy the load's value into its coefficient."""
    c = load.coefficient
    if isinstance(c, fem.Function):
        gdim = c.function_space.mesh.geometry.dim
        fn = load.value

        def values(x):
            out = np.asarray(fn(x), dtype=float)
            if out.shape != (gdim, x.shape[1]):
                raise ValueError(f"traction function on {load.boundary!r} returned shape {out.shape}, "
                                 f"expected {(gdim, x.shape[1])}")
            return out

        c.interpolate(values)
        c.x.scatter_forward()
    else:
        c.value = load.value
