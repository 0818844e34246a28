# SPDX-License-Identifier: MIT
"""In-situ (initial) stress of a rock mass: uniform, depth-dependent, or a user field.

Tensors use the continuum convention (tension positive, like σ(u)): a compressive in-situ stress
has negative diagonal entries. The depth-dependent state is the lithostatic one,::

    σ_v = ρ g (z_surface - z),   σ_h = K0 σ_v          (compression magnitudes),

with z the vertical coordinate (2D: y; 3D: z). Each spec gives the tensor twice: as a UFL
expression for the bulk forms (exact for the uniform and depth-dependent states) and as numbers at
given points (for the joints' initial normal and shear stress).
"""
from __future__ import annotations

import math
from typing import Callable

import numpy as np
import ufl
from dolfinx import fem

from ...validation import positive_number

#: standard gravity [m/s²]
STANDARD_GRAVITY = 9.81


class InSituStress:
    """An in-situ stress field σ0 (build with uniform, depth_dependent or from_function)."""

    def __init__(self, kind: str, **data):
        self.kind = kind
        self.data = data

    # ---- constructors ----------------------------------------------------------------------
    @classmethod
    def uniform(cls, tensor) -> "InSituStress":
        """A uniform tensor σ0 [Pa] (gdim × gdim, symmetric, tension positive)."""
        t = np.asarray(tensor, dtype=float)
        if t.ndim != 2 or t.shape[0] != t.shape[1] or t.shape[0] not in (2, 3):
            raise ValueError(f"in-situ stress tensor must be 2x2 or 3x3, got shape {t.shape}")
        if not np.all(np.isfinite(t)):
            raise ValueError(f"in-situ stress tensor has non-finite entries: {t.tolist()}")
        if not np.allclose(t, t.T, rtol=1e-12, atol=1e-12 * max(np.abs(t).max(), 1.0)):
            raise ValueError(f"in-situ stress tensor must be symmetric, got {t.tolist()}")
        return cls("uniform", tensor=t)

    @classmethod
    def depth_dependent(cls, surface: float, density: float, k0=1.0,
                        gravity: float = STANDARD_GRAVITY) -> "InSituStress":
        """Lithostatic stress: σ_v = ρ g (surface - z) [Pa, compression], σ_h = K0 σ_v.

        :surface: vertical coordinate of the ground surface [m] (the model lies below it).
        :density: ρ [kg/m³] (must equal the model's rock density: the state is then in equilibrium
            with gravity). k0: horizontal-to-vertical stress ratio, a float, or in 3D (K0_x, K0_y).
        :gravity: g [m/s²]."""
        try:
            surface = float(surface)
        except (TypeError, ValueError):
            raise ValueError(f"surface must be a number (vertical coordinate [m]), got {surface!r}") from None
        if not math.isfinite(surface):
            raise ValueError(f"surface = {surface!r} is invalid; it must be finite")
        density = positive_number("density", density, unit="kg/m³")
        gravity = positive_number("gravity", gravity, unit="m/s²")
        k0s = np.atleast_1d(np.asarray(k0, dtype=float))
        if k0s.ndim != 1 or k0s.size not in (1, 2) or not np.all(np.isfinite(k0s)) or np.any(k0s < 0):
            raise ValueError(f"k0 = {k0!r} is invalid; give a finite K0 >= 0, or (K0_x, K0_y) in 3D")
        return cls("depth", surface=surface, density=density, k0=k0s, gravity=gravity)

    @classmethod
    def from_function(cls, function: Callable) -> "InSituStress":
        """A user field: function(x) with x of shape (3, n) returns (gdim, gdim, n) tensors [Pa]
        (tension positive); interpolated into a continuous tensor space of the element degree."""
        if not callable(function):
            raise ValueError(f"from_function needs a callable f(x) -> (gdim, gdim, n), got {function!r}")
        return cls("function", function=function)

    # ---- evaluation ------------------------------------------------------------------------
    def _k0(self, gdim: int) -> np.ndarray:
        k0 = self.data["k0"]
        if gdim == 2 and k0.size != 1:
            raise ValueError(f"k0 = {k0.tolist()}: give one K0 in 2D")
        return np.resize(k0, gdim - 1)

    def check_dimension(self, gdim: int) -> None:
        """Check the stress fits a `gdim`-dimensional model; ValueError naming the mismatch."""
        if self.kind == "uniform" and self.data["tensor"].shape != (gdim, gdim):
            raise ValueError(f"in-situ stress tensor is {self.data['tensor'].shape}, the model is {gdim}D")
        if self.kind == "depth":
            self._k0(gdim)

    def at(self, points: np.ndarray, gdim: int) -> np.ndarray:
        """σ0 at points (n, k >= gdim coordinates) as an (n, gdim, gdim) array [Pa]."""
        x = np.atleast_2d(np.asarray(points, dtype=float))
        n = x.shape[0]
        if self.kind == "uniform":
            return np.broadcast_to(self.data["tensor"], (n, gdim, gdim)).copy()
        if self.kind == "depth":
            d = self.data
            sv = d["density"] * d["gravity"] * (d["surface"] - x[:, gdim - 1])
            out = np.zeros((n, gdim, gdim))
            for i, k in enumerate(self._k0(gdim)):
                out[:, i, i] = -k * sv
            out[:, gdim - 1, gdim - 1] = -sv
            return out
        x3 = np.zeros((3, n))
        x3[: x.shape[1]] = x.T
        values = np.asarray(self.data["function"](x3), dtype=float)
        if values.shape != (gdim, gdim, n):
            raise ValueError(f"in-situ stress function returned shape {values.shape}, expected {(gdim, gdim, n)}")
        return np.moveaxis(values, 2, 0)

    def expression(self, mesh, degree: int):
        """σ0 as a UFL tensor on `mesh` (a Constant, an exact linear expression, or an interpolant
        in a continuous tensor space of `degree`)."""
        gdim = mesh.geometry.dim
        self.check_dimension(gdim)
        if self.kind == "uniform":
            return fem.Constant(mesh, self.data["tensor"])
        if self.kind == "depth":
            d = self.data
            x = ufl.SpatialCoordinate(mesh)
            sv = d["density"] * d["gravity"] * (d["surface"] - x[gdim - 1])
            k0 = list(self._k0(gdim)) + [1.0]
            return -sv * ufl.as_matrix([[k0[i] if i == j else 0.0 for j in range(gdim)] for i in range(gdim)])
        T = fem.functionspace(mesh, ("Lagrange", degree, (mesh.geometry.dim, mesh.geometry.dim)))
        sigma0 = fem.Function(T, name="in_situ_stress")
        fn = self.data["function"]

        def flat(x):
            values = np.asarray(fn(x), dtype=float)
            if values.shape != (gdim, gdim, x.shape[1]):
                raise ValueError(f"in-situ stress function returned shape {values.shape}, "
                                 f"expected {(gdim, gdim, x.shape[1])}")
            return values.reshape(gdim * gdim, -1)

        sigma0.interpolate(flat)
        return sigma0

    def check_gravity(self, densities: dict, gravity_vector) -> None:
        """A depth-dependent state is in equilibrium only with gravity ρ g along -vertical in every
        block: raise ValueError naming the disagreement. densities: {block name: ρ} (empty without
        gravity)."""
        if self.kind != "depth":
            return
        d = self.data
        if not densities or gravity_vector is None:
            raise ValueError(f"a depth-dependent in-situ stress (gradient ρ g = "
                             f"{d['density'] * d['gravity']:.6g} Pa/m) needs gravity in the model: "
                             f"give JointedRockModel(..., density={d['density']:g})")
        g = np.asarray(gravity_vector, dtype=float)
        expected = np.zeros_like(g)
        expected[-1] = -d["gravity"]
        if not np.allclose(g, expected, rtol=1e-12, atol=1e-12 * d["gravity"]):
            raise ValueError(f"in-situ stress gradient assumes gravity {expected.tolist()} m/s², the model's "
                             f"gravity is {g.tolist()} m/s²")
        for block, rho in densities.items():
            if not math.isclose(rho, d["density"], rel_tol=1e-12):
                raise ValueError(f"in-situ stress gradient ρ g uses density {d['density']:g} kg/m³ but block "
                                 f"{block!r} has density {rho:g} kg/m³: the initial state would not be in "
                                 f"equilibrium with gravity")
