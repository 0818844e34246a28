# SPDX-License-Identifier: MIT
"""The flow through one aperture field (docs/flow.md, "Flow through the gap field"): the effective
transmissivity and hydraulic apertures of a joint's gap field under load.

:func:`transmissivity` solves the Reynolds (local cubic law) equation ∇·(e³/12 ∇p) = 0 on an
aperture field (the gap field of the contact solution under load: ``contact.closure_curve(...,
flow=True)`` does it at every load) under a unit mean pressure gradient along x and along y, and
returns the effective transmissivity tensor T and the hydraulic apertures e_h = (12 T)^(1/3).
Convention: mean flux per unit width q̄ = -(T/μ) ∇p̄, so T [m³] is e³/12 for parallel plates.
rockjoint.flow re-exports all of it beside the transmissivity laws T(Δ).

SI units: m, m³.
"""
from __future__ import annotations

import dataclasses
import logging
from typing import Tuple, Union

import numpy as np

from ._rockjoint import flow as _cpp
from ._rockjoint.topography import Surface

log = logging.getLogger(__name__)

Boundary = _cpp.Boundary
LinearSolver = _cpp.LinearSolver
#: the pressure solver unless one is named: sparse LDLᵀ (bench/results/flow.md measured it against
#: conjugate gradients with incomplete Cholesky on the 512² bench joint)
DEFAULT_SOLVER = "cholesky"


def hydraulic_aperture(transmissivity) -> Union[float, np.ndarray]:
    """e_h = (12 T)^(1/3) [m] of a transmissivity T [m³] (parallel plates: their spacing). A
    negative or non-finite T is not a transmissivity (a pressure system that was not solved):
    ValueError, never a negative aperture."""
    t = np.asarray(transmissivity, dtype=float)
    if not np.all(np.isfinite(t) & (t >= 0)):
        bad = float(t[~(np.isfinite(t) & (t >= 0))].ravel()[0])
        raise ValueError(f"hydraulic_aperture: transmissivity {bad:g} m³ is not finite and >= 0")
    return np.cbrt(12.0 * t)


@dataclasses.dataclass(frozen=True)
class Transmissivity:
    """The flow answer for one aperture field (SI)."""

    tensor: np.ndarray           # T [m³], 2 x 2: q̄ = -(T/μ) ∇p̄ (x, y)
    mechanical_aperture: float   # mean aperture over the scanned points, contact spots as 0 [m]
    open_fraction: float         # scanned points with e > 0 [-] (a contact gap: 1 - A/A0)
    percolates: Tuple[bool, bool]  # an open path carries flow along x, y (docs/flow.md)
    iterations: Tuple[int, int]  # CG iterations per gradient (0: direct solver)
    relative_residual: float     # largest |A p - b|/|b| of the pressure systems
    periodic: bool
    #: conjugate_gradient only: CG stalled (near percolation) and the supernodal factorisation
    #: solved the system instead (`iterations`: CG's before it gave up)
    direct_fallback: bool = False

    @property
    def mean(self) -> float:
        """The mean of the principal transmissivities, (T_xx + T_yy)/2 [m³]."""
        return 0.5 * float(self.tensor[0, 0] + self.tensor[1, 1])

    @property
    def principal(self) -> np.ndarray:
        """Principal transmissivities [m³], largest first, of the symmetric part of T (periodic: T
        is symmetric; sealed sides: its off-diagonal terms are not, docs/flow.md)."""
        return np.linalg.eigvalsh(0.5 * (self.tensor + self.tensor.T))[::-1]

    @property
    def hydraulic_aperture(self) -> float:
        """e_h of the mean transmissivity [m]."""
        return float(hydraulic_aperture(self.mean))

    @property
    def principal_hydraulic_apertures(self) -> np.ndarray:
        """e_h [m] along the principal directions, largest first."""
        return hydraulic_aperture(np.maximum(self.principal, 0.0))


class ApertureFlow:
    """The flow problem of one grid: `shape` (rows along y, cols along x), `spacing` h or (h_x, h_y)
    [m], `periodic` (one period of a periodic joint, the periodic BEM kernel) or not (an isolated
    scan: fixed pressures on the faces normal to the gradient, sealed sides parallel to it),
    `solver` "cholesky" (supernodal, CHOLMOD), "simplicial_cholesky" (Eigen's LDLᵀ) or
    "conjugate_gradient" (incomplete-Cholesky CG to `tolerance`; where it stalls, near percolation,
    the supernodal factorisation solves the system instead, said in the result and once in the
    log of this module). Its symbolic factorisation is
    made once and serves every field (the loads of a closure curve). Call it on an aperture field
    [m] (NaN = masked, not scanned, impermeable; 0 = closed, a contact spot): a Transmissivity.
    Raises ValueError for bad input (naming it), RuntimeError if a pressure system was not
    solved."""

    def __init__(self, shape: Tuple[int, int], spacing: Union[float, Tuple[float, float]], *,
                 periodic: bool = True, solver: str = DEFAULT_SOLVER, tolerance: float = 1e-10,
                 maximum_iterations: int = 10000):
        hx, hy = (spacing, spacing) if np.isscalar(spacing) else tuple(spacing)
        if solver not in LinearSolver.__members__:
            raise ValueError(f"transmissivity: solver {solver!r}; expected one of "
                             f"{', '.join(LinearSolver.__members__)}")
        rows, cols = (int(x) for x in shape)
        if rows < 2 or cols < 2:
            raise ValueError(f"transmissivity: the aperture grid is {rows} x {cols}; it needs at "
                             "least 2 rows and 2 columns")
        self.periodic, self.solver, self.tolerance = periodic, solver, tolerance
        self._fallback_said = False
        self._cpp = _cpp.ReynoldsFlow(rows, cols, float(hx), float(hy),
                                      Boundary.periodic if periodic else Boundary.sealed_sides,
                                      LinearSolver.__members__[solver], float(tolerance),
                                      int(maximum_iterations))

    def __call__(self, aperture) -> Transmissivity:
        r = self._cpp.transmissivity(np.asarray(aperture, dtype=float))
        if not r.converged:
            raise RuntimeError(f"transmissivity: the pressure system was not solved to the "
                               f"tolerance ({self.solver}: relative residual "
                               f"{r.relative_residual:.2e}, tolerance {self.tolerance:g}, "
                               f"iterations {tuple(r.iterations)})")
        if r.direct_fallback and not self._fallback_said:
            self._fallback_said = True
            log.warning("transmissivity: conjugate_gradient did not reach %g in %s iterations (a field "
                        "near percolation: conductances over many decades); solved by the supernodal "
                        "factorisation instead (Transmissivity.direct_fallback)", self.tolerance,
                        max(r.iterations))
        return Transmissivity(tensor=np.array(r.transmissivity),
                              mechanical_aperture=r.mechanical_aperture,
                              open_fraction=r.open_fraction, percolates=tuple(r.percolates),
                              iterations=tuple(r.iterations),
                              relative_residual=r.relative_residual, periodic=self.periodic,
                              direct_fallback=r.direct_fallback)


def transmissivity(gap_field, spacing: Union[None, float, Tuple[float, float]] = None, *,
                   periodic: bool = True, solver: str = DEFAULT_SOLVER, tolerance: float = 1e-10,
                   maximum_iterations: int = 10000) -> Transmissivity:
    """Transmissivity of one aperture field [m]: a 2-D array with `spacing` h or (h_x, h_y) [m],
    or a topography.Surface (its own spacing); the rest as ApertureFlow."""
    if isinstance(gap_field, Surface):
        if spacing is not None:
            raise ValueError("transmissivity: a Surface carries its own spacing; give no spacing")
        spacing = (gap_field.spacing_x, gap_field.spacing_y)
        field = gap_field.heights
    else:
        if spacing is None:
            raise ValueError("transmissivity: give the grid spacing [m] of the aperture array")
        field = np.asarray(gap_field, dtype=float)
        if field.ndim != 2:
            raise ValueError(f"transmissivity: the aperture field must be 2-D (rows, cols); got "
                             f"shape {field.shape}")
    return ApertureFlow(field.shape, spacing, periodic=periodic, solver=solver,
                        tolerance=tolerance, maximum_iterations=maximum_iterations)(field)
